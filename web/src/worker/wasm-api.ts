// The thin typed wrapper over the module: checks arguments at the JS edge and turns the module's
// { ok: false, error } values into GeoshiftError, so callers use try/catch like any JS API.

import type { Failure, CorePreset, GeoshiftModule, RunFailure, RunResult } from '../../../wasm/geoshift';
import type { ErrorKind, LoadInfo, MeshArrays, ReadInfo, RunOutput } from './protocol';

export class GeoshiftError extends Error {
  override readonly name = 'GeoshiftError';
  constructor(
    message: string,
    readonly kind: ErrorKind,
  ) {
    super(message);
  }
}

function fail(failure: Failure | RunFailure): never {
  const r = failure as RunFailure;
  const kind: ErrorKind = r.cancelled ? 'cancelled' : r.outOfMemory ? 'memory' : r.error.startsWith('internal error') ? 'internal' : 'input';
  throw new GeoshiftError(r.error, kind);
}

function expect(value: unknown, type: { new (...args: never[]): unknown; name: string }, what: string): void {
  if (!(value instanceof type)) throw new GeoshiftError(`${what} must be a ${type.name}`, 'input');
}

export class GeoshiftApi {
  constructor(readonly module: GeoshiftModule) {}

  ops(): string[] {
    return this.module.ops();
  }

  /** The core's filter presets: the one source of their values. */
  presets(): CorePreset[] {
    return this.module.presets();
  }

  /** The core's readers on a file's bytes; a damaged file fails with the CLI's message (kind 'input'). */
  readFile(fileName: string, bytes: Uint8Array): ReadInfo {
    expect(bytes, Uint8Array, 'the file\'s bytes');
    const r = this.module.readFile(fileName, bytes);
    if (!r.ok) fail(r);
    const { parts, vertices, triangles, warnings } = r;
    return { parts, vertices, triangles, warnings };
  }

  /** Copies the mesh into the module; returns its handle and what welding found. */
  load(mesh: MeshArrays): { handle: number; info: LoadInfo } {
    expect(mesh.positions, Float32Array, 'positions');
    expect(mesh.indices, Uint32Array, 'indices');
    if (mesh.colors !== undefined) expect(mesh.colors, Float32Array, 'colors');
    if (mesh.normals !== undefined) expect(mesh.normals, Float32Array, 'normals');
    const extras: { colors?: Float32Array; normals?: Float32Array } = {};
    if (mesh.colors) extras.colors = mesh.colors;
    if (mesh.normals) extras.normals = mesh.normals;
    const r = this.module.loadMesh(mesh.positions, mesh.indices, extras);
    if (!r.ok) fail(r);
    const { handle, vertexCount, weldedVertexCount, faceCount, averageEdgeLength, report } = r;
    return { handle, info: { vertexCount, weldedVertexCount, faceCount, averageEdgeLength, report } };
  }

  setAttribute(handle: number, name: string, dim: number, values: Float32Array): void {
    expect(values, Float32Array, `attribute ${name}`);
    const r = this.module.setAttribute(handle, name, dim, values);
    if (!r.ok) fail(r);
  }

  free(handle: number): void {
    this.module.freeMesh(handle);
  }

  /**
   * Runs an op; `onProgress` returning true stops it (GeoshiftError kind 'cancelled'). The arrays
   * of the output are copies owned by the caller, free to transfer.
   */
  run(handle: number, op: string, params: Record<string, unknown>, onProgress?: (fraction: number, stage: string) => boolean): RunOutput {
    return outputOf(this.module.run(handle, op, params, onProgress));
  }

  /** The op on a coarse level of the mesh, brought back to every vertex (a live preview). */
  preview(handle: number, op: string, params: Record<string, unknown>, maxVertices: number, onProgress?: (fraction: number, stage: string) => boolean): RunOutput {
    if (!Number.isInteger(maxVertices)) throw new GeoshiftError('maxVertices must be a whole number', 'input');
    return outputOf(this.module.preview(handle, op, params, maxVertices, onProgress));
  }
}

function outputOf(r: RunResult): RunOutput {
  if (!r.ok) fail(r);
  const output: RunOutput = { scalars: r.scalars, stats: r.stats };
  if (r.positions) output.positions = r.positions;
  if (r.colors) output.colors = r.colors;
  return output;
}
