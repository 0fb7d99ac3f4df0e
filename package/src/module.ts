// Types of the WebAssembly module's exports (wasm/bindings.cpp, wasm/adapters.hpp): change both
// together. The package ships two flavours built from the same sources (wasm/CMakeLists.txt):
//   geoshift_web.js      single-threaded; the default export is the factory (createGeoshift)
//   geoshift_web_mt.js   pthreads (+ geoshift_web_mt.worker.js) for cross-origin-isolated pages and Node
// Only the worker talks to the module; users of the package see the typed API of index.ts.

import type { BuildReport, CorePreset, FilePart, FilePartArrays, RunStats } from './reports.js';

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
  /** Caller vertex -> welded vertex; length = vertexCount. */
  vertexOf: Int32Array;
}

export interface RunSuccess {
  ok: true;
  positions?: Float32Array;
  colors?: Float32Array;
  normals?: Float32Array;
  scalars: Record<string, Float32Array>;
  stats: RunStats;
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
  /** Every op's parameter table (the core's params.hpp): options.ts is generated from it. */
  paramSpecs(): ParamSpecs;
  /** The threaded flavour's pthread pool (Emscripten's), terminated with the module. */
  PThread?: { terminateAllThreads(): void };
}

/** One parameter of an op's table (core/include/geoshift/params.hpp), as paramSpecs() gives it. */
export interface ParamSpec {
  type: 'number' | 'integer' | 'boolean' | 'enum' | 'string';
  doc: string;
  /** Absent: none, or computed by the op (the doc says how). A list's default is a number when it is one value. */
  default?: number | boolean | string | number[];
  min?: number;
  max?: number;
  /** min itself is refused (the parameter must be > min). */
  minExclusive?: true;
  /** enum: the choices. */
  values?: string[];
  /** number, integer: one value or an array of them (e.g. one per level). */
  list?: true;
  /** Applies only where one of these holds: each named parameter has one of the listed values. */
  when?: Array<Record<string, string[]>>;
  /** Other defaults or bounds where `when` holds (the first that holds). */
  cases?: Array<{ when: Record<string, string[]>; default?: number | boolean | string | number[]; min?: number; max?: number }>;
}
export type ParamSpecs = Record<string, { doc: string; params: Record<string, ParamSpec> }>;

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
