// The curvature demo as issue 30 found it: Filter curvature with its preset's two wavelet levels
// drew saw teeth along the creases of the CAD part, its legend read −41.1 … 41.1 for an absolute
// curvature, and the "before" half of the split view was plain grey. Here: the gallery's noisy CAD
// part, its raw absolute curvature (the Curvature preset), then the Filter curvature preset.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { colourfulFraction, decodePng } from './png.mjs';
import { runPreset, useApp, waitForStatusAbout } from './harness.mjs';

const app = useApp({ viewport: { width: 1280, height: 800 } });

const field = (page) => page.evaluate(() => window.__geoshift.scalar('_curvature')[0]);

/**
 * Median |difference| of a field across the mesh's edges: how speckled it is. The median looks at
 * the faces (most edges); the few edges across a crease, sharp in both fields, do not count.
 */
function edgeVariation(values, indices) {
  const d = [];
  for (let t = 0; t < indices.length; t += 3) for (let k = 0; k < 3; k++) d.push(Math.abs(values[indices[t + k]] - values[indices[t + ((k + 1) % 3)]]));
  return d.sort((a, b) => a - b)[d.length >> 1];
}

test('the filtered absolute curvature stays within the raw field, is cleaner, and is drawn from zero beside the raw one', async () => {
  const { page } = app;
  await page.locator('[data-testid="gallery-item"][data-case="cad-part"]').click();
  await page.waitForFunction(() => decodeURIComponent(location.hash).includes('case=cad-part'));
  await waitForStatusAbout(page, 'fandisk-noisy.glb');
  const caseValues = (await page.evaluate(() => window.__geoshift.params())).params;
  assert.ok(caseValues.levels >= 1, `the preset's wavelet levels (${caseValues.levels}) are what issue 30 is about`);

  await runPreset(page, 'curvature', { kind: 'abs' });
  const raw = await field(page);
  const [indices] = await page.evaluate(() => window.__geoshift.indices());
  const lo = Math.min(...raw), hi = Math.max(...raw);
  assert.ok(lo >= 0 && hi > 0, `raw absolute curvature ${lo} … ${hi}`);
  await page.getByTestId('revert-button').click();

  await page.getByTestId('preset-select').selectOption('filter-curvature');
  await page.getByTestId('run-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  await page.evaluate(() => window.__geoshift.settled());
  assert.equal(await page.evaluate(() => window.__geoshift.lastError()), null);
  const filtered = await field(page);
  // Within the raw field's range (the mean shift reads values through approximate charts, a few
  // 1e-9 of the range off at most): no spike above the creases, nothing below zero.
  const tolerance = 1e-6 * hi;
  const outside = filtered.findIndex((v) => v < lo - tolerance || v > hi + tolerance);
  assert.equal(outside, -1, `vertex ${outside}: filtered ${filtered[outside]} outside the raw ${lo} … ${hi}`);
  const speckle = [edgeVariation(raw, indices), edgeVariation(filtered, indices)];
  console.log(`# median |difference| across edges: raw ${speckle[0].toFixed(3)}, filtered ${speckle[1].toFixed(3)}; raw range ${lo.toFixed(3)} … ${hi.toFixed(3)}`);
  assert.ok(speckle[1] < 0.25 * speckle[0], `the filtered field is hardly cleaner: ${speckle}`);

  // The legend: a magnitude, from zero, on the sequential map.
  const legend = await page.getByTestId('legend').evaluate((el) => ({ ...el.dataset, text: el.textContent }));
  assert.equal(legend.scalar, '_curvature');
  assert.equal(legend.kind, 'sequential', JSON.stringify(legend));
  assert.equal(Number(legend.min), 0, JSON.stringify(legend));
  assert.doesNotMatch(legend.text, /−|-\d/, `a negative end on the legend: ${legend.text}`);

  // Split view: the left half shows the raw field in color, not the mesh in grey.
  await page.getByTestId('split-slider').fill('50');
  await page.evaluate(() => window.__geoshift.settled());
  const png = decodePng(await page.getByTestId('canvas').screenshot({ path: 'test-output/e2e/curvature-split.png', style: '.view-tools, .view-status, .legend { visibility: hidden; }' }));
  // Each half without the split line (colourfulFraction takes its top-left pixel for the background).
  const half = (from) => {
    const width = Math.floor(png.width / 2) - 4;
    const data = new Uint8Array(width * png.height * 4);
    for (let y = 0; y < png.height; y++) data.set(png.data.subarray(4 * (y * png.width + from), 4 * (y * png.width + from + width)), 4 * y * width);
    return { width, height: png.height, data };
  };
  // The clay grey spreads its channels by 13 levels at most; the color map's darkest (viridis'
  // purple) by ~80, less where the shading darkens it.
  const [before, after] = [colourfulFraction(half(0), 15), colourfulFraction(half(Math.ceil(png.width / 2) + 4), 15)];
  console.log(`# colored share of the mesh: before half ${(100 * before).toFixed(0)}%, after half ${(100 * after).toFixed(0)}%`);
  assert.ok(before > 0.5, `the before half is grey (${(100 * before).toFixed(0)}% colored)`);
  assert.ok(after > 0.5, `the after half is grey (${(100 * after).toFixed(0)}% colored)`);
});

test('a class field is drawn as labels with their names; the geodesic distance starts at zero at a marked source', async () => {
  const { page } = app;
  await page.locator('[data-testid="gallery-item"][data-case="terrain"]').click();
  await page.waitForFunction(() => decodeURIComponent(location.hash).includes('case=terrain'));
  await waitForStatusAbout(page, 'autzen-terrain.glb');
  await page.getByTestId('view-mode').selectOption('scalar');
  await page.getByTestId('scalar-select').selectOption('_class');
  const legend = await page.getByTestId('legend').evaluate((el) => ({ kind: el.dataset.kind, text: el.textContent }));
  assert.equal(legend.kind, 'categorical');
  assert.match(legend.text, /1 unclassified.*2 ground/);

  await runPreset(page, 'geodesic', { source: 100 });
  const ends = await page.locator('[data-testid="legend"] .legend-ends span').allTextContents();
  assert.equal(ends[0], '0', `the distance legend starts at ${ends[0]}`);
  const marker = await page.evaluate(() => window.__geoshift.marker());
  assert.ok(marker, 'the source vertex is not marked');
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
