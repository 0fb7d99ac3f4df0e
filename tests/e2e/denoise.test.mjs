// A GLB given to the file picker is denoised with the Denoise preset, mesh by mesh, and the
// exported GLB keeps the scene: same meshes and vertex counts, only finite values, moved positions.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { parseGlb, sceneGlb, torus, TETRA } from './fixtures.mjs';
import { exportedGlb, openFile, runPreset, shoot, useApp } from './harness.mjs';

const app = useApp();

/** name -> translation of the named nodes; the exporter writes a matrix where the input had TRS. */
function placements(json) {
  const out = {};
  for (const n of json.nodes) {
    if (n.name) out[n.name] = n.translation ?? (n.matrix ? n.matrix.slice(12, 15) : [0, 0, 0]);
  }
  return out;
}

/**
 * The exported scene against the input: same placements, and per mesh the same vertex count with
 * finite positions; the meshes `moved(m)` names must have moved.
 */
function assertExportedScene(before, after, moved) {
  assert.deepEqual(placements(after.json), placements(before.json));
  for (let m = 0; m < before.json.meshes.length; m++) {
    const p0 = before.accessor(before.json.meshes[m].primitives[0].attributes.POSITION);
    const p1 = after.accessor(after.json.meshes[m].primitives[0].attributes.POSITION);
    assert.equal(p1.length, p0.length, `mesh ${m}: vertex count changed`);
    assert.ok(p1.every(Number.isFinite), `mesh ${m}: non-finite positions`);
    if (moved(m)) assert.ok(p1.some((v, i) => Math.abs(v - p0[i]) > 1e-6), `mesh ${m} did not move`);
  }
}

function noisyTorus(n = 64, m = 32) {
  const t = torus(n, m);
  let s = 12345;
  const rand = () => ((s = (Math.imul(s, 1664525) + 1013904223) >>> 0) / 2 ** 32 - 0.5);
  // Noise on the seam copies too; welding keeps the first copy's position for both.
  t.positions = t.positions.map((v) => v + 0.01 * rand());
  return t;
}

test('a GLB given to file-input is denoised and exported with the same vertex counts', async () => {
  const { page } = app;
  const ops = (await page.evaluate(() => window.__geoshift.workerReady())).ops;
  assert.ok(ops.includes('denoise'), `the wasm module has no 'denoise' op (it has ${ops.join(', ')})`);
  // Small (about 800 vertices), so one pass of the paper's settings takes well under a second.
  const mesh = noisyTorus(32, 24);
  const tetra = { positions: TETRA.positions.flat(), indices: TETRA.triangles.flat() };
  const input = sceneGlb([mesh, tetra]);
  const s = await openFile(page, 'noisy-torus.glb', input);
  assert.equal(s.state, 'ok', s.text);
  await shoot(page, 'denoise-input');

  // The Denoise preset leads with strength, keep edges and the noise level; the rest is folded.
  await page.getByTestId('preset-select').selectOption('denoise');
  for (const key of ['strength', 'hr', 'noise']) assert.ok(await page.locator(`[data-param="${key}"]`).isVisible(), key);
  for (const key of ['passes', 'impulse', 'lightStart']) {
    assert.equal(await page.locator(`[data-param="${key}"]`).count(), 1, key);
    assert.equal(await page.locator(`[data-param="${key}"]`).isVisible(), false, `${key} is an expert setting`);
  }

  await runPreset(page, 'denoise', { passes: 1 });
  const report = await page.evaluate(() => window.__geoshift.lastRun());
  assert.ok(report, await page.evaluate(() => window.__geoshift.lastError()));
  assert.equal(report.meshes, 2);
  // The noise level was measured on the torus (±0.005 per coordinate, about 0.02 of its average
  // edge length across the surface) and is shown.
  const torusStats = report.stats.find((s) => typeof s.noiseLevel === 'number');
  assert.ok(torusStats && torusStats.noiseEstimated === 'yes', JSON.stringify(report.stats));
  assert.ok(torusStats.noiseLevel > 0.005 && torusStats.noiseLevel < 0.1, `noise level ${torusStats.noiseLevel}`);
  const metrics = await page.getByTestId('metrics').innerText();
  assert.match(metrics, /Noise level[\s\S]*measured on the mesh/);
  // The Chosen row words the torus's own stats (web/src/denoise-summary.ts).
  assert.match(metrics, new RegExp(`Chosen\\s+${torusStats.presmoothingSteps} Taubin steps? (\\+|alone)`), metrics);
  await shoot(page, 'denoise-output');

  const before = parseGlb(input);
  const after = parseGlb(await exportedGlb(page));
  assert.equal(after.json.meshes.length, 2);
  assertExportedScene(before, after, (m) => m === 0);  // the torus moves
});

// The same scene with the ops that exist today: every mesh is filtered, the export keeps both
// meshes, their nodes and vertex counts.
test('a two-mesh GLB is smoothed mesh by mesh and exported with its scene', async () => {
  const { page } = app;
  const mesh = noisyTorus();
  const tetra = { positions: TETRA.positions.flat(), indices: TETRA.triangles.flat() };
  const input = sceneGlb([mesh, tetra]);
  const s = await openFile(page, 'two-meshes.glb', input);
  assert.equal(s.state, 'ok', s.text);
  await runPreset(page, 'taubin', { iterations: 4 });
  const report = await page.evaluate(() => window.__geoshift.lastRun());
  assert.ok(report, await page.evaluate(() => window.__geoshift.lastError()));
  assert.equal(report.meshes, 2);
  assert.equal(report.vertices, mesh.positions.length / 3 + 4);
  const before = parseGlb(input);
  const after = parseGlb(await exportedGlb(page));
  assert.equal(after.json.meshes.length, 2);
  assertExportedScene(before, after, () => true);
  await shoot(page, 'two-meshes-smoothed');
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
