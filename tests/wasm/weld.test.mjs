// Welding: glTF-style split vertices become one connected surface, and per-vertex results come
// back in the caller's layout so coincident caller vertices get identical values.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';

import { loadGeoshift, unweldedCube, cubeCorners } from './support.mjs';

let geoshift;
before(async () => { geoshift = await loadGeoshift(); });

// The mesh as loadMesh builds it, with its three curvatures per caller vertex (the op "curvature").
function curvaturesOf(positions, indices) {
  const r = geoshift.loadMesh(positions, indices);
  assert.equal(r.ok, true, r.error);
  const kinds = { meanCurvature: 'mean', gaussianCurvature: 'gauss', absoluteCurvature: 'abs' };
  for (const [name, kind] of Object.entries(kinds)) {
    const run = geoshift.run(r.handle, 'curvature', { kind });
    assert.equal(run.ok, true, run.error);
    r[name] = run.scalars._CURVATURE;
  }
  geoshift.freeMesh(r.handle);
  return r;
}

test('an unwelded cube (36 vertices, 12 faces) welds to 8 corners', () => {
  const cube = unweldedCube();
  const r = geoshift.loadMesh(cube.positions, cube.indices);
  assert.equal(r.ok, true, r.error);
  geoshift.freeMesh(r.handle);
  assert.equal(r.weldedVertexCount, 8);
  assert.equal(r.report.weldedVertices, 36 - 8);
  assert.equal(r.report.nonManifoldEdges, 0);
  assert.equal(r.report.nonManifoldVertices, 0);
  assert.ok(r.vertexOf instanceof Int32Array);
  assert.equal(r.vertexOf.length, 36);

  // Same corner <=> same welded vertex, and welded vertices are numbered by first appearance.
  const weldedOfCorner = new Map();
  for (let v = 0; v < 36; ++v) {
    const c = cube.corner[v];
    if (!weldedOfCorner.has(c)) weldedOfCorner.set(c, r.vertexOf[v]);
    assert.equal(r.vertexOf[v], weldedOfCorner.get(c), `caller vertex ${v} (corner ${c})`);
  }
  assert.equal(new Set(weldedOfCorner.values()).size, 8);
  const firstAppearance = [...new Set(cube.corner)];
  firstAppearance.forEach((c, i) => assert.equal(weldedOfCorner.get(c), i, `corner ${c} ${cubeCorners[c]}`));

  // 12 cube edges of length 1 and 6 face diagonals of length √2, each counted once: an unwelded
  // input would count every edge twice and see 36 boundary edges.
  assert.ok(Math.abs(r.averageEdgeLength - (12 + 6 * Math.SQRT2) / 18) < 1e-12, `${r.averageEdgeLength}`);
});

test('curvature is identical at seams for coincident caller vertices', () => {
  const cube = unweldedCube();
  const r = curvaturesOf(cube.positions, cube.indices);
  for (const name of ['meanCurvature', 'gaussianCurvature', 'absoluteCurvature']) {
    const values = r[name];
    assert.ok(values instanceof Float32Array, name);
    assert.equal(values.length, 36, name);
    const first = new Map();
    for (let v = 0; v < 36; ++v) {
      const c = cube.corner[v];
      if (!first.has(c)) first.set(c, values[v]);
      assert.equal(Object.is(values[v], first.get(c)), true, `${name} at caller vertex ${v} (corner ${c})`);
    }
  }
  // A closed convex polyhedron: every corner has angle defect π/2 and positive mean curvature, all
  // corners alike by symmetry.
  const k = r.gaussianCurvature[0];
  assert.ok(k > 0 && r.gaussianCurvature.every((x) => Math.abs(x - k) <= 1e-6 * k), `${r.gaussianCurvature}`);
  assert.ok(r.meanCurvature.every((x) => x > 0), `${r.meanCurvature}`);
});

test('a welded input is left as it is', () => {
  const cube = unweldedCube();
  const welded = curvaturesOf(cube.positions, cube.indices);
  const positions = new Float32Array(3 * 8);
  for (let v = 0; v < 36; ++v) positions.set(cube.positions.subarray(3 * v, 3 * v + 3), 3 * welded.vertexOf[v]);
  const indices = Uint32Array.from(cube.indices, (v) => welded.vertexOf[v]);
  const r = curvaturesOf(positions, indices);
  assert.equal(r.report.weldedVertices, 0);
  assert.deepEqual([...r.vertexOf], [0, 1, 2, 3, 4, 5, 6, 7]);
  for (const name of ['meanCurvature', 'gaussianCurvature', 'absoluteCurvature']) {
    for (let v = 0; v < 36; ++v) assert.equal(r[name][welded.vertexOf[v]], welded[name][v], `${name} at ${v}`);
  }
});

// A cube glTF-style (unwelded) with two faces written the other way round: they are turned to
// agree with their neighbours (docs/denoising.md#bad-input), counted, and named in the messages,
// and the curvature is the consistently wound cube's.
test('faces wound against their neighbours are turned over and reported', () => {
  const cube = unweldedCube();
  const mixed = Uint32Array.from(cube.indices);
  for (const f of [1, 6]) [mixed[3 * f + 1], mixed[3 * f + 2]] = [mixed[3 * f + 2], mixed[3 * f + 1]];
  const r = geoshift.loadMesh(cube.positions, mixed);
  assert.equal(r.ok, true, r.error);
  geoshift.freeMesh(r.handle);
  assert.equal(r.report.reorientedFaces, 2);
  assert.equal(r.report.nonManifoldEdges, 0);
  assert.ok(r.report.messages.some((m) => m.startsWith('re-oriented 2 face(s) to agree with their neighbours')), r.report.messages.join('\n'));
  const consistent = geoshift.loadMesh(cube.positions, cube.indices);
  assert.equal(consistent.report.reorientedFaces, 0);
  geoshift.freeMesh(consistent.handle);
  const a = curvaturesOf(cube.positions, cube.indices), b = curvaturesOf(cube.positions, mixed);
  assert.deepEqual(b.meanCurvature, a.meanCurvature);
});
