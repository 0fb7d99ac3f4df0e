// Types of the geoshift WebAssembly module's exports, hand-written beside bindings.cpp: change both
// together. They describe every flavour:
//   geoshift_web.js / geoshift_web_mt.js    ES modules; the default export is the factory below
//                                           (createGeoshift / createGeoshiftMT).
//   geoshift_node.js / geoshift_node_mt.js  CommonJS; `module.exports` is the factory.
// From the web app: `import type { GeoshiftFactory, GeoshiftModule } from '../../wasm/geoshift';`
// then `const create: GeoshiftFactory = (await import(/* @vite-ignore */ url)).default;`.

/** What mesh construction found and repaired (geoshift::BuildReport). */
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

export interface ProcessMeshSuccess {
  ok: true;
  /** Vertices of the welded (and repaired) mesh. */
  weldedVertexCount: number;
  /** Faces of that mesh (degenerate input faces dropped). */
  faceCount: number;
  /** Caller vertex -> mesh vertex; length = positions.length / 3. */
  vertexOf: Int32Array;
  report: BuildReport;
  /** Mean edge length of the welded mesh: the unit of every spatial parameter. */
  averageEdgeLength: number;
  /** Per caller vertex: mean curvature H, positive on a sphere with outward normals. */
  meanCurvature: Float32Array;
  /** Per caller vertex: Gaussian curvature K. */
  gaussianCurvature: Float32Array;
  /** Per caller vertex: |k1| + |k2| (MeshLab's "absolute" curvature). */
  absoluteCurvature: Float32Array;
}

/** Every call reports failure as a value; nothing throws across the boundary. */
export interface Failure {
  ok: false;
  /** The core's message, meant for the user as it is (names the face, vertex or index). */
  error: string;
}

export type ProcessMeshResult = ProcessMeshSuccess | Failure;

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
export type LoadMeshResult = LoadMeshSuccess | Failure;

/** Per-vertex signals loadMesh can take along (caller layout). */
export interface MeshExtras {
  /** RGB or RGBA per vertex, linear [0, 1]; stored as the signal "color" (alpha dropped). */
  colors?: Float32Array;
  /** One normal per vertex; stored as the unit-vector signal "normal". */
  normals?: Float32Array;
}

/** Parameters of each op (all optional; spatial ones in multiples of the average edge length). */
export interface OpParams {
  noise: { amount?: number; distribution?: 'fixed' | 'uniform' | 'gaussian' | 'impulsive'; direction?: 'random' | 'normal'; seed?: number };
  smooth: { iterations?: number; lambda?: number; mu?: number; weights?: 'uniform' | 'fujiwara' | 'cotangent' };
  curvature: { kind?: 'abs' | 'mean' | 'gauss' | 'rms' };
  /** source: caller vertex index; radius in AEL (default: unlimited). */
  geodesic: { source?: number; radius?: number };
  /**
   * Mean shift of a vertex signal, as `geoshift filter`. signal: "color", "normal", "curvature",
   * "terrain" or a scalar attribute's name (several joined by commas are filtered together).
   * mode "ms" runs one pass, "bms" passes (default 10). hr in the signal's units (default: color
   * 0.1, normal 0.45, others a tenth of their 10-90% spread); hs, radius (0 = 3 hs), eps in AEL.
   * threads: 0 = every worker of the pool; results do not depend on it. levels > 0: the hybrid
   * filter (Algorithm 2) on a mesh coarsened that many wavelet levels, the details added back times
   * alpha (one gain for every level; default 0); filterGeometry: the positions get the gain too.
   */
  filter: {
    signal?: string; mode?: 'ms' | 'bms'; passes?: number; hs?: number; hr?: number; radius?: number;
    kmax?: number; eps?: number; rangeUpdate?: 'joint' | 'sampled'; segments?: boolean; threads?: number;
    levels?: number; alpha?: number; filterGeometry?: boolean;
  };
  /**
   * Denoising of the positions, as `geoshift denoise`. meanshift (default), preset 'default': noise
   * level in AEL (0 = estimated from the mesh), strength (times the noise level), hr between unit
   * normals (smaller keeps more edges), hs and radius in AEL, passes (0 = chosen by SURE);
   * stats say what was estimated and chosen (docs/denoising.md). preset 'paper' (the paper's 4.1):
   * hs, radius, eps in AEL, hr of the normal kernel (eq. 8), kmax, passes, rangeUpdate ('sampled'),
   * faceNormals ('consensus'), supportIterations. A parameter of the other preset is an error.
   * bilateral: normalIterations, sigmaC (AEL, 0 = automatic), sigmaS, neighbors. taubin:
   * iterations, lambda, mu. A parameter of another method than the chosen one is an error.
   * levels > 0 (meanshift only): denoise a mesh coarsened that many wavelet levels and add the
   * details back times alpha (default 0).
   */
  denoise: {
    method?: 'meanshift' | 'bilateral' | 'taubin';
    preset?: 'default' | 'paper'; noise?: number; strength?: number;
    hs?: number; hr?: number; radius?: number; kmax?: number; eps?: number; passes?: number;
    rangeUpdate?: 'joint' | 'sampled'; faceNormals?: 'consensus' | 'mean'; threads?: number;
    supportIterations?: number; vertexIterations?: number;
    normalIterations?: number; sigmaC?: number; sigmaS?: number; neighbors?: 'vertex' | 'edge';
    iterations?: number; lambda?: number; mu?: number;
    levels?: number; alpha?: number;
  };
  // Added with its op (ops_wavelet.cpp); untyped until then.
  [op: string]: Record<string, unknown>;
}
export type OpName = keyof OpParams & string;

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
   * meanIterations, maxIterations (filter), convergedFraction, threads (used) and ms (core time).
   */
  [key: string]: number | string;
}

