// Hooks for the end-to-end tests (tests/e2e), set by main.ts.

interface GeoshiftTestHooks {
  /** Resolves once the startup sample has been loaded (or failed to) and drawn. */
  ready: Promise<void>;
  /** The model on screen, or null if none could be shown. */
  stats(): { vertices: number; triangles: number; file: string } | null;
  /** Resolves when no file is loading and the latest change has been drawn. */
  settled(): Promise<void>;
}

interface Window {
  __geoshift: GeoshiftTestHooks;
}
