// run() and friends report bad calls as values naming the op, the parameter or the handle, fail
// before doing any work, and leave the kept mesh as it was; a cancelled run changes nothing.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';

import { loadGeoshift, saddle } from './support.mjs';

let geoshift;
let mesh;
let handle;
before(async () => {
  geoshift = await loadGeoshift();
  mesh = saddle(10);
  handle = geoshift.loadMesh(mesh.positions, mesh.indices).handle;
});

const positionsNow = () => geoshift.run(handle, 'noise', { amount: 0 }).positions;

test('ops() lists the table', () => {
  const ops = geoshift.ops();
  for (const op of ['noise', 'smooth', 'curvature', 'geodesic']) assert.ok(ops.includes(op), op);
});

test('an unknown op names itself and the known ones', () => {
  const r = geoshift.run(handle, 'sharpen', {});
  assert.equal(r.ok, false);
  assert.match(r.error, /unknown op "sharpen"/);
  assert.match(r.error, /smooth/);
});

test('an unknown parameter is rejected before running, naming the accepted ones', () => {
  const r = geoshift.run(handle, 'smooth', { iteration: 3 });
  assert.equal(r.ok, false);
  assert.match(r.error, /smooth: unknown parameter "iteration"/);
  assert.match(r.error, /iterations/);
});

test('wrong parameter types and ranges name the parameter', () => {
  assert.match(geoshift.run(handle, 'smooth', { iterations: 'ten' }).error, /smooth: parameter iterations must be a number/);
  assert.match(geoshift.run(handle, 'smooth', { iterations: 2.5 }).error, /whole number/);
  assert.match(geoshift.run(handle, 'noise', { amount: -1 }).error, /noise: parameter amount .* outside/);
  assert.match(geoshift.run(handle, 'curvature', { kind: 'max' }).error, /kind = "max" is not one of abs, mean, gauss, rms/);
  assert.equal(geoshift.run(handle, 'smooth', null).ok, true, 'null params should mean all defaults');
});

test("the core's own checks come back as errors (Taubin needs mu < -lambda)", () => {
  const r = geoshift.run(handle, 'smooth', { lambda: 0.5, mu: -0.2 });
  assert.equal(r.ok, false);
  assert.match(r.error, /mu/);
});

test('an unknown or freed handle is named', () => {
  assert.match(geoshift.run(12345, 'smooth', {}).error, /mesh handle 12345 is unknown/);
  const { handle: h } = geoshift.loadMesh(mesh.positions, mesh.indices);
  assert.equal(geoshift.freeMesh(h), true);
  assert.equal(geoshift.freeMesh(h), false);
  assert.match(geoshift.run(h, 'smooth', {}).error, /unknown/);
});

test('setAttribute checks the length and the values, naming the vertex', () => {
  const n = mesh.positions.length / 3;
  assert.deepEqual(geoshift.setAttribute(handle, '_height', 1, new Float32Array(n)), { ok: true });
  assert.match(geoshift.setAttribute(handle, '_height', 1, new Float32Array(n - 1)).error, /expected/);
  const bad = new Float32Array(n);
  bad[5] = NaN;
  assert.match(geoshift.setAttribute(handle, '_height', 1, bad).error, /vertex 5/);
  assert.match(geoshift.setAttribute(handle, '_height', 1, [1, 2]).error, /Float32Array/);
});

test('loadMesh checks its extras', () => {
  const n = mesh.positions.length / 3;
  assert.equal(geoshift.loadMesh(mesh.positions, mesh.indices, { colors: new Float32Array(4 * n) }).ok, true);
  assert.match(geoshift.loadMesh(mesh.positions, mesh.indices, { colors: new Float32Array(5) }).error, /colors holds 5 numbers/);
  assert.match(geoshift.loadMesh(mesh.positions, mesh.indices, { normals: [0, 0, 1] }).error, /normals must be a Float32Array/);
  assert.match(geoshift.loadMesh(mesh.positions, new Uint32Array([0, 1, 999])).error, /face 0/);
});

test('a failed or cancelled run leaves the kept mesh unchanged, and progress is reported with stages', () => {
  const start = positionsNow();
  assert.equal(geoshift.run(handle, 'smooth', { lambda: 0.5, mu: -0.2 }).ok, false);
  assert.deepEqual(positionsNow(), start);

  const seen = [];
  const cancelled = geoshift.run(handle, 'smooth', { iterations: 1000 }, (fraction, stage) => {
    seen.push([fraction, stage]);
    return seen.length >= 3;
  });
  assert.deepEqual({ ok: cancelled.ok, cancelled: cancelled.cancelled, error: cancelled.error }, { ok: false, cancelled: true, error: 'cancelled' });
  assert.ok(seen.length >= 3 && seen.length <= 4, `the run went on after the callback asked to stop (${seen.length} reports)`);
  assert.ok(seen.every(([f, s]) => f >= 0 && f <= 1 && typeof s === 'string' && s.length > 0));
  assert.deepEqual(positionsNow(), start);

  const ok = geoshift.run(handle, 'smooth', { iterations: 2 }, () => false);
  assert.equal(ok.ok, true, ok.error);
  assert.notDeepEqual(ok.positions, start);
});
