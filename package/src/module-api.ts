// The thin typed wrapper over the module, used inside the worker: checks arguments at the JS edge
// and turns the module's { ok: false, error } values into GeoshiftError, so the engine uses
// try/catch like any JS API.

import { GeoshiftError, type GeoshiftErrorKind } from './errors.js';
import type { Failure, GeoshiftModule, RunSuccess } from './module.js';
import type { CorePreset } from './reports.js';
import type { LoadInfo, MeshArrays, Params, ReadInfo, RunOutput } from './protocol.js';

function fail(failure: Failure): never {
  const kind: GeoshiftErrorKind = failure.cancelled ? 'cancelled' : failure.outOfMemory ? 'out-of-memory' : failure.error.startsWith('internal error') ? 'internal' : 'input';
  throw new GeoshiftError(failure.error, kind);
}

function expect(value: unknown, type: { new (...args: never[]): unknown; name: string }, what: string): void {
  if (!(value instanceof type)) throw new GeoshiftError(`${what} must be a ${type.name}`, 'input');
}

export class ModuleApi {
  constructor(readonly module: GeoshiftModule) {}

  ops(): string[] {
    return this.module.ops();
  }

  /** The core's filter presets and the denoiser's defaults: the one source of their values. */
  presets(): CorePreset[] {
    return this.module.presets();
  }

  /** The core's readers on a file's bytes; a damaged file fails with the CLI's message (kind 'input'). */
  readFile(fileName: string, bytes: Uint8Array, maxVertices: number, arrays: boolean): ReadInfo {
    expect(bytes, Uint8Array, "the file's bytes");
    const r = this.module.readFile(fileName, bytes, maxVertices, arrays);
    if (!r.ok) fail(r);
    const { parts, vertices, triangles, warnings } = r;
    return { parts, vertices, triangles, warnings };
  }

  /** Copies the mesh into the module, its attributes too; returns its handle and what welding found. */
  load(mesh: MeshArrays): { handle: number; info: LoadInfo } {
    expect(mesh.positions, Float32Array, 'positions');
    expect(mesh.indices, Uint32Array, 'indices');
    if (mesh.colors !== undefined) expect(mesh.colors, Float32Array, 'colors');
    const extras: { colors?: Float32Array } = {};
    if (mesh.colors) extras.colors = mesh.colors;
    const r = this.module.loadMesh(mesh.positions, mesh.indices, extras);
    if (!r.ok) fail(r);
    const { handle, vertexCount, weldedVertexCount, faceCount, averageEdgeLength, report } = r;
    try {
      for (const [name, values] of Object.entries(mesh.attributes ?? {})) {
        expect(values, Float32Array, `attribute "${name}"`);
        this.setAttribute(handle, name, vertexCount > 0 ? values.length / vertexCount : 1, values);
      }
    } catch (e) {
      this.free(handle);
      throw e;
    }
    return { handle, info: { vertexCount, weldedVertexCount, faceCount, averageEdgeLength, report } };
  }

  setAttribute(handle: number, name: string, dim: number, values: Float32Array): void {
    expect(values, Float32Array, `attribute "${name}"`);
    if (!Number.isInteger(dim)) throw new GeoshiftError(`attribute "${name}": ${values.length} numbers is not a whole number per vertex`, 'input');
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
  run(handle: number, op: string, params: Params, onProgress?: (fraction: number, stage: string) => boolean): RunOutput {
    return outputOf(this.module.run(handle, op, params, onProgress));
  }

  /** The op on a coarse level of the mesh, brought back to every vertex (a live preview). */
  preview(handle: number, op: string, params: Params, maxVertices: number, onProgress?: (fraction: number, stage: string) => boolean): RunOutput {
    if (!Number.isInteger(maxVertices) || maxVertices < 1) throw new GeoshiftError(`maxVertices must be a whole number of at least 1 (got ${maxVertices})`, 'input');
    return outputOf(this.module.preview(handle, op, params, maxVertices, onProgress));
  }
}

function outputOf(r: RunSuccess | Failure): RunOutput {
  if (!r.ok) fail(r);
  const output: RunOutput = { attributes: r.scalars, stats: r.stats };
  if (r.positions) output.positions = r.positions;
  if (r.colors) output.colors = r.colors;
  if (r.normals) output.normals = r.normals;
  return output;
}
