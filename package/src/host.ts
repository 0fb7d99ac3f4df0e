// The part of the worker both platforms share (worker.ts in browsers, node-worker.ts under Node):
// wait for the page's `init`, start the module flavour it asks for, then hand every request to the
// Engine. The platform supplies only how a flavour's files are found and loaded.

import { Engine } from './engine.js';
import type { ModuleFactory, ModuleOptions } from './module.js';
import { ModuleApi } from './module-api.js';
import { isRequest, type Init, type Response } from './protocol.js';

export type FlavourName = 'geoshift_web' | 'geoshift_web_mt';

export interface Host {
  post(message: Response, transfer?: ArrayBuffer[]): void;
  /** The flavour's factory and the module options this platform needs to find its files. */
  load(name: FlavourName, init: Init): Promise<{ factory: ModuleFactory; options: ModuleOptions }>;
}

const PAGE = 65536;
const INITIAL_HEAP_MB = 64; // -sINITIAL_MEMORY in wasm/CMakeLists.txt

/** The worker's message handler: `init` first, requests after (queued until the module is ready). */
export function serve(host: Host): (data: unknown) => void {
  let engine: Engine | null = null;
  const queued: unknown[] = [];

  const receive = (data: unknown): void => {
    if (!engine) {
      queued.push(data);
      return;
    }
    if (isRequest(data)) engine.handle(data);
    else console.error('geoshift worker: ignored a message that is not a request', data);
  };

  const start = async (init: Init): Promise<void> => {
    const name: FlavourName = init.threaded ? 'geoshift_web_mt' : 'geoshift_web';
    try {
      const { factory, options } = await host.load(name, init);
      if (init.threaded) options.pthreadPoolSize = init.threads;
      else if (init.maxMemoryMB > 0) {
        // A heap that may grow this far and no more, so that a mesh too large for it fails as it
        // would on a device with less memory (the single-threaded flavour imports its memory).
        const maximum = Math.max(INITIAL_HEAP_MB, Math.floor(init.maxMemoryMB));
        options.wasmMemory = new WebAssembly.Memory({ initial: (INITIAL_HEAP_MB << 20) / PAGE, maximum: (maximum << 20) / PAGE });
      }
      const api = new ModuleApi(await factory(options));
      const flag = init.threaded && init.cancelFlag ? new Int32Array(init.cancelFlag) : undefined;
      engine = new Engine(api, (message, transfer) => host.post(message, transfer), flag ? { cancelFlag: flag } : {});
      host.post({ type: 'ready', threaded: init.threaded, threads: init.threaded ? init.threads : 1, ops: api.ops(), presets: api.presets() });
      for (const message of queued.splice(0)) receive(message);
    } catch (e) {
      host.post({ type: 'fatal', message: `the WebAssembly module ${name} could not start (${e instanceof Error ? e.message : String(e)})` });
    }
  };

  return (data: unknown) => {
    if ((data as { type?: unknown } | null)?.type === 'init') void start(data as Init);
    else receive(data);
  };
}
