// geoshift/three under Node (three runs without a browser): geometries in the layouts three produces
// become meshes with the same numbers, results come back into a clone that keeps everything else,
// and the helpers give what the plain jobs give.
import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';
import { BufferAttribute, BufferGeometry, InterleavedBuffer, InterleavedBufferAttribute } from 'three';

import { createGeoshift } from 'geoshift';
import { applyResult, curvatureGeometry, denoiseGeometry, geometryToMesh, meshToGeometry, smoothGeometry } from 'geoshift/three';
import { saddle } from '../wasm/support.mjs';

const mesh = saddle(8);
const count = mesh.positions.length / 3;
let gs;
before(async () => {
  gs = await createGeoshift({ threads: 1 });
});
after(() => gs.terminate());

/** The saddle as glTF files hold meshes: quantized normalized positions interleaved with uvs, RGBA bytes, a Uint16 index, a group. */
function quantized() {
  const scale = 32767 / 2;
  const interleaved = new Int16Array(5 * count);
  for (let v = 0; v < count; v++) {
    for (let c = 0; c < 3; c++) interleaved[5 * v + c] = Math.round(mesh.positions[3 * v + c] * scale);
    interleaved[5 * v + 3] = v;
    interleaved[5 * v + 4] = -v;
  }
  const buffer = new InterleavedBuffer(interleaved, 5);
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new InterleavedBufferAttribute(buffer, 3, 0, true));
  geometry.setAttribute('uv', new InterleavedBufferAttribute(buffer, 2, 3, false));
  const rgba = new Uint8Array(4 * count).map((_, i) => (i % 4 === 3 ? 128 : (i * 37) % 256));
  geometry.setAttribute('color', new BufferAttribute(rgba, 4, true));
  geometry.setAttribute('_height', new BufferAttribute(Float32Array.from({ length: count }, (_, v) => mesh.positions[3 * v + 2]), 1));
  geometry.setIndex(new BufferAttribute(Uint16Array.from(mesh.indices), 1));
  geometry.addGroup(0, mesh.indices.length, 2);
  geometry.userData.source = 'test';
  return geometry;
}

test('geometryToMesh undoes interleaving, quantization and normalization, and passes the index and the other attributes', () => {
  const geometry = quantized();
  const m = geometryToMesh(geometry);
  const position = geometry.getAttribute('position');
  for (let v = 0; v < count; v++) assert.equal(m.positions[3 * v + 1], Math.fround(position.getY(v)));
  // Normalized Int16 reads as value / 32767: half the saddle's coordinates, to the quantization step.
  assert.ok(m.positions.every((x, i) => Math.abs(x - mesh.positions[i] / 2) <= 1 / 32767));
  assert.ok(m.indices instanceof Uint32Array);
  assert.deepEqual(Array.from(m.indices), Array.from(mesh.indices));
  assert.equal(m.colors.length, 4 * count);
  assert.equal(m.colors[3], Math.fround(128 / 255));
  assert.deepEqual(Object.keys(m.attributes), ['_height'], 'uv is not a signal');
  const soup = geometryToMesh(new BufferGeometry().setAttribute('position', new BufferAttribute(new Float32Array(9), 3)));
  assert.equal(soup.indices, undefined);
});

test('applyResult writes positions, colors (alpha kept) and attributes into a clone; normals and bounds follow the positions', () => {
  const geometry = quantized();
  const moved = Float32Array.from(geometryToMesh(geometry).positions, (x) => x * 2);
  const colors = new Float32Array(3 * count).fill(0.5);
  const out = applyResult(geometry, { positions: moved, colors, attributes: { _CURVATURE: new Float32Array(count).fill(7) } });
  assert.notEqual(out, geometry);
  assert.deepEqual(Array.from(out.getAttribute('position').array), Array.from(moved));
  assert.equal(out.getAttribute('color').itemSize, 4);
  assert.equal(out.getAttribute('color').getW(3), Math.fround(geometry.getAttribute('color').getW(3)));
  assert.equal(out.getAttribute('color').getX(3), 0.5);
  assert.equal(out.getAttribute('_CURVATURE').itemSize, 1);
  assert.equal(out.getAttribute('normal').count, count);
  assert.equal(out.boundingBox.max.x, Math.max(...moved.filter((_, i) => i % 3 === 0)));
  assert.equal(out.boundingSphere !== null, true);
  // Everything else is kept; the input is not touched.
  assert.deepEqual(out.groups, [{ start: 0, count: mesh.indices.length, materialIndex: 2 }]);
  assert.equal(out.getAttribute('uv').getY(5), -5);
  assert.equal(out.userData.source, 'test');
  assert.equal(geometry.getAttribute('normal'), undefined);
  assert.equal(geometry.getAttribute('_CURVATURE'), undefined);
  // Positions that did not move leave the normals alone.
  const still = applyResult(geometry, { positions: geometryToMesh(geometry).positions, attributes: {} });
  assert.equal(still.getAttribute('normal'), undefined);
});

test('the helpers give what the jobs give, on any layout', async () => {
  const geometry = quantized();
  const plain = geometryToMesh(geometry);
  const smoothed = await smoothGeometry(gs, geometry, { iterations: 3 });
  assert.deepEqual(Array.from(smoothed.getAttribute('position').array), Array.from((await gs.smooth(plain, { iterations: 3 })).positions));
  const denoised = await denoiseGeometry(gs, geometry, { method: 'taubin', iterations: 2 });
  assert.deepEqual(Array.from(denoised.getAttribute('position').array), Array.from((await gs.denoise(plain, { method: 'taubin', iterations: 2 })).positions));
  const curved = await curvatureGeometry(gs, geometry, { kind: 'mean' });
  assert.deepEqual(Array.from(curved.getAttribute('_CURVATURE').array), Array.from((await gs.curvature(plain, { kind: 'mean' })).attributes._CURVATURE));
  assert.equal(curved.getAttribute('color').itemSize, 4, 'the color map keeps the alpha channel of RGBA colors');
});

test('meshToGeometry builds a geometry of a read part, normals computed when the file has none', async () => {
  const r = await gs.read(new TextEncoder().encode('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n'), 't.obj');
  const geometry = meshToGeometry(r.parts[0].mesh);
  assert.deepEqual(Array.from(geometry.index.array), [0, 1, 2]);
  assert.deepEqual(Array.from(geometry.getAttribute('normal').array.slice(0, 3)), [0, 0, 1]);
});
