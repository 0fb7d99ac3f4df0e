// The package's public data types: what goes in (a mesh, call options) and what comes out.

import type { BuildReport, CorePreset, RunStats } from './reports.js';
import type { OpName, OpOptions } from './options.js';
import type { LoadInfo } from './protocol.js';

export type { BuildReport, CorePreset, DenoiseDefaults, FilterPreset, RunStats } from './reports.js';
export type { LoadInfo } from './protocol.js';

/**
 * A triangle mesh in flat arrays, as WebGL and three.js hold it. Vertices that share a position are
 * welded inside the filters (so a mesh split along UV or normal seams filters as one surface) and
 * every result comes back in this layout, one value per vertex given.
 */
export interface Mesh {
  /** x, y, z per vertex. */
  positions: Float32Array;
  /**
   * Three vertex indices per triangle, counter-clockwise seen from outside. Omitted: the positions
   * are a triangle soup (vertices 0, 1, 2 form the first triangle, and so on).
   */
  indices?: Uint32Array | Uint16Array;
  /** RGB or RGBA per vertex, linear, in [0, 1]: the signal "color" (filters use RGB; alpha is not filtered). */
  colors?: Float32Array;
  /**
   * Named per-vertex signals (a terrain's height, a scan's intensity): one or more numbers per
   * vertex, the length saying how many. `filter` can smooth them by name (`signal: 'height'`).
   */
  attributes?: Record<string, Float32Array>;
}

/** What every job returns: fresh arrays in the input's vertex layout; the input is not modified. */
export interface MeshResult {
  /** x, y, z per vertex: moved by the job, or a copy of the input's. */
  positions: Float32Array;
  /** RGB per vertex: filtered colors (`filter` of "color"), or a color map of the result (curvature). */
  colors?: Float32Array;
  /** Unit normals per vertex, when the job filtered normals (`filter` of "normal"). */
  normals?: Float32Array;
  /**
   * Named per-vertex scalars the job computed: `_CURVATURE`, `_GEODESIC` (-1 where not reached),
   * `_SEGMENT` (filter with segments), or a filtered attribute under its own name.
   */
  attributes: Record<string, Float32Array>;
  /** Figures of the run: op, timeMs, vertices, weldedVertices, threadsAvailable, and the op's own. */
  stats: RunStats;
  /** What building the mesh found and repaired (welded vertices, dropped faces, non-manifold parts). */
  report: BuildReport;
}

/** What a run on a loaded mesh changed ({@link GeoshiftMesh.run}). */
export interface MeshUpdate {
  /** New positions, when the op moved vertices. */
  positions?: Float32Array;
  colors?: Float32Array;
  normals?: Float32Array;
  attributes: Record<string, Float32Array>;
  stats: RunStats;
}

/** Options every call takes. */
export interface CallOptions {
  /**
   * Called in the page with the fraction done (0 to 1) of the named stage ("mean shift pass 2/4",
   * "copying results"), a few times a second.
   */
  onProgress?: (fraction: number, stage: string) => void;
  /**
   * Cancels the call: its promise rejects with a GeoshiftError of kind 'cancelled'. With threads the
   * run stops at its next progress step; single-threaded, the worker is replaced at once.
   */
  signal?: AbortSignal;
}

/** Options of {@link createGeoshift}. */
export interface CreateOptions {
  /**
   * 'auto' (default): the threaded build with one thread per core (at most 8) where it can run (a
   * cross-origin-isolated page, Node), else one thread. A number: that many threads (1: the
   * single-threaded build). Results do not depend on it.
   */
  threads?: 'auto' | number;
  /**
   * Where the module's files are, for a CDN or a server path of your choice: called with the name
   * of each file the build needs (geoshift_web.js and geoshift_web.wasm, or geoshift_web_mt.js and
   * geoshift_web_mt.wasm); return its URL (under Node: a path or file: URL), or undefined for the
   * default, beside the package's own files.
   */
  locateFile?: (file: string) => string | URL | undefined;
  /**
   * The most the single-threaded build's heap may grow to, in MB (at least 64). Default: wasm32's
   * 4 GB. The threaded build always may grow to 4 GB.
   */
  maxMemoryMB?: number;
}

/** What runs: set once the worker is ready. */
export interface GeoshiftInfo {
  /** True when the threaded build runs. */
  threaded: boolean;
  /** Threads the jobs use (1 single-threaded). */
  threads: number;
  /** Why threads were asked for and not used (e.g. the page is not cross-origin isolated). */
  note?: string;
  /** The ops this build knows. */
  ops: string[];
  /** The core's filter presets and the denoiser's defaults (the command-line tool's `--preset`). */
  presets: CorePreset[];
  /** The package's version. */
  version: string;
}

/** Options of {@link Geoshift.read}. */
export interface ReadOptions extends CallOptions {
  /** Refuse files declaring more vertices than this (default 50 000 000, the CLI's --max-vertices). */
  maxVertices?: number;
  /** false: only check and count (no arrays cross back), as before showing a file with your own loader. */
  meshes?: boolean;
}

/** One mesh of a file. */
export interface ReadPart {
  /** As in the core's messages: "mesh 0 'Duck' primitive 0", or the file's name. */
  label: string;
  vertices: number;
  triangles: number;
  /** Nodes that draw it (glTF); 1 for the other formats. */
  instances: number;
  /** What building it as the filters do would find and repair. */
  report: BuildReport;
  /** Its arrays, in the file's own vertex order (colors as RGBA; normals where the file has them); absent with `meshes: false`. */
  mesh?: Mesh & { indices: Uint32Array; normals?: Float32Array };
  /** The world transform of every instance, 16 numbers each, column-major (three's Matrix4.fromArray). */
  transforms?: Float64Array;
}

/** What the core's readers found in a file. */
export interface ReadResult {
  parts: ReadPart[];
  vertices: number;
  triangles: number;
  /** Content passed over, and why (points, lines; what the command-line tool prints as warnings). */
  warnings: string[];
}

/** A mesh kept in the worker ({@link Geoshift.load}): runs chain, and previews reuse their coarse level. */
export interface GeoshiftMesh {
  /** Counts, the unit of spatial options and what the core repaired. */
  readonly info: LoadInfo;
  /** Runs an op on the kept mesh, which then keeps the op's output (so ops chain: noise, then denoise). */
  run<Op extends OpName>(op: Op, options?: OpOptions[Op] & CallOptions): Promise<MeshUpdate>;
  /**
   * The op on a coarse wavelet level of the mesh (at most maxVertices vertices), brought back to
   * every vertex: a quick look while a slider moves. The level is analysed once and reused; the
   * kept mesh does not change. Its signal stops a threaded preview at once and lets a
   * single-threaded one finish (the worker keeps its level) before rejecting as cancelled.
   */
  preview<Op extends OpName>(op: Op, options: OpOptions[Op] & CallOptions & { maxVertices: number }): Promise<MeshUpdate>;
  /** Frees the worker's copy. */
  free(): Promise<void>;
}
