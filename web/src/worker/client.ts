// The app's bookkeeping over the `geoshift` package (package/, docs/architecture.md#the-npm-package),
// which owns the worker, its protocol and cancel: the app names its meshes by id (one per mesh of
// the open file, and one per preview session), has one run at a time and a Cancel button. Nothing
// here talks to the worker or the module directly.

import { coreNames, createGeoshift, GeoshiftError, type Geoshift, type GeoshiftInfo, type GeoshiftMesh, type MeshUpdate, type OpName, type OpOptions, type ReadResult } from 'geoshift';

export { GeoshiftError };

export type WorkerInfo = GeoshiftInfo;
export type ReadInfo = ReadResult;

/** A mesh as the page holds it, in its own (three.js) vertex layout. */
export interface MeshArrays {
  positions: Float32Array;
  indices?: Uint32Array;
  /** RGB or RGBA per vertex, linear [0, 1]. */
  colors?: Float32Array;
  /** Named one-number-per-vertex signals (terrain attributes, earlier results). */
  scalars?: Record<string, Float32Array>;
}

/** What a run changed, as the app applies it (model.ts). */
export interface RunOutput {
  positions?: Float32Array;
  colors?: Float32Array;
  scalars: Record<string, Float32Array>;
  stats: MeshUpdate['stats'];
}

export type ProgressListener = (fraction: number, stage: string) => void;

type Build = 'auto' | 'single' | 'threaded';

export class WorkerClient {
  private readonly started: Promise<Geoshift>;
  private readonly meshes = new Map<string, Promise<GeoshiftMesh>>();
  /** The run or preview in progress, to cancel. */
  private current: { controller: AbortController; preview: boolean } | null = null;

  constructor(
    build: Build = 'auto',
    /** The single-threaded build's heap limit in MB (?heap=, main.ts); default: wasm32's 4 GB. */
    heapMB?: number,
  ) {
    const threads = build === 'single' ? 1 : build === 'threaded' ? Math.max(2, Math.min(navigator.hardwareConcurrency || 4, 8)) : 'auto';
    this.started = createGeoshift({ threads, ...(heapMB ? { maxMemoryMB: Math.max(64, heapMB) } : {}) });
    this.started.catch(() => undefined);
  }

  /** Resolves with what the worker runs once its module is ready; rejects if it cannot start. */
  async ready(): Promise<WorkerInfo> {
    return (await this.started).info;
  }

  /**
   * Reads a file with the core's readers, counts only (the caller keeps its bytes). Rejects with a
   * GeoshiftError of kind 'input' (the CLI's message) or 'out-of-memory' (the package then starts
   * a fresh worker, whose heap is small again).
   */
  async read(fileName: string, bytes: ArrayBuffer): Promise<ReadInfo> {
    return (await this.started).read(bytes, fileName, { meshes: false });
  }

  /** Copies the mesh into the worker under `meshId` (replacing what was there). */
  async load(meshId: string, mesh: MeshArrays): Promise<void> {
    const gs = await this.started;
    void this.free(meshId);
    const loading = gs.load({
      positions: mesh.positions,
      ...(mesh.indices ? { indices: mesh.indices } : {}),
      ...(mesh.colors ? { colors: mesh.colors } : {}),
      ...(mesh.scalars ? { attributes: mesh.scalars } : {}),
    });
    this.meshes.set(meshId, loading);
    loading.catch(() => this.meshes.get(meshId) === loading && this.meshes.delete(meshId));
    await loading;
  }

  async free(meshId: string): Promise<void> {
    const kept = this.meshes.get(meshId);
    this.meshes.delete(meshId);
    if (kept) await (await kept).free();
  }

  async run(meshId: string, op: string, params: Record<string, unknown>, onProgress?: ProgressListener): Promise<RunOutput> {
    const mesh = await this.mesh(meshId);
    const controller = this.begin(false);
    try {
      const options = { ...optionsOf(op, params), signal: controller.signal, ...(onProgress ? { onProgress } : {}) };
      return outputOf(await mesh.run(op as OpName, options));
    } finally {
      this.end(controller);
    }
  }

  /** The op on a coarse level of a loaded mesh (live preview); the worker's mesh is not changed. */
  async preview(meshId: string, op: string, params: Record<string, unknown>, maxVertices: number): Promise<RunOutput> {
    const mesh = await this.mesh(meshId);
    const controller = this.begin(true);
    try {
      return outputOf(await mesh.preview(op as OpName, { ...optionsOf(op, params), maxVertices, signal: controller.signal }));
    } finally {
      this.end(controller);
    }
  }

  /**
   * Asks a running preview to stop: with threads at once, keeping the worker and the coarse level it
   * analysed; without, the preview finishes and its caller drops it.
   */
  stopPreview(): void {
    if (this.current?.preview) this.current.controller.abort();
  }

  /** Stops the current run, if any; its promise rejects with a GeoshiftError of kind 'cancelled'. */
  cancel(): void {
    this.current?.controller.abort();
  }

  dispose(): void {
    void this.started.then((gs) => gs.terminate(), () => undefined);
  }

  private async mesh(meshId: string): Promise<GeoshiftMesh> {
    const kept = this.meshes.get(meshId);
    if (!kept) throw new GeoshiftError(`mesh "${meshId}" was not loaded into the worker`, 'input');
    return kept;
  }

  private begin(preview: boolean): AbortController {
    const controller = new AbortController();
    this.current = { controller, preview };
    return controller;
  }

  private end(controller: AbortController): void {
    if (this.current?.controller === controller) this.current = null;
  }
}

/**
 * The panel's parameters (presets.ts) carry the core's names, as the CLI's options and the core's
 * presets do; the package names a few differently (filter's signal is its field). The core refuses
 * a wrong name or value with a message naming it.
 */
function optionsOf(op: string, params: Record<string, unknown>): OpOptions[OpName] {
  const renamed = coreNames[op as OpName] ?? {};
  const packageName = new Map(Object.entries(renamed).map(([name, core]) => [core, name]));
  return Object.fromEntries(Object.entries(params).map(([name, value]) => [packageName.get(name) ?? name, value])) as OpOptions[OpName];
}

function outputOf(update: MeshUpdate): RunOutput {
  const output: RunOutput = { scalars: update.attributes, stats: update.stats };
  if (update.positions) output.positions = update.positions;
  if (update.colors) output.colors = update.colors;
  return output;
}
