// The Node worker (a worker_threads thread started by node.ts): loads the same ES6 flavours as
// browsers from the package's wasm/ directory and serves requests (host.ts).
//
// Emscripten 3.1.6's ES6 output takes Node's branch under Node and expects CommonJS there: it calls
// `require` and reads `__dirname` (TOOLCHAIN notes); both are given to it as globals of this
// thread. It cannot fetch() a path, so it gets its .wasm bytes; and its pthread workers, which
// Node starts from the .worker.js with worker_threads, get a CommonJS copy of it (.worker.cjs; in
// this "type": "module" package a .js would load as an ES module and lack `require`).

import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { parentPort } from 'node:worker_threads';

import type { ModuleFactory, ModuleOptions } from './module.js';
import { serve, type FlavourName } from './host.js';
import type { Init, Response } from './protocol.js';

const port = parentPort;
if (!port) throw new Error('geoshift: node-worker.js runs as a worker_threads worker (started by createGeoshift)');

const wasmDir = fileURLToPath(new URL('./wasm/', import.meta.url));

/** A file's path: the caller's locateFile answer (a path or a file: URL) or the package's own. */
function pathOf(init: Init, file: string): string {
  const given = init.files[file];
  if (given !== undefined) return given.startsWith('file:') ? fileURLToPath(given) : given;
  return path.join(wasmDir, file.endsWith('.worker.js') ? file.replace(/\.js$/, '.cjs') : file);
}

async function load(name: FlavourName, init: Init): Promise<{ factory: ModuleFactory; options: ModuleOptions }> {
  const globals = globalThis as { require?: NodeJS.Require; __dirname?: string };
  globals.require ??= createRequire(import.meta.url);
  globals.__dirname ??= wasmDir;
  const js = pathToFileURL(pathOf(init, `${name}.js`)).href;
  const factory = ((await import(js)) as { default: ModuleFactory }).default;
  const options: ModuleOptions = {
    wasmBinary: fs.readFileSync(pathOf(init, `${name}.wasm`)),
    locateFile: (file: string) => pathOf(init, file),
  };
  if (init.threaded) options.mainScriptUrlOrBlob = js;
  return { factory, options };
}

const handler = serve({ post: (message: Response, transfer: ArrayBuffer[] = []) => port.postMessage(message, transfer), load });
port.on('message', handler);
