// A file that really is too large for the tab: with the single-threaded build's heap limited to
// 64 MB (?heap=64, as on a device with little memory), the core's reader runs out of WebAssembly
// memory on a 500 000-vertex GLB. The page says so in words, the worker is replaced by a fresh one
// (which reads and filters the next file), and the mesh on screen stays as it was.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { glb, tetraGlb } from './fixtures.mjs';
import { lastRun, openFile, positions, runPreset, stats, useApp } from './harness.mjs';

const app = useApp({ query: '?build=single&heap=64' });
const SAMPLE = { file: 'ChineseDragon-10kv.off', vertices: 10000, triangles: 19994 };

/** A flat n x n grid as a GLB: float positions, uint32 indices (about 36 bytes per vertex). */
function gridGlb(n) {
  const positions = new Float32Array(3 * n * n);
  for (let i = 0; i < n; i++) for (let j = 0; j < n; j++) positions.set([i, j, 0], 3 * (i * n + j));
  const indices = new Uint32Array(6 * (n - 1) * (n - 1));
  let k = 0;
  for (let i = 0; i + 1 < n; i++) {
    for (let j = 0; j + 1 < n; j++) {
      const v = i * n + j;
      indices.set([v, v + n, v + 1, v + 1, v + n, v + n + 1], k);
      k += 6;
    }
  }
  const bin = Buffer.concat([Buffer.from(positions.buffer), Buffer.from(indices.buffer)]);
  return glb({
    asset: { version: '2.0' },
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: n * n, type: 'VEC3', min: [0, 0, 0], max: [n - 1, n - 1, 0] },
      { bufferView: 1, componentType: 5125, count: indices.length, type: 'SCALAR' },
    ],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: positions.byteLength },
      { buffer: 0, byteOffset: positions.byteLength, byteLength: indices.byteLength },
    ],
    buffers: [{ byteLength: bin.length }],
  }, bin);
}

test('a file too large for the heap is refused in words; the worker restarts; the mesh stays', async () => {
  const { page } = app;
  const before = await positions(page);
  const s = await openFile(page, 'big-grid.glb', gridGlb(708));
  assert.equal(s.state, 'error', s.text);
  assert.match(s.text, /^Could not read big-grid\.glb: it is too large for the memory this browser tab may use \(reading it needs more than the WebAssembly heap can grow to\)/);
  assert.match(s.text, /Still showing ChineseDragon-10kv\.off\.$/);
  assert.deepEqual(await stats(page), SAMPLE);
  assert.deepEqual(await positions(page), before);

  // The fresh worker reads the next file with the core and runs a filter on it.
  const damaged = await openFile(page, 'damaged.glb', tetraGlb({ extraJson: { scene: 3 } }));
  assert.match(damaged.text, /^Could not read damaged\.glb: the default scene is 3, which names no object/);
  const ok = await openFile(page, 'tetra.glb', tetraGlb());
  assert.equal(ok.state, 'ok', ok.text);
  await runPreset(page, 'taubin', { iterations: 3 });
  assert.ok(await lastRun(page), await page.evaluate(() => window.__geoshift.lastError()));
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
