// Errors come back as values ({ ok: false, error }) carrying the core's message; the module stays
// usable afterwards.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';

import { loadGeoshift, unweldedCube } from './support.mjs';

let geoshift;
before(async () => { geoshift = await loadGeoshift(); });

const triangle = () => new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0]);

test('an index out of range names the face', () => {
  const r = geoshift.loadMesh(triangle(), new Uint32Array([0, 1, 2, 2, 1, 7]));
  assert.equal(r.ok, false);
  assert.match(r.error, /face 1\b/);
  assert.match(r.error, /\b7\b/);
});

test('an index too large for the core (> INT_MAX) names the face too', () => {
  const r = geoshift.loadMesh(triangle(), new Uint32Array([0, 1, 2, 2, 1, 0xffffffff]));
  assert.equal(r.ok, false);
  assert.match(r.error, /face 1\b/);
  assert.match(r.error, /4294967295/);
});

test('a NaN coordinate names the vertex', () => {
  const positions = triangle();
  positions[3 * 2 + 1] = NaN;
  const r = geoshift.loadMesh(positions, new Uint32Array([0, 1, 2, 2, 1, 3]));
  assert.equal(r.ok, false);
  assert.match(r.error, /vertex 2\b/);
});

test('an infinite coordinate names the vertex', () => {
  const positions = triangle();
  positions[3 * 3] = Infinity;
  const r = geoshift.loadMesh(positions, new Uint32Array([0, 1, 2, 2, 1, 3]));
  assert.equal(r.ok, false);
  assert.match(r.error, /vertex 3\b/);
});

test('empty input is refused', () => {
  for (const [positions, indices] of [
    [new Float32Array(), new Uint32Array()],
    [triangle(), new Uint32Array()],
    [new Float32Array(), new Uint32Array([0, 1, 2])],
  ]) {
    const r = geoshift.loadMesh(positions, indices);
    assert.equal(r.ok, false, `${positions.length} numbers, ${indices.length} indices`);
    assert.equal(typeof r.error, 'string');
    assert.ok(r.error.length > 0);
  }
});

test('wrong argument types and lengths are refused with a plain message', () => {
  let r = geoshift.loadMesh([0, 0, 0, 1, 0, 0, 0, 1, 0], new Uint32Array([0, 1, 2]));
  assert.deepEqual(r, { ok: false, error: 'positions must be a Float32Array' });
  r = geoshift.loadMesh(triangle(), new Int32Array([0, 1, 2]));
  assert.deepEqual(r, { ok: false, error: 'indices must be a Uint32Array' });
  r = geoshift.loadMesh(new Float32Array(10), new Uint32Array([0, 1, 2]));
  assert.equal(r.ok, false);
  assert.match(r.error, /multiple of 3/);
  r = geoshift.loadMesh(triangle(), new Uint32Array([0, 1, 2, 3]));
  assert.equal(r.ok, false);
  assert.match(r.error, /multiple of 3/);
});

test('the module still works after errors', () => {
  const cube = unweldedCube();
  const r = geoshift.loadMesh(cube.positions, cube.indices);
  assert.equal(r.ok, true, r.error);
  assert.equal(r.weldedVertexCount, 8);
  assert.equal(geoshift.run(r.handle, 'curvature', {}).ok, true);
  geoshift.freeMesh(r.handle);
});
