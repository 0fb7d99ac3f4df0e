// The worker's logic (web/src/worker/engine.ts) driven in Node with the Node build of the module:
// requests in, messages out, as the page would see them. The TypeScript files are transpiled on the
// fly with the project's own `typescript`, so the test runs the app's very source.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import ts from 'typescript';

import { loadGeoshift, repoRoot, saddle } from './support.mjs';

let Engine;
let GeoshiftApi;
let isRequest;
let module;

before(async () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'geoshift-engine-'));
  const src = path.join(repoRoot, 'web/src/worker');
  for (const name of ['engine', 'wasm-api', 'protocol']) {
    const { outputText } = ts.transpileModule(fs.readFileSync(path.join(src, `${name}.ts`), 'utf8'), {
      compilerOptions: { module: ts.ModuleKind.ESNext, target: ts.ScriptTarget.ES2022, verbatimModuleSyntax: true },
    });
    // Relative imports of the sources have no extension (Vite resolves them); Node needs one.
    fs.writeFileSync(path.join(dir, `${name}.mjs`), outputText.replace(/from '(\.\/[\w-]+)'/g, "from '$1.mjs'"));
  }
  const load = async (name) => import(pathToFileURL(path.join(dir, `${name}.mjs`)).href);
  ({ Engine } = await load('engine'));
  ({ GeoshiftApi } = await load('wasm-api'));
  ({ isRequest } = await load('protocol'));
  module = await loadGeoshift();
});

/** An engine whose posts land in an array, with a fake clock that advances 10 ms per reading. */
function engineWith(options = {}) {
  const posted = [];
  let t = 0;
  const engine = new Engine(new GeoshiftApi(module), (message, transfer) => posted.push({ message, transfer }), {
    now: () => (t += 10),
    ...options,
  });
  return { engine, posted, messages: () => posted.map((p) => p.message) };
}

function loadRequest(id, meshId = 'm') {
  const { positions, indices } = saddle(12);
  return { type: 'load', id, meshId, positions, indices };
}

test('load then run: one result per request, buffers transferred, progress with stages', () => {
  const { engine, posted, messages } = engineWith();
  const load = loadRequest(1);
  assert.ok(isRequest(load));
  engine.handle(load);
  assert.equal(messages()[0].type, 'result');
  assert.equal(messages()[0].kind, 'load');
  assert.equal(messages()[0].info.vertexCount, 13 * 13);

  engine.handle({ type: 'run', id: 2, meshId: 'm', op: 'smooth', params: { iterations: 30 } });
  const progress = messages().filter((m) => m.type === 'progress');
  const result = posted.at(-1);
  assert.equal(result.message.type, 'result');
  assert.equal(result.message.id, 2);
  assert.equal(result.message.kind, 'run');
  assert.ok(result.message.output.positions instanceof Float32Array);
  assert.ok(result.transfer.includes(result.message.output.positions.buffer), 'the positions are not transferred');
  assert.ok(progress.length >= 2, `only ${progress.length} progress messages`);
  assert.ok(progress.every((m) => m.id === 2 && typeof m.stage === 'string' && m.fraction >= 0 && m.fraction <= 1));
});

test('progress is throttled to the interval but never drops a stage change', () => {
  const { engine, messages } = engineWith({ progressInterval: 35 });  // the fake clock ticks 10 ms
  engine.handle(loadRequest(1));
  engine.handle({ type: 'run', id: 2, meshId: 'm', op: 'smooth', params: { iterations: 40 } });
  const progress = messages().filter((m) => m.type === 'progress');
  const stages = new Set(progress.map((m) => m.stage));
  assert.ok(stages.has('copying results'), `stages seen: ${[...stages]}`);
  // 40 iterations + a final stage at one reading per step: far fewer messages than steps.
  assert.ok(progress.length < 25, `${progress.length} progress messages: not throttled`);
});

test('errors come back as typed error messages and the engine stays usable', () => {
  const { engine, messages } = engineWith();
  engine.handle({ type: 'run', id: 1, meshId: 'nothing', op: 'smooth', params: {} });
  assert.deepEqual(messages()[0], { type: 'error', id: 1, kind: 'input', message: 'mesh "nothing" was not loaded into the worker' });

  engine.handle({ ...loadRequest(2), indices: new Uint32Array([0, 1, 500]) });
  assert.equal(messages()[1].type, 'error');
  assert.equal(messages()[1].kind, 'input');
  assert.match(messages()[1].message, /face 0/);

  engine.handle(loadRequest(3));
  engine.handle({ type: 'run', id: 4, meshId: 'm', op: 'smooth', params: { bogus: 1 } });
  assert.equal(messages().at(-1).type, 'error');
  assert.match(messages().at(-1).message, /unknown parameter "bogus"/);
  engine.handle({ type: 'run', id: 5, meshId: 'm', op: 'curvature', params: {} });
  assert.equal(messages().at(-1).type, 'result');
  assert.ok(messages().at(-1).output.scalars._CURVATURE instanceof Float32Array);
});

