// What the worker does with each request, as a plain class over the module wrapper: no `self`, no
// onmessage, so Node tests drive it with the Node build of the module
// (tests/wasm/worker-engine.test.mjs).

import { GeoshiftError } from './errors.js';
import type { ModuleApi } from './module-api.js';
import { arraysOf, transferables, type JobOutput, type MeshArrays, type Request, type Response } from './protocol.js';

export type Post = (message: Response, transfer: ArrayBuffer[]) => void;

export interface EngineOptions {
  /**
   * Shared with the page (threaded build): the page stores the id of the run to stop in element 0,
   * and the progress callback, which the module calls from inside the run, sees it at once.
   */
  cancelFlag?: Int32Array;
  /** Progress messages closer together than this are dropped, except on a stage change (ms). */
  progressInterval?: number;
  now?: () => number;
}

export class Engine {
  private readonly handles = new Map<string, number>();
  private readonly interval: number;
  private readonly now: () => number;

  constructor(
    private readonly api: ModuleApi,
    private readonly post: Post,
    private readonly options: EngineOptions = {},
  ) {
    this.interval = options.progressInterval ?? 50;
    this.now = options.now ?? (() => performance.now());
  }

  /** Handles one request; every outcome, including failures, is posted. */
  handle(request: Request): void {
    try {
      this.dispatch(request);
    } catch (e) {
      const error = e instanceof GeoshiftError ? e : new GeoshiftError(`internal error: ${e instanceof Error ? e.message : String(e)}`, 'internal');
      this.post({ type: 'error', id: request.id, kind: error.kind, message: error.message }, []);
    }
  }

  private dispatch(request: Request): void {
    switch (request.type) {
      case 'read': {
        const info = this.api.readFile(request.fileName, request.bytes, request.maxVertices, request.arrays);
        this.post({ type: 'result', id: request.id, kind: 'read', info }, transferables(info.parts.flatMap((p) => [...arraysOf(p), p.transforms])));
        return;
      }
      case 'load': {
        this.forget(request.meshId);
        const { handle, info } = this.api.load(request);
        this.handles.set(request.meshId, handle);
        this.post({ type: 'result', id: request.id, kind: 'load', info }, []);
        return;
      }
      case 'run': {
        const output = this.api.run(this.handleOf(request.meshId), request.op, request.params, this.progressFor(request.id));
        this.post({ type: 'result', id: request.id, kind: 'run', output }, transferables(arraysOf(output)));
        return;
      }
      case 'preview': {
        const output = this.api.preview(this.handleOf(request.meshId), request.op, request.params, request.maxVertices, this.progressFor(request.id));
        this.post({ type: 'result', id: request.id, kind: 'run', output }, transferables(arraysOf(output)));
        return;
      }
      case 'job': {
        const output = this.job(request, request.op, request.params, request.id);
        this.post({ type: 'result', id: request.id, kind: 'job', output }, transferables(arraysOf(output)));
        return;
      }
      case 'free':
        this.forget(request.meshId);
        this.post({ type: 'result', id: request.id, kind: 'free' }, []);
        return;
      case 'cancel':
        // Reaches the worker only between runs (a run blocks it): nothing left to stop.
        this.post({ type: 'result', id: request.id, kind: 'cancel' }, []);
        return;
    }
  }

  /** Load, run, forget. The input's positions (already this worker's copy) stand in when the op keeps them. */
  private job(mesh: MeshArrays, op: string, params: Record<string, unknown>, id: number): JobOutput {
    const { handle, info } = this.api.load(mesh);
    try {
      const output = this.api.run(handle, op, params, this.progressFor(id));
      return { ...output, positions: output.positions ?? mesh.positions, report: info.report };
    } finally {
      this.api.free(handle);
    }
  }

  private handleOf(meshId: string): number {
    const handle = this.handles.get(meshId);
    if (handle === undefined) throw new GeoshiftError(`mesh "${meshId}" was not loaded into the worker`, 'input');
    return handle;
  }

  private forget(meshId: string): void {
    const old = this.handles.get(meshId);
    if (old !== undefined) this.api.free(old);
    this.handles.delete(meshId);
  }

  private progressFor(id: number): (fraction: number, stage: string) => boolean {
    let lastTime = -Infinity;
    let lastStage = '';
    const flag = this.options.cancelFlag;
    return (fraction, stage) => {
      const t = this.now();
      if (stage !== lastStage || t - lastTime >= this.interval) {
        lastTime = t;
        lastStage = stage;
        this.post({ type: 'progress', id, fraction, stage }, []);
      }
      return flag !== undefined && Atomics.load(flag, 0) === id;
    };
  }
}
