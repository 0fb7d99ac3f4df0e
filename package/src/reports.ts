// Data the module reports (build reports, run figures, file parts, presets): plain values that
// cross the worker boundary and appear in the package's public types.

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
  /** Faces turned over to agree with their neighbours (each piece keeps the orientation of most of its faces). */
  reorientedFaces: number;
  /** Edges with more than two faces, or of two faces whose orientations could not be made to agree; cut apart. */
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
  /** How outliers of impulsive noise are treated (docs/denoising.md#impulsive-noise). */
  impulse: 'auto' | 'on' | 'off';
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
