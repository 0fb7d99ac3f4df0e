// The worker's logic (package/src/engine.ts) driven in Node with the Node build of the module:
// requests in, messages out, as the page would see them. The TypeScript files are transpiled on the
// fly with the project's own `typescript`, so the test runs the package's very source.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import ts from 'typescript';

import { loadGeoshift, repoRoot, saddle, scratchDir } from './support.mjs';

let Engine;
let ModuleApi;
let isRequest;
let module;

before(async () => {
  const dir = scratchDir('geoshift-engine-');
  const src = path.join(repoRoot, 'package/src');
  fs.writeFileSync(path.join(dir, 'package.json'), '{ "type": "module" }\n');
  for (const name of ['engine', 'module-api', 'protocol', 'errors']) {
    const { outputText } = ts.transpileModule(fs.readFileSync(path.join(src, `${name}.ts`), 'utf8'), {
      compilerOptions: { module: ts.ModuleKind.ESNext, target: ts.ScriptTarget.ES2022, verbatimModuleSyntax: true },
    });
    fs.writeFileSync(path.join(dir, `${name}.js`), outputText);
  }
  const load = async (name) => import(pathToFileURL(path.join(dir, `${name}.js`)).href);
  ({ Engine } = await load('engine'));
  ({ ModuleApi } = await load('module-api'));
  ({ isRequest } = await load('protocol'));
  module = await loadGeoshift();
});

/** An engine whose posts land in an array, with a fake clock that advances 10 ms per reading. */
function engineWith(options = {}) {
  const posted = [];
  let t = 0;
  const engine = new Engine(new ModuleApi(module), (message, transfer) => posted.push({ message, transfer }), {
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
  assert.ok(messages().at(-1).output.attributes._CURVATURE instanceof Float32Array);
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
      const engine = new Engine(new ModuleApi(m), (message) => posted.push(message), { cancelFlag: flag });
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

test('read: the core\'s counts and arrays for a good file, the CLI\'s message (kind input) for a damaged one', () => {
  const { engine, posted, messages } = engineWith();
  const obj = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n';
  const good = { type: 'read', id: 1, fileName: 'quad.obj', bytes: new TextEncoder().encode(obj), maxVertices: 0, arrays: true };
  assert.ok(isRequest(good));
  engine.handle(good);
  const bad = { type: 'read', id: 2, fileName: 'quad.obj', bytes: new TextEncoder().encode(obj.replace('f 2 4 3', 'f 2 5 3')), maxVertices: 0, arrays: false };
  engine.handle(bad);
  engine.handle({ type: 'read', id: 3, fileName: 'quad.obj', bytes: new TextEncoder().encode(obj), maxVertices: 3, arrays: false });
  assert.ok(!isRequest({ type: 'read', id: 4, fileName: 'x.obj', bytes: [1, 2], maxVertices: 0, arrays: false }), 'bytes must be a Uint8Array');
  const [r1, r2, r3] = messages();
  assert.equal(r1.type, 'result');
  assert.equal(r1.kind, 'read');
  assert.equal(r1.info.vertices, 4);
  assert.equal(r1.info.triangles, 2);
  const [part] = r1.info.parts;
  assert.equal(part.label, 'quad.obj');
  assert.deepEqual([...part.positions], [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0]);
  assert.deepEqual([...part.indices], [0, 1, 2, 1, 3, 2]);
  assert.deepEqual([...part.transforms], [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
  assert.ok(posted[0].transfer.includes(part.positions.buffer), 'the arrays are not transferred');
  assert.deepEqual(r2, { type: 'error', id: 2, kind: 'input', message: "quad.obj: face 2 (group '') references vertex 5 but the file has 4 vertices" });
  assert.equal(r3.type, 'error');
  assert.match(r3.message, /quad\.obj.*4 vertices.*3/, 'maxVertices is passed to the readers');
});

test('a job loads, runs and forgets in one request, and always answers with positions', () => {
  const { engine, posted, messages } = engineWith();
  const { positions, indices } = saddle(12);
  engine.handle({ type: 'job', id: 1, op: 'curvature', params: { kind: 'mean' }, positions: positions.slice(), indices });
  const curvature = posted.at(-1);
  assert.equal(curvature.message.kind, 'job');
  assert.deepEqual(curvature.message.output.positions, positions, 'an op that keeps the positions answers with the input\'s');
  assert.ok(curvature.message.output.attributes._CURVATURE instanceof Float32Array);
  assert.equal(curvature.message.output.report.inputVertices, 13 * 13);
  engine.handle({ type: 'job', id: 2, op: 'smooth', params: { iterations: 3 }, positions: positions.slice(), indices });
  const smooth = posted.at(-1).message.output.positions;
  assert.notDeepEqual(smooth, positions);
  // Nothing stays loaded: the same run through load + run gives the same numbers.
  engine.handle({ type: 'load', id: 3, meshId: 'm', positions: positions.slice(), indices });
  engine.handle({ type: 'run', id: 4, meshId: 'm', op: 'smooth', params: { iterations: 3 } });
  assert.deepEqual(messages().at(-1).output.positions, smooth);
  engine.handle({ type: 'job', id: 5, op: 'smooth', params: { iterations: 3, bogus: 1 }, positions: positions.slice(), indices });
  assert.equal(messages().at(-1).type, 'error');
  assert.match(messages().at(-1).message, /unknown parameter "bogus"/);
});
