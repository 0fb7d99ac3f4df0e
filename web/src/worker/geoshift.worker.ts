// The worker's onmessage shim: picks the wasm build, starts it, and hands every request to Engine.
// Cross-origin-isolated pages get the threaded build (SharedArrayBuffer available); others the
// single-threaded one, which the page cancels by terminating this worker.

import type { GeoshiftFactory } from '../../../wasm/geoshift';
import { Engine } from './engine';
import { isRequest, type Response } from './protocol';
import { GeoshiftApi } from './wasm-api';

interface Init {
  type: 'init';
  /** Base URL of the wasm files (web/public/wasm). */
  wasmBase: string;
  /** 'auto' follows crossOriginIsolated; the page forces 'single' for comparisons and tests. */
  build: 'auto' | 'single' | 'threaded';
  cancelFlag?: SharedArrayBuffer;
  /**
   * The single-threaded build's heap limit in MB (at least 64, its initial size): the module gets a
   * WebAssembly.Memory that can grow to this much and no more, so that a file too large for it
   * fails as it would on a device with less memory. The threaded build keeps wasm32's 4 GB.
   */
  heapMB?: number;
}

const PAGE = 65536;
const INITIAL_HEAP_MB = 64; // -sINITIAL_MEMORY in wasm/CMakeLists.txt

// The app's tsconfig has the DOM library, not WebWorker; this is the part of the worker scope used.
interface WorkerScope {
  crossOriginIsolated: boolean;
  postMessage(message: unknown, transfer: Transferable[]): void;
  onmessage: ((event: MessageEvent) => void) | null;
}
const scope = self as unknown as WorkerScope;
const post = (message: Response, transfer: ArrayBuffer[] = []): void => scope.postMessage(message, transfer);

let engine: Engine | null = null;
const queued: unknown[] = [];

/** Threads of the threaded build; its pthread pool (wasm/CMakeLists.txt) has the same size. */
const MAX_THREADS = 8;

async function start(init: Init): Promise<void> {
  const threaded = init.build === 'threaded' || (init.build === 'auto' && scope.crossOriginIsolated);
  // std::thread::hardware_concurrency() reads navigator.hardwareConcurrency, and a core call asked
  // for "all cores" would start that many threads; beyond the capped pool one would never start
  // while the caller blocks. Capping what this worker reports keeps the two equal.
  const cores = Math.min(navigator.hardwareConcurrency || 4, MAX_THREADS);
  Object.defineProperty(navigator, 'hardwareConcurrency', { value: cores, configurable: true });
  const name = threaded ? 'geoshift_web_mt' : 'geoshift_web';
  const url = new URL(`${name}.js`, init.wasmBase).href;
  try {
    const factory = (await import(/* @vite-ignore */ url)).default as GeoshiftFactory;
    // The pthread workers load the module script themselves; they need its URL, not this file's.
    const heapMB = init.heapMB ? Math.max(INITIAL_HEAP_MB, Math.floor(init.heapMB)) : 0;
    const options = threaded
      ? { mainScriptUrlOrBlob: url }
      : heapMB
        ? { wasmMemory: new WebAssembly.Memory({ initial: (INITIAL_HEAP_MB << 20) / PAGE, maximum: (heapMB << 20) / PAGE }) }
        : {};
    const module = await factory(options);
    const api = new GeoshiftApi(module);
    const flag = threaded && init.cancelFlag ? new Int32Array(init.cancelFlag) : undefined;
    engine = new Engine(api, post, flag ? { cancelFlag: flag } : {});
    const threads = threaded ? cores : 1;
    post({ type: 'ready', threaded, threads, ops: api.ops(), presets: api.presets() });
    for (const message of queued.splice(0)) receive(message);
  } catch (e) {
    post({ type: 'fatal', message: `the WebAssembly module ${name} could not start (${e instanceof Error ? e.message : String(e)})` });
  }
}

function receive(data: unknown): void {
  if (!engine) {
    queued.push(data);
    return;
  }
  if (isRequest(data)) engine.handle(data);
  else console.error('geoshift worker: ignored a message that is not a request', data);
}

scope.onmessage = (event: MessageEvent) => {
  const data = event.data as { type?: unknown };
  if (data?.type === 'init') void start(data as Init);
  else receive(data);
};
