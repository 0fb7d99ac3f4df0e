// The gallery's files hold what the core makes from their sources (scripts/gallery-sources.mjs),
// vertex for vertex, as the app reads them: issue 30 found both colored files scrambled (COLOR_0
// read as RGB rows of an RGBA array), the mean color difference across an edge as large as between
// two random vertices. Every vertex the app shows must be a vertex of the core's mesh, at its place
// (within the 16-bit quantization) and with its color, height above ground and class.
//
// Needs the shared data folder (../shared/data, or GEOSHIFT_SHARED_DATA) and the native CLI
// (build/native-release/cli/geoshift); skipped when either is missing.
import assert from 'node:assert/strict';
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { test } from 'node:test';
import { NodeIO } from '@gltf-transform/core';
import { coreMesh, GALLERY_SOURCES, placed } from '../../scripts/gallery-sources.mjs';
import { useApp } from './harness.mjs';

const repo = fileURLToPath(new URL('../../', import.meta.url));
const dataDir = process.env.GEOSHIFT_SHARED_DATA || `${repo}../shared/data`;
const cli = `${repo}build/native-release/cli/geoshift`;
const missing = !existsSync(dataDir) ? `no shared data at ${dataDir}` : !existsSync(cli) ? `no CLI at ${cli} (build it)` : '';

const app = missing ? null : useApp();

/**
 * In the page: a gallery file read by the app's own loader (three's glTF loader with the meshopt
 * decoder, loaders.ts), its one mesh's world positions, colors as the filters read them, indices
 * and scalar attributes.
 */
async function readAsTheAppDoes(file) {
  const { loadModel } = await import('/src/loaders.ts');
  const { meshArrays } = await import('/src/model.ts');
  const model = await loadModel(file, await (await fetch(`/gallery/${file}`)).arrayBuffer());
  const mesh = model.meshes[0];
  mesh.updateWorldMatrix(true, false);
  const arrays = meshArrays(mesh.geometry);
  const m = mesh.matrixWorld.elements;
  const positions = [];
  for (let i = 0; i < arrays.positions.length; i += 3) {
    const [x, y, z] = arrays.positions.subarray(i, i + 3);
    for (let r = 0; r < 3; r++) positions.push(m[r] * x + m[4 + r] * y + m[8 + r] * z + m[12 + r]);
  }
  const scalars = Object.fromEntries(Object.entries(arrays.scalars).map(([k, v]) => [k, Array.from(v)]));
  return { positions, colors: arrays.colors && Array.from(arrays.colors), indices: Array.from(arrays.indices), scalars };
}

/** Nearest reference vertex of each point within `tolerance` (a grid of that cell size), or -1. */
function match(points, reference, tolerance) {
  const cell = (x) => Math.floor(x / tolerance);
  const grid = new Map();
  for (let v = 0; v < reference.length / 3; v++) {
    const key = `${cell(reference[3 * v])},${cell(reference[3 * v + 1])},${cell(reference[3 * v + 2])}`;
    if (!grid.has(key)) grid.set(key, []);
    grid.get(key).push(v);
  }
  const found = new Int32Array(points.length / 3).fill(-1);
  for (let i = 0; i < found.length; i++) {
    const [x, y, z] = [points[3 * i], points[3 * i + 1], points[3 * i + 2]];
    let best = tolerance;
    for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
      for (const v of grid.get(`${cell(x) + dx},${cell(y) + dy},${cell(z) + dz}`) ?? []) {
        const d = Math.hypot(reference[3 * v] - x, reference[3 * v + 1] - y, reference[3 * v + 2] - z);
        if (d <= best) [best, found[i]] = [d, v];
      }
    }
  }
  return found;
}

