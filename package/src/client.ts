// The page's side of the worker: request ids, one request in the worker at a time (it runs them one
// after another anyway, and a queue kept here lets a queued call be cancelled without the worker),
// progress listeners, cancel, and replacing the worker. docs/architecture.md#worker-protocol.
//
// Cancel: with the threaded build the page shares an Int32 flag with the worker and stores the id
// of the run to stop; the module sees it at its next progress step (~100 ms) and the run fails as
// cancelled. Without shared memory the page terminates the worker and starts a new one; the run
// fails as cancelled at once. A replaced worker has lost its kept meshes: calls on them fail with
// a message saying so (the caller loads the mesh again).

import { GeoshiftError } from './errors.js';
import { isResponse, type Init, type Request, type Response } from './protocol.js';
import type { CorePreset } from './reports.js';

/** A started worker, whatever the platform (platform-browser.ts, platform-node.ts). */
export interface WorkerPort {
  postMessage(message: unknown, transfer?: Transferable[]): void;
  terminate(): void;
  /** Node: keep the process alive only while a call is pending. */
  busy?(busy: boolean): void;
}

export interface WorkerEvents {
  message(data: unknown): void;
  /** The worker failed outside any request (a script that does not load, a crash). */
  error(message: string): void;
}

export type Spawn = (events: WorkerEvents) => WorkerPort;

export interface Ready {
  threaded: boolean;
  threads: number;
  ops: string[];
  presets: CorePreset[];
}

/** How long a threaded run may take to notice the cancel flag before its worker is replaced. */
const CANCEL_GRACE_MS = 350;

// Without a request payload type per message, `Omit` over the union keeps each member.
export type RequestBody = Request extends infer R ? (R extends { id: number } ? Omit<R, 'id'> : never) : never;

export interface RequestOptions {
  transfer?: ArrayBuffer[];
  onProgress?: ((fraction: number, stage: string) => void) | undefined;
  signal?: AbortSignal | undefined;
  /**
   * A preview: its signal only raises the shared flag (threaded build) and never replaces the
   * worker, which keeps the coarse level it analysed; without the flag the preview finishes and
   * its promise then rejects as cancelled.
   */
  soft?: boolean;
  /** The worker generation the request's mesh lives in; a request for an older one fails at once. */
  generation?: number;
}

interface Job {
  body: RequestBody;
  options: RequestOptions;
  resolve: (value: Response) => void;
  reject: (error: Error) => void;
  id: number;
  /** Aborted while in the worker without a way to stop it (soft, single-threaded): reject on arrival. */
  abandoned: boolean;
  unlisten: () => void;
}

export class Client {
  private worker!: WorkerPort;
  private nextId = 1;
  private readonly queue: Job[] = [];
  private running: Job | null = null;
  private readonly cancelFlag: Int32Array | null;
  private started!: Promise<Ready>;
  private closed: GeoshiftError | null = null;
  /** Counts workers: a mesh kept by one is gone with it. */
  generation = 0;

  constructor(
    private readonly spawnWorker: Spawn,
    private readonly init: Omit<Init, 'type' | 'cancelFlag'>,
  ) {
    this.cancelFlag = init.threaded ? new Int32Array(new SharedArrayBuffer(4)) : null;
    this.spawn();
  }

  /** Resolves with what the worker runs once its module is ready; rejects if it cannot start. */
  ready(): Promise<Ready> {
    return this.started;
  }

  /** Sends a request when the worker is free; resolves with its result message. */
  request(body: RequestBody, options: RequestOptions = {}): Promise<Response> {
    if (this.closed) return Promise.reject(this.closed);
    if (options.signal?.aborted) return Promise.reject(new GeoshiftError('cancelled', 'cancelled'));
    return new Promise<Response>((resolve, reject) => {
      const job: Job = { body, options, resolve, reject, id: this.nextId++, abandoned: false, unlisten: () => undefined };
      if (options.signal) {
        const signal = options.signal;
        const onAbort = () => this.abort(job);
        signal.addEventListener('abort', onAbort, { once: true });
        job.unlisten = () => signal.removeEventListener('abort', onAbort);
      }
      this.queue.push(job);
      this.pump();
    });
  }

  /** Ends the worker; pending and later calls fail as cancelled. */
  terminate(): void {
    if (this.closed) return;
    this.closed = new GeoshiftError('the geoshift worker was terminated', 'cancelled');
    this.worker.terminate();
    const jobs = [...(this.running ? [this.running] : []), ...this.queue.splice(0)];
    this.running = null;
    for (const job of jobs) this.settle(job, this.closed);
  }

