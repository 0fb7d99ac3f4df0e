// Hooks for the end-to-end tests (tests/e2e), set by test-hooks.ts: the one test interface.

interface GeoshiftTestHooks {
  /** Resolves once the startup sample has been loaded (or failed to) and drawn. */
  ready: Promise<void>;
  /** The model on screen, or null if none could be shown. */
  stats(): { vertices: number; triangles: number; file: string } | null;
  /** Resolves when no file is loading, no filter is running, and the latest change has been drawn. */
  settled(): Promise<void>;
  /** What the worker runs: { threaded, threads, ops }; rejects when it cannot start. */
  workerReady(): Promise<{ threaded: boolean; threads: number; ops: string[] }>;
  /** Sets a parameter of the current preset, as if chosen in the panel (choices by value). */
  setParam(key: string, value: unknown): void;
  /** Resolves when no filter is running. */
  idle(): Promise<void>;
  /** The report of the last successful run (time, vertices, iterations, error), or null. */
  lastRun(): unknown;
  /** The plain-words message of the last failed or cancelled run, or null. */
  lastError(): string | null;
  /** Progress events of the current or last run; `at` is performance.now() on arrival. */
  progressEvents(): Array<{ fraction: number; stage: string; stageFraction: number | null; at: number }>;
  /** Positions of every mesh on screen, as plain arrays. */
  positions(): number[][];
  /** A scalar attribute of every mesh (null where a mesh lacks it), as plain arrays. */
  scalar(name: string): Array<number[] | null>;
  /** The bytes Export would download, base64-encoded. */
  exportGlb(): Promise<string>;
  /** Vertex colors (linear RGB rows) of every mesh on screen (null where a mesh has none). */
  colors(): Array<number[] | null>;
  /** Triangle vertex indices of every mesh on screen (null for a non-indexed one). */
  indices(): Array<number[] | null>;
  /** World position of the point marked on the model (a geodesic source), or null. */
  marker(): number[] | null;
  /** The camera: position, orbit target and up, as [x, y, z]. */
  camera(): { position: number[]; target: number[]; up: number[] };
  /** The up axis in use ('+y', '+z', ...). */
  upAxis(): string;
  /** The current preset's id and the parameters a run would send. */
  params(): { preset: string; params: Record<string, unknown> };
  /** Every live preview and full result put on screen since the page opened, in order. */
  previewEvents(): Array<{ kind: 'preview' | 'full'; at: number; vertices: number; ms: number }>;
  /** The PNG the Snapshot button saves, base64-encoded. */
  snapshot(): Promise<string>;
}

interface Window {
  __geoshift: GeoshiftTestHooks;
}
