// The messages between the page and the geoshift worker. Every request carries an id; the worker
// answers it with exactly one `result` or `error`, after any number of `progress` messages.
// Typed arrays travel as transferred buffers in both directions, never structured-cloned.

import type { BuildReport, CorePreset, FilePart, RunStats } from '../../../wasm/geoshift';

/** A mesh as the page holds it, in its own (three.js) vertex layout. */
export interface MeshArrays {
  positions: Float32Array;
  indices: Uint32Array;
  /** RGB or RGBA per vertex, linear [0, 1]. */
  colors?: Float32Array;
  normals?: Float32Array;
  /** Named one-number-per-vertex signals (terrain attributes, earlier results). */
  scalars?: Record<string, Float32Array>;
}

export type Request =
  /** Reads a file's bytes with the core's readers (the CLI's): the page opens only what they accept. */
  | { type: 'read'; id: number; fileName: string; bytes: Uint8Array }
  | ({ type: 'load'; id: number; meshId: string } & MeshArrays)
  | { type: 'run'; id: number; meshId: string; op: string; params: Record<string, unknown> }
  /** The op on a coarse level of the mesh (at most maxVertices vertices); the mesh is not changed. */
  | { type: 'preview'; id: number; meshId: string; op: string; params: Record<string, unknown>; maxVertices: number }
  /**
   * Asks run `runId` to stop. A run blocks the worker, so this message is read only after the run
   * ended; the shared flag (threaded build) or terminating the worker does the actual stopping (see
   * client.ts). It is answered, and keeps a log of the exchange complete.
   */
  | { type: 'cancel'; id: number; runId: number }
  /** Forgets a mesh (a new file replaced it). */
  | { type: 'free'; id: number; meshId: string };

export interface LoadInfo {
  vertexCount: number;
  weldedVertexCount: number;
  faceCount: number;
  averageEdgeLength: number;
  report: BuildReport;
}

/** What the core's readers found in a file (readFile without its ok flag). */
export interface ReadInfo {
  parts: FilePart[];
  vertices: number;
  triangles: number;
  warnings: string[];
}

export interface RunOutput {
  positions?: Float32Array;
  colors?: Float32Array;
  scalars: Record<string, Float32Array>;
  stats: RunStats;
}

/** Why a request failed: the page words each kind differently. */
export type ErrorKind = 'input' | 'cancelled' | 'memory' | 'internal';

export type Response =
  /** Sent once when the module is ready: which build runs and what it can do. */
  | { type: 'ready'; threaded: boolean; threads: number; ops: string[]; presets: CorePreset[] }
  /** The module could not start (no wasm, a missing file). */
  | { type: 'fatal'; message: string }
  | { type: 'progress'; id: number; fraction: number; stage: string }
  | { type: 'result'; id: number; kind: 'read'; info: ReadInfo }
  | { type: 'result'; id: number; kind: 'load'; info: LoadInfo }
  | { type: 'result'; id: number; kind: 'run'; output: RunOutput }
  | { type: 'result'; id: number; kind: 'free' | 'cancel' }
  | { type: 'error'; id: number; kind: ErrorKind; message: string };

const requestTypes = new Set(['read', 'load', 'run', 'preview', 'cancel', 'free']);
const responseTypes = new Set(['ready', 'fatal', 'progress', 'result', 'error']);

function hasType(value: unknown, types: Set<string>): value is { type: string } {
  return typeof value === 'object' && value !== null && types.has((value as { type?: unknown }).type as string);
}

/** Run-time check of an incoming message: a stray postMessage must not be taken for a request. */
export function isRequest(value: unknown): value is Request {
  if (!hasType(value, requestTypes)) return false;
  const v = value as Record<string, unknown>;
  if (typeof v.id !== 'number') return false;
  switch (v.type) {
    case 'read':
      return typeof v.fileName === 'string' && v.bytes instanceof Uint8Array;
    case 'load':
      return typeof v.meshId === 'string' && v.positions instanceof Float32Array && v.indices instanceof Uint32Array;
    case 'run':
      return typeof v.meshId === 'string' && typeof v.op === 'string' && typeof v.params === 'object' && v.params !== null;
    case 'preview':
      return typeof v.meshId === 'string' && typeof v.op === 'string' && typeof v.params === 'object' && v.params !== null && typeof v.maxVertices === 'number';
    case 'free':
      return typeof v.meshId === 'string';
    case 'cancel':
      return typeof v.runId === 'number';
    default:
      return true;
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