  private async pump(): Promise<void> {
    if (this.running || this.closed) return;
    const job = this.queue.shift();
    if (!job) {
      this.worker.busy?.(false);
      return;
    }
    this.worker.busy?.(true);
    this.running = job;
    try {
      await this.started;
    } catch (error) {
      this.running = null;
      this.settle(job, error as Error);
      void this.pump();
      return;
    }
    if (this.running !== job) return; // aborted or terminated while the worker started
    if (job.options.generation !== undefined && job.options.generation !== this.generation) {
      this.running = null;
      this.settle(job, new GeoshiftError('the mesh was loaded into a worker that has since been replaced (after a cancel or an error); load it again', 'input'));
      void this.pump();
      return;
    }
    if (this.cancelFlag) Atomics.store(this.cancelFlag, 0, 0);
    this.worker.postMessage({ ...job.body, id: job.id }, job.options.transfer ?? []);
  }

  private abort(job: Job): void {
    const queued = this.queue.indexOf(job);
    if (queued >= 0) {
      this.queue.splice(queued, 1);
      this.settle(job, new GeoshiftError('cancelled', 'cancelled'));
      return;
    }
    if (this.running !== job) return;
    if (this.cancelFlag) {
      Atomics.store(this.cancelFlag, 0, job.id);
      if (job.options.soft) return;
      this.worker.postMessage({ type: 'cancel', id: this.nextId++, runId: job.id } satisfies Request);
      // An op that does not report progress for a while cannot see the flag: do not wait for it.
      setTimeout(() => {
        if (this.running === job) this.respawn(new GeoshiftError('cancelled', 'cancelled'));
      }, CANCEL_GRACE_MS);
      return;
    }
    if (job.options.soft) {
      job.abandoned = true;
      return;
    }
    this.respawn(new GeoshiftError('cancelled', 'cancelled'));
  }

  /** Replaces the worker; the request in it fails with `error`, the queue goes to the new one. */
  private respawn(error: GeoshiftError): void {
    this.worker.terminate();
    const job = this.running;
    this.running = null;
    if (job) this.settle(job, error);
    this.spawn();
    void this.pump();
  }

  private spawn(): void {
    this.generation++;
    let settle!: { resolve: (info: Ready) => void; reject: (e: Error) => void };
    this.started = new Promise<Ready>((resolve, reject) => (settle = { resolve, reject }));
    // A start failure is reported to whoever awaits ready() or a call; nobody else needs an unhandled rejection.
    this.started.catch(() => undefined);
    const generation = this.generation;
    const current = () => generation === this.generation && !this.closed;
    let up = false;
    this.worker = this.spawnWorker({
      message: (data) => {
        if (!current() || !isResponse(data)) return;
        if (data.type === 'ready') {
          up = true;
          settle.resolve({ threaded: data.threaded, threads: data.threads, ops: data.ops, presets: data.presets });
          // Idle from now on unless a call is queued (Node: the process may exit).
          if (!this.running && this.queue.length === 0) this.worker.busy?.(false);
        } else if (data.type === 'fatal') this.fail(new GeoshiftError(data.message, 'internal'), settle.reject);
        else this.receive(data);
      },
      error: (message) => {
        if (!current()) return;
        const error = new GeoshiftError(`the geoshift worker failed: ${message || 'unknown error'}`, 'internal');
        // Before the module is up nothing would go better the next time; after, a new worker may.
        if (up) this.respawn(error);
        else this.fail(error, settle.reject);
      },
    });
    const init: Init = { type: 'init', ...this.init, ...(this.cancelFlag ? { cancelFlag: this.cancelFlag.buffer as SharedArrayBuffer } : {}) };
    this.worker.postMessage(init);
  }

  /** The module could not start (or the worker died): every call fails with that error from now on. */
  private fail(error: GeoshiftError, rejectStart: (e: Error) => void): void {
    rejectStart(error);
    this.closed = error;
    this.worker.terminate();
    const jobs = [...(this.running ? [this.running] : []), ...this.queue.splice(0)];
    this.running = null;
    for (const job of jobs) this.settle(job, error);
  }

  private receive(message: Exclude<Response, { type: 'ready' | 'fatal' }>): void {
    const job = this.running;
    if (!job || message.id !== job.id) return;
    if (message.type === 'progress') {
      if (!job.abandoned) job.options.onProgress?.(message.fraction, message.stage);
      return;
    }
    this.running = null;
    if (message.type === 'error') {
      const error = new GeoshiftError(message.message, message.kind);
      this.settle(job, error);
      // A heap never shrinks, and an internal error may have left the module broken: start afresh.
      if (message.kind === 'out-of-memory' || message.kind === 'internal') {
        this.respawn(error);
        return;
      }
    } else if (job.abandoned) {
      this.settle(job, new GeoshiftError('cancelled', 'cancelled'));
    } else {
      job.unlisten();
      job.resolve(message);
    }
    void this.pump();
  }

  private settle(job: Job, error: Error): void {
    job.unlisten();
    job.reject(error);
  }
}
