// The pthreads flavour loads under Node and gives bit-identical results to the single-threaded
// one: the core's parallel loops must not change any sum's order with the thread count.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';

import { loadGeoshift, readOff, saddle, sphereOff, unweldedCube } from './support.mjs';

let single;
let threaded;
before(async () => {
  single = await loadGeoshift();
  threaded = await loadGeoshift({ threads: true });
});
// Its worker pool would keep the test process alive.
after(() => threaded?.close());

function meshes() {
  const list = [['unwelded cube', unweldedCube()], ['jittered saddle', saddle(40)]];
  if (fs.existsSync(sphereOff)) list.push(['sphere.off', readOff(sphereOff)]);
  return list;
}

test('the threaded module really runs with threads', () => {
  assert.ok(threaded.PThread, 'geoshift_node_mt was built without -pthread');
  assert.ok(threaded.PThread.unusedWorkers.length + threaded.PThread.runningWorkers.length >= 2,
    'the pthread pool did not start');
});

for (const [name, mesh] of meshes()) {
  test(`threaded and single-threaded agree bit for bit: ${name}`, () => {
    // The mesh as loaded, and its curvatures (op "curvature"), from each build.
    const loadAndMeasure = (module) => {
      const { handle, ...loaded } = module.loadMesh(mesh.positions, mesh.indices);
      assert.equal(loaded.ok, true, loaded.error);
      for (const kind of ['mean', 'gauss', 'abs']) {
        const r = module.run(handle, 'curvature', { kind });
        assert.equal(r.ok, true, r.error);
        loaded[kind] = r.scalars._CURVATURE;
      }
      module.freeMesh(handle);
      return loaded;
    };
    const a = loadAndMeasure(single);
    const b = loadAndMeasure(threaded);
    assert.deepStrictEqual(b, a);
    // deepStrictEqual compares float arrays with ===, blind to -0 vs 0 and failing on NaN: compare
    // the bytes as well.
    for (const [key, value] of Object.entries(a)) {
      if (ArrayBuffer.isView(value)) {
        assert.ok(Buffer.from(b[key].buffer).equals(Buffer.from(value.buffer)), `${key} differs in its bits`);
      }
    }
  });
}

// The ops of run(), on kept meshes: same bits from both builds.
const opCases = [
  ['noise', { amount: 0.4, seed: 5 }],
  ['smooth', { iterations: 4, weights: 'cotangent' }],
  ['curvature', { kind: 'gauss' }],
  ['geodesic', { source: 3 }],
];
for (const [op, params] of opCases) {
  test(`threaded and single-threaded run('${op}') agree bit for bit`, () => {
    const mesh = saddle(30);
    const results = [single, threaded].map((m) => {
      const { handle } = m.loadMesh(mesh.positions, mesh.indices);
      const r = m.run(handle, op, params);
      m.freeMesh(handle);
      assert.equal(r.ok, true, r.error);
      return r;
    });
    const arrays = (r) => [r.positions, r.colors, ...Object.values(r.scalars)].filter(Boolean);
    const [a, b] = results.map(arrays);
    assert.equal(a.length, b.length);
    assert.ok(a.length > 0, `${op} returned no arrays`);
    a.forEach((array, i) => assert.ok(Buffer.from(b[i].buffer).equals(Buffer.from(array.buffer)), `${op}: array ${i} differs in its bits`));
    assert.equal(results[0].stats.threadsAvailable, 1);
    assert.ok(results[1].stats.threadsAvailable >= 1);
  });
}

// Taubin smoothing (the smooth op, and the denoise op's method taubin) takes a thread count: one
// thread and the whole pool give the same bits, and the stats say how many ran.
for (const [op, params] of [['smooth', { iterations: 6 }], ['denoise', { method: 'taubin', iterations: 6 }]]) {
  test(`run('${op}') with threads 1 and 0 agree bit for bit on the threaded build`, () => {
    const mesh = saddle(40);
    // A kept mesh takes each op's result: each run on a mesh of its own.
    const [one, all] = [1, 0].map((threads) => {
      const { handle } = threaded.loadMesh(mesh.positions, mesh.indices);
      const r = threaded.run(handle, op, { ...params, threads });
      threaded.freeMesh(handle);
      return r;
    });
    assert.equal(one.ok, true, one.error);
    assert.equal(all.ok, true, all.error);
    assert.equal(one.stats.threads, 1);
    assert.equal(all.stats.threads, all.stats.threadsAvailable);
    assert.ok(!Buffer.from(one.positions.buffer).equals(Buffer.from(mesh.positions.buffer)), `${op} moved nothing`);
    assert.ok(Buffer.from(all.positions.buffer).equals(Buffer.from(one.positions.buffer)), `${op}: threads changed the bits`);
  });
}
