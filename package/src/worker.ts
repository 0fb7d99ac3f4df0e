// The browser worker: finds the module's files beside this script (bundlers see the
// `new URL('./wasm/...', import.meta.url)` literals and copy the files), or where the page's
// locateFile said, and serves requests (host.ts). Started by client.ts as a module worker.

import type { ModuleFactory, ModuleOptions } from './module.js';
import { serve, type FlavourName } from './host.js';
import pthreadSource from './pthread-worker.js';
import type { Init, Response } from './protocol.js';

// The DOM library is what the package compiles with; this is the part of the worker scope used.
interface WorkerScope {
  postMessage(message: unknown, transfer: Transferable[]): void;
  onmessage: ((event: MessageEvent) => void) | null;
}
const scope = self as unknown as WorkerScope;

function beside(name: string): string | undefined {
  // One literal per file: bundlers only follow `new URL` with a literal path.
  switch (name) {
    case 'geoshift_web.js':
      return new URL('./wasm/geoshift_web.js', import.meta.url).href;
    case 'geoshift_web.wasm':
      return new URL('./wasm/geoshift_web.wasm', import.meta.url).href;
    case 'geoshift_web_mt.js':
      return new URL('./wasm/geoshift_web_mt.js', import.meta.url).href;
    case 'geoshift_web_mt.wasm':
      return new URL('./wasm/geoshift_web_mt.wasm', import.meta.url).href;
    default:
      return undefined;
  }
}

async function load(name: FlavourName, init: Init): Promise<{ factory: ModuleFactory; options: ModuleOptions }> {
  const url = (file: string): string => init.files[file] ?? beside(file) ?? file;
  if (init.threaded) {
    // std::thread::hardware_concurrency() reads navigator.hardwareConcurrency, and a core call asked
    // for "all cores" would start that many threads; beyond the pool one would never start while
    // the caller blocks. Reporting the pool's size keeps the two equal.
    Object.defineProperty(navigator, 'hardwareConcurrency', { value: init.threads, configurable: true });
  }
  const js = url(`${name}.js`);
  const factory = ((await import(/* @vite-ignore */ /* webpackIgnore: true */ js)) as { default: ModuleFactory }).default;
  const options: ModuleOptions = { locateFile: (file: string) => url(file) };
  if (init.threaded) {
    // The pthread workers import the module script themselves; they need its URL, not this file's.
    options.mainScriptUrlOrBlob = js;
    // Their own script (3 KB) is started from a blob: a bundler would inline a file that small as
    // a data: URL (Vite below 4 KB), whose worker has an opaque origin and cannot share the
    // memory, and Vite's dev server would rewrite its dynamic import() for modules, which a
    // classic worker script cannot hold.
    const pthread = URL.createObjectURL(new Blob([pthreadSource], { type: 'text/javascript' }));
    options.locateFile = (file: string) => (file.endsWith('.worker.js') ? pthread : url(file));
  }
  return { factory, options };
}

scope.onmessage = ((handler) => (event: MessageEvent) => handler(event.data))(
  serve({ post: (message: Response, transfer: ArrayBuffer[] = []) => scope.postMessage(message, transfer), load }),
);
