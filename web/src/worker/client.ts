// The page's side of the worker: request ids, promises, progress callbacks, and cancel.
//
// Cancel: with the threaded build the page shares an Int32 flag with the worker and stores the id
// of the run to stop; the module sees it at its next progress step (~100 ms) and the run fails as
// cancelled. Without cross-origin isolation there is no shared memory, so the page terminates the
// worker and starts a new one; the run fails as cancelled at once. The page is the keeper of the
// meshes (it loads the current geometry before each run), so a new worker loses nothing.

import type { CorePreset } from '../../../wasm/geoshift';
import type { ErrorKind, LoadInfo, MeshArrays, ReadInfo, Request, Response, RunOutput } from './protocol';
import { isResponse, transferables } from './protocol';
import { GeoshiftError } from './wasm-api';

export { GeoshiftError };

export interface WorkerInfo {
  threaded: boolean;
  threads: number;
  ops: string[];
  /** The core's filter presets, whose values the panel shows. */
  presets: CorePreset[];
}

export type ProgressListener = (fraction: number, stage: string) => void;

interface Pending {
  resolve: (value: Response) => void;
  reject: (error: Error) => void;
  onProgress?: ProgressListener;
}

type Build = 'auto' | 'single' | 'threaded';

/** How long a threaded run may take to notice the cancel flag before its worker is replaced. */
const CANCEL_GRACE_MS = 350;

// Without an explicit request payload type per message, `Omit` over the union keeps each member.
type RequestBody = Request extends infer R ? (R extends { id: number } ? Omit<R, 'id'> : never) : never;

export class WorkerClient {
  private worker!: Worker;
  private nextId = 1;
  private readonly pending = new Map<number, Pending>();
  private readonly cancelFlag: Int32Array | null;
  private started!: Promise<WorkerInfo>;
  private runningId = 0;
  private readonly previewIds = new Set<number>();
  private threaded = false;

  constructor(
    private readonly wasmBase: string,
    private readonly build: Build = 'auto',
    /** The single-threaded build's heap limit in MB (?heap=, main.ts); default: wasm32's 4 GB. */
    private readonly heapMB?: number,
  ) {
    this.cancelFlag = typeof SharedArrayBuffer !== 'undefined' && crossOriginIsolated ? new Int32Array(new SharedArrayBuffer(4)) : null;
    this.spawn();
  }

  /** Resolves with what the worker runs once its module is ready; rejects if it cannot start. */
  ready(): Promise<WorkerInfo> {
    return this.started;
  }

  /**
   * Reads a file with the core's readers (a copy of the bytes is transferred; the caller keeps its
   * own). Rejects with a GeoshiftError of kind 'input' (the CLI's message) or 'memory'.
   */
  async read(fileName: string, bytes: ArrayBuffer): Promise<ReadInfo> {
    const copy = new Uint8Array(bytes.slice(0));
    const response = await this.request({ type: 'read', fileName, bytes: copy }, () => [copy.buffer]);
    return (response as Extract<Response, { kind: 'read' }>).info;
  }

  /**
   * Replaces the worker by a fresh one (its heap, grown by a file that did not fit, is released);
   * whatever was pending fails as cancelled. The page reloads meshes before each run.
   */
  restart(): void {
    this.respawn();
  }

  /** Copies the mesh into the worker (copies of the arrays are transferred; the caller keeps its own). */
  async load(meshId: string, mesh: MeshArrays): Promise<LoadInfo> {
    const response = await this.request({ type: 'load', meshId, ...copyMesh(mesh) }, transferablesOf);
    return (response as Extract<Response, { kind: 'load' }>).info;
  }

  async free(meshId: string): Promise<void> {
    await this.request({ type: 'free', meshId });
  }

  async run(meshId: string, op: string, params: Record<string, unknown>, onProgress?: ProgressListener): Promise<RunOutput> {
    const response = await this.request({ type: 'run', meshId, op, params }, () => [], onProgress);
    return (response as Extract<Response, { kind: 'run' }>).output;
  }

  /** The op on a coarse level of a loaded mesh (live preview); the worker's mesh is not changed. */
  async preview(meshId: string, op: string, params: Record<string, unknown>, maxVertices: number): Promise<RunOutput> {
    const response = await this.request({ type: 'preview', meshId, op, params, maxVertices });
    return (response as Extract<Response, { kind: 'run' }>).output;
  }

  /**
   * Asks a running preview to stop, through the shared flag only (threaded build): the worker and
   * the coarse level it keeps stay. Without the flag the preview finishes and its caller drops it.
   */
  stopPreview(): void {
    const id = this.runningId;
    if (!id || !this.pending.has(id) || !this.previewIds.has(id) || !this.cancelFlag || !this.threaded) return;
    Atomics.store(this.cancelFlag, 0, id);
  }