export interface RunSuccess {
  ok: true;
  /** New positions (x, y, z per caller vertex) when the op moved vertices. */
  positions?: Float32Array;
  /** RGB per caller vertex, linear [0, 1]: a filtered color signal or a color map of a scalar. */
  colors?: Float32Array;
  /** Unit normals per caller vertex, when the op filtered the normals (filter, signal "normal"). */
  normals?: Float32Array;
  /** Named per-vertex scalars such as _CURVATURE, _GEODESIC (-1 = not reached), _SEGMENT. */
  scalars: Record<string, Float32Array>;
  stats: RunStats;
}
export interface RunFailure extends Failure {
  /** Set when onProgress asked the run to stop. */
  cancelled?: true;
  /** Set when the heap could not grow enough. */
  outOfMemory?: true;
}
export type RunResult = RunSuccess | RunFailure;

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
export interface ReadFileSuccess {
  ok: true;
  parts: FilePart[];
  /** Sums over the parts (each part counted once, whatever its instances). */
  vertices: number;
  triangles: number;
  /** What the CLI prints as warnings: content passed through untouched, and why. */
  warnings: string[];
}
export interface ReadFileFailure extends Failure {
  /** Set when the heap could not grow enough to read the file. */
  outOfMemory?: true;
}
export type ReadFileResult = ReadFileSuccess | ReadFileFailure;

/** Called with the fraction done of the named stage; return true to stop the run. */
export type ProgressCallback = (fraction: number, stage: string) => boolean | void;

export interface GeoshiftModule {
  /**
   * Welds coincident vertices, builds the mesh and computes its discrete curvatures. The arrays are
   * copied in; the result's arrays are fresh copies that stay valid whatever the module does next.
   * @param positions x, y, z per vertex, in the caller's layout
   * @param indices three vertex indices per triangle, counter-clockwise from outside
   */
  processMesh(positions: Float32Array, indices: Uint32Array): ProcessMeshResult;
  /** Welds and builds a mesh the module keeps until freeMesh; arrays are copied in. */
  loadMesh(positions: Float32Array, indices: Uint32Array, extras?: MeshExtras): LoadMeshResult;
  /** Adds or replaces a per-vertex signal (dim numbers per caller vertex). "normal" is a unit vector. */
  setAttribute(handle: number, name: string, dim: number, values: Float32Array): { ok: true } | Failure;
  /** Forgets a mesh; false when the handle was unknown. */
  freeMesh(handle: number): boolean;
  /**
   * Runs an op on a kept mesh. Unknown ops and parameters fail before any work. On success the
   * mesh keeps the new positions and signals, so ops chain (noise, then a filter).
   */
  run<Op extends OpName>(handle: number, op: Op, params: OpParams[Op], onProgress?: ProgressCallback): RunResult;
  /**
   * The op run on a coarse wavelet level of a kept mesh (at most maxVertices vertices), its outputs
   * brought back to every vertex without the details: a quick look for a live preview. The level is
   * analysed at the first call and reused while the mesh's positions and signals stay the same. The
   * mesh is left as it was. Stats add previewVertices, levels, stages (analyses chained: a smaller
   * maxVertices analyses the kept coarse mesh further), analysisMs, analysisReused and coarseOpMs.
   */
  preview<Op extends OpName>(handle: number, op: Op, params: OpParams[Op], maxVertices: number, onProgress?: ProgressCallback): RunResult;
  /**
   * The core's readers (the CLI's) on a file's bytes; the name's extension picks the format. The
   * error is the CLI's message, beginning with the name. maxVertices defaults to the CLI's limit
   * (50 000 000; --max-vertices). Nothing of the file is kept.
   */
  readFile(name: string, bytes: Uint8Array, maxVertices?: number): ReadFileResult;
  /** Names of the ops this build knows. */
  ops(): string[];
  /**
   * The core's filter presets (the CLI's --preset), as parameters of the filter op, then one named
   * "denoise": the default denoiser's settings as parameters of the denoise op.
   */
  presets(): CorePreset[];
}

/** What presets() lists: the filter presets, then the denoiser's defaults. */
export type CorePreset = FilterPreset | DenoiseDefaults;

/** The default denoiser's settings (core/include/geoshift/denoise.hpp) in the denoise op's names. */
export interface DenoiseDefaults {
  name: 'denoise';
  description: string;
  signal: 'normal';
  strength: number; hr: number; noise: number; passes: number; radius: number; hs: number;
  vertexIterations: number; levels: number; alpha: number;
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

/** Emscripten module options the app may need; all optional. */
export interface GeoshiftModuleOptions {
  /**
   * The heap (geoshift_web only, built with IMPORTED_MEMORY): a WebAssembly.Memory of at least
   * 1024 pages (64 MB); its maximum is the most the module may grow to.
   */
  wasmMemory?: WebAssembly.Memory;
  /** The .wasm bytes; required under Node for the CommonJS flavours (no fetch from a path). */
  wasmBinary?: ArrayBuffer | Uint8Array;
  /** Where the .wasm (and the threaded flavours' .worker.js) are; default: beside the .js. */
  locateFile?: (path: string, scriptDirectory: string) => string;
  /** Threaded flavours: the URL their pthread workers import the module from. */
  mainScriptUrlOrBlob?: string | Blob;
  print?: (text: string) => void;
  printErr?: (text: string) => void;
}

export type GeoshiftFactory = (options?: GeoshiftModuleOptions) => Promise<GeoshiftModule>;

declare const createGeoshift: GeoshiftFactory;
export default createGeoshift;
