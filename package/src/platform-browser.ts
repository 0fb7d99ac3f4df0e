// Browsers (and bundlers): the worker is a module worker beside this file, written the way Vite and
// webpack recognise and bundle (`new Worker(new URL('./worker.js', import.meta.url), ...)`).

import type { Platform } from './geoshift.js';

export const browser: Platform = {
  sharedMemory: () => typeof SharedArrayBuffer !== 'undefined' && globalThis.crossOriginIsolated === true,
  cores: () => (typeof navigator === 'object' && navigator.hardwareConcurrency) || 4,
  noThreads:
    'threads need a cross-origin-isolated page (served with Cross-Origin-Opener-Policy: same-origin and Cross-Origin-Embedder-Policy: require-corp); running on one thread',
  spawn(events) {
    let worker: Worker;
    try {
      worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    } catch (error) {
      // The package was imported from another origin (a CDN): a worker must be same-origin, but it
      // may import a module from anywhere, and then finds the wasm files beside that module.
      if (!(error instanceof DOMException && error.name === 'SecurityError')) throw error;
      // Not the literal pattern again, or bundlers would copy worker.js a second time, unbundled.
      const base = import.meta.url;
      const source = `import ${JSON.stringify(new URL('./worker.js', base).href)};`;
      worker = new Worker(URL.createObjectURL(new Blob([source], { type: 'text/javascript' })), { type: 'module' });
    }
    worker.onmessage = (event: MessageEvent) => events.message(event.data);
    worker.onerror = (event: ErrorEvent) => {
      event.preventDefault();
      events.error(event.message);
    };
    return {
      postMessage: (message, transfer = []) => worker.postMessage(message, transfer),
      terminate: () => worker.terminate(),
    };
  },
};
