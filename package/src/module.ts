// Types of the WebAssembly module's exports (wasm/bindings.cpp, wasm/adapters.hpp): change both
// together. The package ships two flavours built from the same sources (wasm/CMakeLists.txt):
//   geoshift_web.js      single-threaded; the default export is the factory (createGeoshift)
//   geoshift_web_mt.js   pthreads (+ geoshift_web_mt.worker.js) for cross-origin-isolated pages and Node
// Only the worker talks to the module; users of the package see the typed API of index.ts.

/** What mesh construction found and repaired (geoshift::BuildReport, core/include/geoshift/mesh.hpp). */
export interface BuildReport {
  inputVertices: number;
  inputFaces: number;
  /** Caller vertices merged into an earlier coincident one. */
  weldedVertices: number;
  /** Faces dropped because they use one vertex twice. */
  repeatedIndexFaces: number;
  /** Faces dropped because their corners are collinear. */
  zeroAreaFaces: number;
  /** Edges with more than two faces or inconsistent orientation; cut apart. */
  nonManifoldEdges: number;
  /** Vertices whose faces form several fans; split. */
  nonManifoldVertices: number;
  /** Vertices added by that split. */
  splitVertexCopies: number;
  /** Vertices no face uses; kept and left untouched. */
  isolatedVertices: number;
  /** One plain-language line per kind of problem, naming the first offending indices. */
  messages: string[];
}

/** Every call reports failure as a value; nothing throws across the boundary. */
export interface Failure {
  ok: false;
  /** The core's message, meant for the user as it is (names the face, vertex or index). */
  error: string;
  /** Set when onProgress asked the run to stop. */
  cancelled?: true;
  /** Set when the heap could not grow enough. */
  outOfMemory?: true;
}

/** Counts and unit of a mesh the module keeps (loadMesh). */
export interface LoadMeshSuccess {
  ok: true;
  /** Pass to setAttribute / run / freeMesh. */
  handle: number;
  /** Caller vertices (positions.length / 3): the layout every result comes back in. */
  vertexCount: number;
  weldedVertexCount: number;
  faceCount: number;
  /** Mean edge length of the welded mesh: the unit (AEL) of every spatial parameter. */
  averageEdgeLength: number;
  report: BuildReport;
}

/** Figures of one run: the dispatcher's, then the op's own (iterations, passes, ms, ...). */
export interface RunStats {
  op: string;
  /** Time inside the module, including the copy-out, in milliseconds. */
  timeMs: number;
  vertices: number;
  weldedVertices: number;
  /** Threads an op could use in this build (1 in the single-threaded one). */
  threadsAvailable: number;
  /**
   * Op-specific figures: iterations, displacementRms, reachedVertices; the mean shift ops add
   * meanIterations, maxIterations (filter), convergedFraction, threads (used) and ms (core time);
   * preview adds previewVertices, levels, stages, analysisMs, analysisReused and coarseOpMs.
   */
  [key: string]: number | string;
}

export interface RunSuccess {
  ok: true;
  positions?: Float32Array;
  colors?: Float32Array;
  normals?: Float32Array;
  scalars: Record<string, Float32Array>;
  stats: RunStats;
}

/** One mesh of a file as the core's readers found it (readFile). */
export interface FilePart {
  /** As in the CLI's messages: "mesh 0 'Duck' primitive 0", the OBJ file's name, ... */
  label: string;
  vertices: number;
  triangles: number;
  /** Nodes that draw it (glTF); 1 for the other formats. */
  instances: number;
  /** What building it as the filters do found and repaired. */
  report: BuildReport;
}

/** readFile with withArrays: each part also carries its arrays, in the file's own vertex order. */
export interface FilePartArrays {
  positions: Float32Array;
  indices: Uint32Array;
  normals?: Float32Array;
  /** RGBA per vertex, [0, 1] (linear for glTF). */
  colors?: Float32Array;
  /** Extra per-vertex attributes (glTF "_NAME" accessors, PLY properties), dim numbers per vertex. */
  attributes: Record<string, Float32Array>;
  /** World transform of every instance, 16 numbers each, column-major. */
  transforms: Float64Array;
}

export interface ReadFileSuccess {
  ok: true;
  parts: Array<FilePart & Partial<FilePartArrays>>;
  vertices: number;
  triangles: number;
  warnings: string[];
}

/** Called with the fraction done of the named stage; return true to stop the run. */
export type ModuleProgress = (fraction: number, stage: string) => boolean | void;

export interface GeoshiftModule {
  loadMesh(positions: Float32Array, indices: Uint32Array, extras?: { colors?: Float32Array; normals?: Float32Array }): LoadMeshSuccess | Failure;
  setAttribute(handle: number, name: string, dim: number, values: Float32Array): { ok: true } | Failure;
  freeMesh(handle: number): boolean;
  run(handle: number, op: string, params: object, onProgress?: ModuleProgress): RunSuccess | Failure;
  preview(handle: number, op: string, params: object, maxVertices: number, onProgress?: ModuleProgress): RunSuccess | Failure;
  readFile(name: string, bytes: Uint8Array, maxVertices: number, withArrays: boolean): ReadFileSuccess | Failure;
  ops(): string[];
  presets(): CorePreset[];
  /** The threaded flavour's pthread pool (Emscripten's), terminated with the module. */
  PThread?: { terminateAllThreads(): void };
}

/** What presets() lists: the filter presets, then the denoiser's defaults. */
export type CorePreset = FilterPreset | DenoiseDefaults;

/** The default denoiser's settings (core/include/geoshift/denoise.hpp) in the denoise op's names. */
export interface DenoiseDefaults {
  name: 'denoise';
  description: string;
  signal: 'normal';
  strength: number;
  hr: number;
  noise: number;
  passes: number;
  radius: number;
  hs: number;
  vertexIterations: number;
  levels: number;
  alpha: number;
}

/** A filter preset of the core (core/src/presets.cpp): the filter op's parameters and what it is. */
export interface FilterPreset {
  name: string;
  description: string;
  /** The signal it is meant for: color, normal, curvature, terrain. */
  signal: string;
  mode: 'ms' | 'bms';
  passes: number;
  hs: number;
  hr: number;
  /** In AEL; the core's default 3 hs written out. */
  radius: number;
  eps: number;
  kmax: number;
  rangeUpdate: 'joint' | 'sampled';
  levels: number;
  alpha: number;
}

/** Emscripten module options the worker passes; all optional. */
export interface ModuleOptions {
  /** The single-threaded flavour's heap (IMPORTED_MEMORY): at least 1024 pages (64 MB). */
  wasmMemory?: WebAssembly.Memory;
  /** The .wasm bytes (Node: there is no fetch from a path). */
  wasmBinary?: ArrayBuffer | Uint8Array;
  /** Where the .wasm and the threaded flavour's .worker.js are. */
  locateFile?: (path: string, scriptDirectory: string) => string;
  /** Threaded flavour: the URL its pthread workers import the module from. */
  mainScriptUrlOrBlob?: string | Blob;
  /** Threaded flavour: workers in the pthread pool (wasm/CMakeLists.txt, PTHREAD_POOL_SIZE). */
  pthreadPoolSize?: number;
  print?: (text: string) => void;
  printErr?: (text: string) => void;
}

export type ModuleFactory = (options?: ModuleOptions) => Promise<GeoshiftModule>;