test('a shared cancel flag holding the run id stops that run only', () => {
  const flag = new Int32Array(new SharedArrayBuffer(4));
  const { engine, messages } = engineWith({ cancelFlag: flag });
  engine.handle(loadRequest(1));
  Atomics.store(flag, 0, 2);
  engine.handle({ type: 'run', id: 2, meshId: 'm', op: 'smooth', params: { iterations: 100000 } });
  assert.deepEqual(messages().at(-1), { type: 'error', id: 2, kind: 'cancelled', message: 'cancelled' });
  // The cancel message itself reaches the worker only after the run; it is answered, nothing more.
  engine.handle({ type: 'cancel', id: 9, runId: 2 });
  assert.deepEqual(messages().at(-1), { type: 'result', id: 9, kind: 'cancel' });
  // A later run with another id is not affected by the stale flag.
  engine.handle({ type: 'run', id: 3, meshId: 'm', op: 'smooth', params: { iterations: 2 } });
  assert.equal(messages().at(-1).type, 'result');
});

test('requests are checked at run time', () => {
  assert.equal(isRequest({ type: 'load', id: 1, meshId: 'm', positions: [0, 0, 0], indices: new Uint32Array(3) }), false);
  assert.equal(isRequest({ type: 'run', id: 1, meshId: 'm', op: 'smooth' }), false);
  assert.equal(isRequest({ type: 'explode', id: 1 }), false);
  assert.equal(isRequest(null), false);
  assert.equal(isRequest({ type: 'cancel', id: 4, runId: 3 }), true);
  assert.equal(isRequest({ type: 'cancel', id: 4 }), false);
});

test('with the threaded module, the shared flag cancels too and results match the single-threaded engine', async () => {
  const threaded = await loadGeoshift({ threads: true });
  try {
    const flag = new Int32Array(new SharedArrayBuffer(4));
    const runs = [module, threaded].map((m) => {
      const posted = [];
      const engine = new Engine(new GeoshiftApi(m), (message) => posted.push(message), { cancelFlag: flag });
      engine.handle(loadRequest(1));
      engine.handle({ type: 'run', id: 2, meshId: 'm', op: 'smooth', params: { iterations: 6, weights: 'cotangent' } });
      Atomics.store(flag, 0, 3);
      engine.handle({ type: 'run', id: 3, meshId: 'm', op: 'smooth', params: { iterations: 100000 } });
      Atomics.store(flag, 0, 0);
      return posted;
    });
    for (const posted of runs) assert.deepEqual(posted.at(-1), { type: 'error', id: 3, kind: 'cancelled', message: 'cancelled' });
    const result = (posted) => posted.find((m) => m.type === 'result' && m.id === 2).output.positions;
    assert.deepEqual(result(runs[1]), result(runs[0]));
  } finally {
    threaded.close();
  }
});

test('read: the core\'s counts for a good file, the CLI\'s message (kind input) for a damaged one', () => {
  const { engine, messages } = engineWith();
  const obj = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n';
  const good = { type: 'read', id: 1, fileName: 'quad.obj', bytes: new TextEncoder().encode(obj) };
  assert.ok(isRequest(good));
  engine.handle(good);
  const bad = { type: 'read', id: 2, fileName: 'quad.obj', bytes: new TextEncoder().encode(obj.replace('f 2 4 3', 'f 2 5 3')) };
  engine.handle(bad);
  assert.ok(!isRequest({ type: 'read', id: 3, fileName: 'x.obj', bytes: [1, 2] }), 'bytes must be a Uint8Array');
  const [r1, r2] = messages();
  assert.equal(r1.type, 'result');
  assert.equal(r1.kind, 'read');
  assert.equal(r1.info.vertices, 4);
  assert.equal(r1.info.triangles, 2);
  assert.deepEqual(r1.info.parts.map((p) => p.label), ['quad.obj']);
  assert.deepEqual(r2, { type: 'error', id: 2, kind: 'input', message: "quad.obj: face 2 (group '') references vertex 5 but the file has 4 vertices" });
});
