// The messages between the page (client.ts) and the worker (worker.ts, node-worker.ts, both driving
// engine.ts). Every request carries an id; the worker answers it with exactly one `result` or
// `error`, after any number of `progress` messages. Typed arrays travel as transferred buffers in
// both directions, never structured-cloned. docs/architecture.md#worker-protocol.

import type { GeoshiftErrorKind } from './errors.js';
import type { BuildReport, CorePreset, FilePart, FilePartArrays, RunStats } from './reports.js';

/** A mesh as it crosses to the worker: the caller's vertex layout, checked by mesh.ts. */
export interface MeshArrays {
  positions: Float32Array;
  indices: Uint32Array;
  /** RGB or RGBA per vertex, linear [0, 1]. */
  colors?: Float32Array;
  /** Named per-vertex signals, any number of components (the length says how many). */
  attributes?: Record<string, Float32Array>;
}

/** Op parameters as they cross: the caller's options without onProgress and signal. */
export type Params = Record<string, unknown>;

export type Request =
  /** The core's readers on a file's bytes; `arrays` adds each part's arrays to the answer. */
  | { type: 'read'; id: number; fileName: string; bytes: Uint8Array; maxVertices: number; arrays: boolean }
  /** Load a mesh and keep it under meshId (replacing one of that id). */
  | ({ type: 'load'; id: number; meshId: string } & MeshArrays)
  /** Run an op on a kept mesh; it keeps the op's output, so runs chain. */
  | { type: 'run'; id: number; meshId: string; op: string; params: Params }
  /** The op on a coarse level of a kept mesh (at most maxVertices vertices); the mesh is not changed. */
  | { type: 'preview'; id: number; meshId: string; op: string; params: Params; maxVertices: number }
  /** Load, run and forget in one: the answer always carries positions. */
  | ({ type: 'job'; id: number; op: string; params: Params } & MeshArrays)
  /**
   * Asks run `runId` to stop. A run blocks the worker, so this message is read only after the run
   * ended; the shared flag (threaded build) or terminating the worker does the actual stopping (see
   * client.ts). It is answered, and keeps a log of the exchange complete.
   */
  | { type: 'cancel'; id: number; runId: number }
  /** Forgets a kept mesh. */
  | { type: 'free'; id: number; meshId: string };

/** What loading found: counts, the unit of spatial options, and what the core repaired. */
export interface LoadInfo {
  /** Vertices as given (the layout of every result). */
  vertexCount: number;
  /** Vertices after welding coincident ones (what the filters work on). */
  weldedVertexCount: number;
  faceCount: number;
  /** Mean edge length of the welded mesh: the unit (AEL) of every spatial option. */
  averageEdgeLength: number;
  report: BuildReport;
}

/** What the core's readers found in a file. */
export interface ReadInfo {
  parts: Array<FilePart & Partial<FilePartArrays>>;
  vertices: number;
  triangles: number;
  warnings: string[];
}

/** An op's output in the caller's vertex layout; positions only when the op moved vertices. */
export interface RunOutput {
  positions?: Float32Array;
  colors?: Float32Array;
  normals?: Float32Array;
  attributes: Record<string, Float32Array>;
  stats: RunStats;
}

/** A job's output: positions always (the input's when the op does not move vertices). */
export interface JobOutput extends RunOutput {
  positions: Float32Array;
  report: BuildReport;
}

/** Sent once by the page before any request. */
export interface Init {
  type: 'init';
  threaded: boolean;
  /** Threads of the threaded build (its pthread pool); 1 for the single-threaded one. */
  threads: number;
  /**
   * URLs (or, under Node, paths) of the module's files by name, from the caller's locateFile; files
   * not listed are found beside the package's worker.
   */
  files: Record<string, string>;
  /** Threaded build: the page stores the id of the run to stop in element 0. */
  cancelFlag?: SharedArrayBuffer;
  /** The single-threaded build's heap limit in MB (at least 64, its initial size); 0: wasm32's 4 GB. */
  maxMemoryMB: number;
}

export type Response =
  /** Sent once when the module is ready: which build runs and what it can do. */
  | { type: 'ready'; threaded: boolean; threads: number; ops: string[]; presets: CorePreset[] }
  /** The module could not start (no wasm, a missing file). */
  | { type: 'fatal'; message: string }
  | { type: 'progress'; id: number; fraction: number; stage: string }
  | { type: 'result'; id: number; kind: 'read'; info: ReadInfo }
  | { type: 'result'; id: number; kind: 'load'; info: LoadInfo }
  | { type: 'result'; id: number; kind: 'run'; output: RunOutput }
  | { type: 'result'; id: number; kind: 'job'; output: JobOutput }
  | { type: 'result'; id: number; kind: 'free' | 'cancel' }
  | { type: 'error'; id: number; kind: GeoshiftErrorKind; message: string };

const requestTypes = new Set(['read', 'load', 'run', 'preview', 'job', 'cancel', 'free']);
const responseTypes = new Set(['ready', 'fatal', 'progress', 'result', 'error']);

function hasType(value: unknown, types: Set<string>): value is { type: string } {
  return typeof value === 'object' && value !== null && types.has((value as { type?: unknown }).type as string);
}

function isParams(value: unknown): boolean {
  return typeof value === 'object' && value !== null;
}

function isMesh(v: Record<string, unknown>): boolean {
  return v.positions instanceof Float32Array && v.indices instanceof Uint32Array;
}

/** Run-time check of an incoming message: a stray postMessage must not be taken for a request. */
export function isRequest(value: unknown): value is Request {
  if (!hasType(value, requestTypes)) return false;
  const v = value as Record<string, unknown>;
  if (typeof v.id !== 'number') return false;
  switch (v.type) {
    case 'read':
      return typeof v.fileName === 'string' && v.bytes instanceof Uint8Array && typeof v.maxVertices === 'number' && typeof v.arrays === 'boolean';
    case 'load':
      return typeof v.meshId === 'string' && isMesh(v);
    case 'run':
      return typeof v.meshId === 'string' && typeof v.op === 'string' && isParams(v.params);
    case 'preview':
      return typeof v.meshId === 'string' && typeof v.op === 'string' && isParams(v.params) && typeof v.maxVertices === 'number';
    case 'job':
      return typeof v.op === 'string' && isParams(v.params) && isMesh(v);
    case 'free':
      return typeof v.meshId === 'string';
    case 'cancel':
      return typeof v.runId === 'number';
    default:
      return false;
  }
}

export function isResponse(value: unknown): value is Response {
  return hasType(value, responseTypes);
}

/** The buffers of a message's typed arrays, to pass as postMessage's transfer list. */
export function transferables(arrays: Array<ArrayBufferView | undefined>): ArrayBuffer[] {
  const buffers = new Set<ArrayBuffer>();
  for (const a of arrays) {
    if (a && a.buffer instanceof ArrayBuffer) buffers.add(a.buffer);
  }
  return [...buffers];
}

/** Every typed array of a mesh or an output. */
export function arraysOf(m: { positions?: Float32Array; indices?: Uint32Array; colors?: Float32Array; normals?: Float32Array; attributes?: Record<string, Float32Array> }): ArrayBufferView[] {
  return [m.positions, m.indices, m.colors, m.normals, ...Object.values(m.attributes ?? {})].filter((a): a is NonNullable<typeof a> => a !== undefined);
}