  /** Stops the current run, if any; its promise rejects with a GeoshiftError of kind 'cancelled'. */
  cancel(): void {
    const id = this.runningId;
    if (!id || !this.pending.has(id)) return;
    if (this.cancelFlag && this.threaded) {
      Atomics.store(this.cancelFlag, 0, id);
      this.worker.postMessage({ type: 'cancel', id: this.nextId++, runId: id } satisfies Request);
      // An op that does not report progress for a while cannot see the flag: do not wait for it.
      setTimeout(() => {
        if (this.pending.has(id)) this.respawn();
      }, CANCEL_GRACE_MS);
      return;
    }
    this.respawn();
  }

  private respawn(): void {
    this.worker.terminate();
    this.failAll(new GeoshiftError('cancelled', 'cancelled'));
    this.spawn();
  }

  dispose(): void {
    this.worker.terminate();
    this.failAll(new GeoshiftError('the worker was closed', 'internal'));
  }

  private spawn(): void {
    this.worker = new Worker(new URL('./geoshift.worker.ts', import.meta.url), { type: 'module' });
    let settle!: { resolve: (info: WorkerInfo) => void; reject: (e: Error) => void };
    this.started = new Promise<WorkerInfo>((resolve, reject) => (settle = { resolve, reject }));
    // A start failure is reported to whoever awaits ready(); nobody else needs an unhandled rejection.
    this.started.catch(() => undefined);
    this.worker.onmessage = (event: MessageEvent) => {
      const message: unknown = event.data;
      if (!isResponse(message)) return;
      if (message.type === 'ready') {
        this.threaded = message.threaded;
        settle.resolve({ threaded: message.threaded, threads: message.threads, ops: message.ops, presets: message.presets });
      } else if (message.type === 'fatal') {
        const error = new GeoshiftError(message.message, 'internal');
        settle.reject(error);
        this.failAll(error);
      } else {
        this.receive(message);
      }
    };
    this.worker.onerror = (event) => {
      const error = new GeoshiftError(`the worker failed: ${event.message || 'unknown error'}`, 'internal');
      settle.reject(error);
      this.failAll(error);
    };
    this.worker.postMessage({
      type: 'init',
      wasmBase: this.wasmBase,
      build: this.build,
      ...(this.heapMB ? { heapMB: this.heapMB } : {}),
      ...(this.cancelFlag ? { cancelFlag: this.cancelFlag.buffer } : {}),
    });
  }

  private receive(message: Exclude<Response, { type: 'ready' | 'fatal' }>): void {
    const pending = this.pending.get(message.id);
    if (!pending) return;
    if (message.type === 'progress') {
      pending.onProgress?.(message.fraction, message.stage);
      return;
    }
    this.pending.delete(message.id);
    this.previewIds.delete(message.id);
    if (message.id === this.runningId) this.runningId = 0;
    if (message.type === 'error') pending.reject(new GeoshiftError(message.message, message.kind as ErrorKind));
    else pending.resolve(message);
  }

  private async request(body: RequestBody, transfer: (r: Request) => ArrayBuffer[] = () => [], onProgress?: ProgressListener): Promise<Response> {
    await this.started;
    const id = this.nextId++;
    const request = { ...body, id } as Request;
    if (request.type === 'run' || request.type === 'preview') this.runningId = id;
    if (request.type === 'preview') this.previewIds.add(id);
    return new Promise<Response>((resolve, reject) => {
      this.pending.set(id, onProgress ? { resolve, reject, onProgress } : { resolve, reject });
      this.worker.postMessage(request, transfer(request));
    });
  }

  private failAll(error: Error): void {
    const all = [...this.pending.values()];
    this.pending.clear();
    this.previewIds.clear();
    this.runningId = 0;
    for (const p of all) p.reject(error);
  }
}

function copyMesh(mesh: MeshArrays): MeshArrays {
  const copy: MeshArrays = { positions: mesh.positions.slice(), indices: mesh.indices.slice() };
  if (mesh.colors) copy.colors = mesh.colors.slice();
  if (mesh.normals) copy.normals = mesh.normals.slice();
  if (mesh.scalars) copy.scalars = Object.fromEntries(Object.entries(mesh.scalars).map(([k, v]) => [k, v.slice()]));
  return copy;
}

function transferablesOf(request: Request): ArrayBuffer[] {
  if (request.type !== 'load') return [];
  return transferables([request.positions, request.indices, request.colors, request.normals, ...Object.values(request.scalars ?? {})]);
}