/** Mean color difference across the mesh's edges, over that between random vertex pairs. */
function edgeCoherence(colors, indices) {
  const d = (a, b) => Math.hypot(colors[3 * a] - colors[3 * b], colors[3 * a + 1] - colors[3 * b + 1], colors[3 * a + 2] - colors[3 * b + 2]);
  let edges = 0;
  for (let t = 0; t < indices.length; t += 3) for (let k = 0; k < 3; k++) edges += d(indices[t + k], indices[t + ((k + 1) % 3)]);
  let random = 0;
  let s = 1;
  const n = colors.length / 3;
  const next = () => ((s = (Math.imul(s, 1664525) + 1013904223) >>> 0) % n);
  for (let i = 0; i < 20_000; i++) random += d(next(), next());
  return edges / indices.length / (random / 20_000);
}

test('every gallery file holds the core\'s mesh of its source, vertex for vertex', { skip: missing || false, timeout: 180_000 }, async () => {
  const { page } = app;
  const io = new NodeIO();
  const matched = new Map();
  for (const entry of GALLERY_SOURCES) {
    const reference = await coreMesh(entry, dataDir, cli, io);
    const world = placed(reference.positions, reference.matrix);
    const shown = await page.evaluate(readAsTheAppDoes, entry.file);
    const points = shown.positions;
    // Two steps of the 16-bit grid over the largest side: far below any edge of these meshes.
    const extent = Math.max(...[0, 1, 2].map((k) => {
      let lo = Infinity, hi = -Infinity;
      for (let i = k; i < world.length; i += 3) [lo, hi] = [Math.min(lo, world[i]), Math.max(hi, world[i])];
      return hi - lo;
    }));
    const found = match(points, world, extent / 32767);
    const lost = found.findIndex((v) => v < 0);
    assert.equal(lost, -1, `${entry.file}: vertex ${lost} at ${points.slice(3 * lost, 3 * lost + 3)} is no vertex of the core's mesh`);
    assert.ok(points.length / 3 <= world.length / 3 && new Set(found).size === found.length, `${entry.file}: two vertices on one of the source`);
    matched.set(entry.file, found);

    if (reference.colors) {
      const colors = shown.colors;
      assert.ok(colors, `${entry.file}: the app shows no vertex colors`);
      const off = [...found].findIndex((v, i) => [0, 1, 2].some((k) => Math.abs(colors[3 * i + k] - reference.colors[3 * v + k]) > 0.6 / 255));
      assert.equal(off, -1, off < 0 ? '' : `${entry.file}: vertex ${off} has color ${colors.slice(3 * off, 3 * off + 3)}, ` +
        `its source vertex ${found[off]} ${reference.colors.slice(3 * found[off], 3 * found[off] + 3)}`);
      const coherence = edgeCoherence(colors, shown.indices);
      const source = edgeCoherence(reference.colors, reference.indices);
      console.log(`# ${entry.file}: color difference across edges / between random vertices: ${coherence.toFixed(2)} (the core's mesh of the source: ${source.toFixed(2)})`);
      // Scrambled colors read 1.00 (issue 30); the simplified mesh's longer edges differ a little more.
      assert.ok(coherence < 2 * source && coherence < 0.5, `${entry.file}: colors do not follow the surface (${coherence.toFixed(2)})`);
    }
    for (const [name, values] of Object.entries(reference.scalars)) {
      const field = shown.scalars[name.toLowerCase()];
      assert.ok(field, `${entry.file}: the app lacks ${name}`);
      const off = [...found].findIndex((v, i) => field[i] !== values[v]);
      assert.equal(off, -1, off < 0 ? '' : `${entry.file}: ${name} of vertex ${off} is ${field[off]}, of its source vertex ${found[off]} ${values[found[off]]}`);
    }
  }
  // The noisy scan and its clean original pair the same source vertices, in the same order.
  for (const entry of GALLERY_SOURCES.filter((e) => e.pairedWith)) {
    assert.deepEqual(matched.get(entry.file), matched.get(entry.pairedWith), `${entry.file} and ${entry.pairedWith} are not paired vertex for vertex`);
  }
});

test('no uncaught errors in the page', { skip: missing || false }, () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
