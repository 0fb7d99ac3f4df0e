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
