// The filter panel on the startup sample: a preset runs in the worker with progress, its scalar
// field is shown with a legend, noise and smoothing move the vertices (with the error against the
// pre-noise mesh reported), before/after and the split view change the pixels, revert restores
// the original, and Export writes a GLB with the same vertices.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { parseGlb } from './fixtures.mjs';
import { assertMeshVisible, exportedGlb, lastRun, positions, runPreset, shoot, status, useApp } from './harness.mjs';
import { colourfulFraction, differenceFraction } from './png.mjs';

const app = useApp();

test('the worker starts the threaded build in the cross-origin-isolated page', async () => {
  const info = await app.page.evaluate(() => window.__geoshift.workerReady());
  assert.equal(info.threaded, true);
  for (const op of ['noise', 'smooth', 'curvature']) assert.ok(info.ops.includes(op), `${op} missing from ${info.ops}`);
});

test('Curvature runs with progress and shows a color-mapped scalar field with a legend', async () => {
  const { page } = app;
  const shaded = await shoot(page, 'filters-shaded');
  await runPreset(page, 'curvature');
  const report = await lastRun(page);
  assert.ok(report, await page.evaluate(() => window.__geoshift.lastError()));
  assert.equal(report.vertices, 10000);
  assert.deepEqual(report.scalars, ['_curvature']);
  const events = await page.evaluate(() => window.__geoshift.progressEvents());
  assert.ok(events.length >= 2 && events.every((e) => typeof e.stage === 'string' && e.stage), JSON.stringify(events));
  assert.equal(await page.getByTestId('view-mode').inputValue(), 'scalar');
  assert.equal(await page.getByTestId('legend').isVisible(), true);
  assert.match(await page.getByTestId('legend').textContent(), /Curvature/);
  const field = await shoot(page, 'filters-curvature');
  const colourful = colourfulFraction(field);
  assert.ok(colourful > 0.5 && colourfulFraction(shaded) < 0.05, `the scalar field shows little color (${colourful})`);
  assert.ok(differenceFraction(shaded, field) > 0.1, "the scalar field looks like the shaded mesh");
  await page.getByTestId('view-mode').selectOption('shaded');
  assert.equal(await page.getByTestId('legend').isVisible(), false);
});

test('Geodesic distance from a vertex is shown as a scalar field', async () => {
  const { page } = app;
  await runPreset(page, 'geodesic', { source: 5000 });
  const report = await lastRun(page);
  assert.ok(report, await page.evaluate(() => window.__geoshift.lastError()));
  const [distance] = await page.evaluate(() => window.__geoshift.scalar('_geodesic'));
  assert.equal(distance.length, 10000);
  assert.equal(distance[5000], 0);
  assert.ok(distance.filter((d) => d > 0).length > 9000, 'most vertices should be reached');
  assert.match(await page.getByTestId('legend').textContent(), /Geodesic distance/);
  await shoot(page, 'filters-geodesic');
  await page.getByTestId('view-mode').selectOption('shaded');
});

test('Add noise then Taubin: vertices move, the error against the pre-noise mesh is reported', async () => {
  const { page } = app;
  const original = await positions(page);
  await page.getByTestId('add-noise-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  const noisy = await positions(page);
  assert.notDeepEqual(noisy, original);
  await shoot(page, 'filters-noisy');

  await runPreset(page, 'taubin', { iterations: 20 });
  const report = await lastRun(page);
  assert.ok(report, await page.evaluate(() => window.__geoshift.lastError()));
  assert.deepEqual(report.iterations, { kind: 'iterations', value: 20 });
  assert.ok(report.error, 'no error against the pre-noise mesh');
  assert.ok(report.error.rms < report.error.inputRms, `smoothing did not reduce the error: ${JSON.stringify(report.error)}`);
  const metrics = await page.getByTestId('metrics').textContent();
  assert.match(metrics, /Time/);
  assert.match(metrics, /10,000/);
  assert.match(metrics, /Iterations\s*20/);
  assert.match(metrics, /Error vs\. before noise/);
  assert.equal((await status(page)).state, 'ok');
});

test('before/after toggle and split slider show the earlier mesh', async () => {
  const { page } = app;
  const after = await shoot(page, 'compare-after');
  await page.getByTestId('before-toggle').check();
  await page.evaluate(() => window.__geoshift.settled());
  const before = await shoot(page, 'compare-before');
  assert.ok(differenceFraction(before, after) > 0.01, 'showing before does not change the view');
  await page.getByTestId('before-toggle').uncheck();
  await page.getByTestId('split-slider').fill('50');
  await page.evaluate(() => window.__geoshift.settled());
  const split = await shoot(page, 'compare-split');
  assertMeshVisible(split, 'split view');
  const d = differenceFraction(split, after);
  assert.ok(d > 0.005 && d < differenceFraction(before, after), `split view differs by ${d}`);
  assert.equal(await page.getByTestId('split-line').isVisible(), true);
  await page.getByTestId('split-slider').fill('0');
});

test('export writes a GLB with the same vertices, all finite, and revert restores the original', async () => {
  const { page } = app;
  const current = await positions(page);
  const exported = parseGlb(await exportedGlb(page));
  const primitive = exported.json.meshes[0].primitives[0];
  const p = exported.accessor(primitive.attributes.POSITION);
  assert.equal(p.length, current[0].length);
  assert.ok(p.every(Number.isFinite));
  assert.deepEqual(Array.from(p), current[0]);
  assert.ok(primitive.attributes.NORMAL !== undefined);
  assert.ok(primitive.attributes._CURVATURE !== undefined, `attributes: ${Object.keys(primitive.attributes)}`);

  await page.getByTestId('revert-button').click();
  await page.evaluate(() => window.__geoshift.settled());
  const reverted = await positions(page);
  assert.notDeepEqual(reverted, current);
  await page.getByTestId('view-mode').selectOption('shaded');
  assertMeshVisible(await shoot(page, 'filters-reverted'), 'reverted');
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
