// The module's preview (wasm/preview.cpp): an op run on a coarse wavelet level and brought back to
// every vertex, for the web app's live preview. Properties: it never changes the kept mesh, it is
// the run itself when the mesh is already small, the coarse level respects maxVertices and is
// analysed once, labels stay labels, and bad arguments fail with a message.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';

import { loadGeoshift, saddle } from './support.mjs';

let g;
before(async () => {
  g = await loadGeoshift();
});

function load(mesh) {
  const r = g.loadMesh(Float32Array.from(mesh.positions), Uint32Array.from(mesh.indices));
  assert.ok(r.ok, r.error);
  return r.handle;
}

const smoothParams = { iterations: 8, lambda: 0.5, mu: -0.53, weights: 'uniform' };

test('on a mesh below maxVertices the preview is the run, and the kept mesh does not change', () => {
  const mesh = saddle(20);
  const h = load(mesh);
  const preview = g.preview(h, 'smooth', smoothParams, 100000);
  assert.ok(preview.ok, preview.error);
  assert.equal(preview.stats.levels, 0);
  assert.equal(preview.stats.previewVertices, mesh.positions.length / 3);
  const run = g.run(h, 'smooth', smoothParams);
  assert.ok(run.ok, run.error);
  // The run started from the unchanged mesh: the same positions as the preview, to the bit.
  assert.deepEqual(Array.from(preview.positions), Array.from(run.positions));
  g.freeMesh(h);
});

test('a large mesh is previewed on a level of at most maxVertices, analysed once', () => {
  const mesh = saddle(90); // 8281 vertices
  const n = mesh.positions.length / 3;
  const h = load(mesh);
  const first = g.preview(h, 'smooth', smoothParams, 1500);
  assert.ok(first.ok, first.error);
  assert.ok(first.stats.levels > 0);
  assert.ok(first.stats.previewVertices <= 1500 && first.stats.previewVertices > 100, `coarse level of ${first.stats.previewVertices}`);
  assert.equal(first.stats.analysisReused, false);
  assert.equal(first.positions.length, 3 * n);
  assert.ok(first.positions.every(Number.isFinite));
  // Smoothing a saddle pulls it towards flat: the preview moved the interior, inside the mesh's box.
  let moved = 0;
  for (let i = 0; i < first.positions.length; i++) moved = Math.max(moved, Math.abs(first.positions[i] - mesh.positions[i]));
  assert.ok(moved > 1e-3 && moved < 1, `largest move ${moved}`);

  const second = g.preview(h, 'smooth', { ...smoothParams, iterations: 2 }, 1500);
  assert.equal(second.stats.analysisReused, true);
  assert.equal(second.stats.previewVertices, first.stats.previewVertices);
  // A run that moves the vertices makes the next preview analyse again.
  assert.ok(g.run(h, 'smooth', smoothParams).ok);
  assert.equal(g.preview(h, 'smooth', smoothParams, 1500).stats.analysisReused, false);
  g.freeMesh(h);
});

test('a smaller level analyses the kept coarse mesh further; a larger one reuses a shorter chain', () => {
  const mesh = saddle(90);
  const n = mesh.positions.length / 3;
  const h = load(mesh);
  // A constant signal: the mean shift leaves it as it is, and the way back (weights summing to 1,
  // through every stage) must too.
  assert.ok(g.setAttribute(h, '_C', 1, new Float32Array(n).fill(2.5)).ok);
  const params = { signal: '_C', mode: 'ms', hs: 2, hr: 0.5, radius: 4 };
  const big = g.preview(h, 'filter', params, 3000);
  assert.ok(big.ok, big.error);
  assert.equal(big.stats.stages, 1);
  const small = g.preview(h, 'filter', params, 600);
  assert.ok(small.ok, small.error);
  assert.equal(small.stats.stages, 2);
  assert.equal(small.stats.analysisReused, false);
  assert.ok(small.stats.previewVertices <= 600);
  assert.ok(small.stats.levels > big.stats.levels);
  for (const r of [big, small]) assert.ok(r.scalars._C.every((v) => Math.abs(v - 2.5) < 1e-5), 'a constant did not stay constant');
  const again = g.preview(h, 'filter', params, 3000);
  assert.equal(again.stats.analysisReused, true);
  assert.equal(again.stats.stages, 1);
  assert.equal(again.stats.previewVertices, big.stats.previewVertices);
  g.freeMesh(h);
});

test('signals: a filtered scalar is interpolated within its range, segment labels stay labels', () => {
  const mesh = saddle(80);
  const n = mesh.positions.length / 3;
  const h = load(mesh);
  const height = Float32Array.from({ length: n }, (_, v) => mesh.positions[3 * v + 2]);
  assert.ok(g.setAttribute(h, '_H', 1, height).ok);
  const r = g.preview(h, 'filter', { signal: '_H', mode: 'ms', hs: 2, hr: 0.2, radius: 4, segments: true }, 1200);
  assert.ok(r.ok, r.error);
  const filtered = r.scalars._H;
  assert.equal(filtered.length, n);
  const [lo, hi] = [Math.min(...height), Math.max(...height)];
  assert.ok(filtered.every((v) => v >= lo - 1e-4 && v <= hi + 1e-4), 'a filtered value left the input range');
  const segments = r.scalars._SEGMENT;
  assert.ok(segments.every((v) => Number.isInteger(v) && v >= 0), 'a segment label was interpolated');
  assert.ok(new Set(segments).size <= r.stats.segmentCount);
  g.freeMesh(h);
});

test('bad arguments fail with a message naming them', () => {
  const h = load(saddle(6));
  assert.match(g.preview(h, 'smooth', {}, 10).error, /maxVertices must be at least 100/);
  assert.match(g.preview(h, 'nope', {}, 1000).error, /unknown op "nope"/);
  assert.match(g.preview(h, 'smooth', { bogus: 1 }, 1000).error, /unknown parameter "bogus"/);
  assert.match(g.preview(12345, 'smooth', {}, 1000).error, /handle 12345 is unknown/);
  g.freeMesh(h);
});
