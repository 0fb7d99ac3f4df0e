// The gallery: each case opens in one click with its preset and a line of what to try; the noisy
// scan reports the error against its clean original, and a link opens a case directly.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { assertMeshVisible, openFile, shoot, useApp, waitForStatusAbout } from './harness.mjs';

const app = useApp();

const EXPECTED = {
  'noisy-scan': { file: 'fertility-noisy.glb', preset: 'denoise' },
  'colored-mesh': { file: 'autzen-terrain.glb', preset: 'smooth-colors' },
  terrain: { file: 'autzen-terrain.glb', preset: 'terrain' },
  'cad-part': { file: 'fandisk-noisy.glb', preset: 'filter-curvature' },
};

async function openCase(page, id) {
  await page.locator(`[data-testid="gallery-item"][data-case="${id}"]`).click();
  await waitForStatusAbout(page, EXPECTED[id].file);
  await page.waitForFunction((i) => decodeURIComponent(location.hash).includes(`case=${i}`), id);
}

test('every case opens in one click, with its preset, a hint and its name in the URL', async () => {
  const { page } = app;
  const items = page.getByTestId('gallery-item');
  assert.equal(await items.count(), Object.keys(EXPECTED).length);
  for (const [id, { file, preset }] of Object.entries(EXPECTED)) {
    await openCase(page, id);
    const status = await page.getByTestId('status').textContent();
    assert.match(status, new RegExp(`^${file}: [\\d,]+ vertices, [\\d,]+ triangles$`));
    assert.equal(await page.getByTestId('preset-select').inputValue(), preset, id);
    assert.equal(await page.getByTestId('gallery-hint').isVisible(), true);
    assert.ok((await page.getByTestId('gallery-hint').textContent()).length > 30, `${id}: no hint`);
    assertMeshVisible(await shoot(page, `gallery-${id}`), id);
  }
  // Case-specific: the colored scene shows colors; the terrain filters its heights, not its classes.
  await openCase(page, 'colored-mesh');
  assert.equal(await page.getByTestId('view-mode').inputValue(), 'colors');
  await openCase(page, 'terrain');
  assert.equal((await page.evaluate(() => window.__geoshift.params())).params.signal, '_height_above_ground');
  assert.deepEqual(
    (await page.evaluate(() => window.__geoshift.scalar('_class')))[0].filter((v, i, a) => a.indexOf(v) === i).sort(),
    [1, 2],
  );
});

test('the noisy scan: denoising lowers the error against the clean scan', async () => {
  const { page } = app;
  await openCase(page, 'noisy-scan');
  await page.getByTestId('run-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  const report = await page.evaluate(() => window.__geoshift.lastRun());
  assert.ok(report, await page.evaluate(() => window.__geoshift.lastError()));
  assert.ok(report.error, 'no error against the clean scan was reported');
  assert.ok(report.error.inputRms > 0, 'the noisy input equals the clean scan');
  assert.ok(report.error.rms < report.error.inputRms, `denoising raised the error: ${report.error.inputRms} -> ${report.error.rms}`);
  assert.match(await page.getByTestId('metrics').textContent(), /Error vs\. the clean scan/);
  // Revert keeps the clean original: the next run reports against it again.
  await page.getByTestId('revert-button').click();
  await page.getByTestId('preset-select').selectOption('taubin');
  await page.getByTestId('run-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  assert.ok((await page.evaluate(() => window.__geoshift.lastRun())).error, 'revert forgot the clean original');
});

test('a link to a case opens that case with the linked settings', async () => {
  const other = await app.page.context().browser().newPage({ viewport: { width: 800, height: 540 } });
  try {
    await other.goto(`${app.url}#case=terrain&preset=terrain&signal=_class&hr=0.5`);
    await other.evaluate(() => window.__geoshift.ready);
    assert.equal((await other.evaluate(() => window.__geoshift.stats())).file, 'autzen-terrain.glb');
    const { preset, params } = await other.evaluate(() => window.__geoshift.params());
    assert.equal(preset, 'terrain');
    assert.equal(params.signal, '_class');
    assert.equal(params.hr, 0.5);
    assert.equal(await other.getByTestId('gallery-hint').isVisible(), true);

    await other.goto(`${app.url}#case=no-such-case`);
    await other.evaluate(() => window.__geoshift.ready);
    assert.match(await other.getByTestId('status').textContent(), /no gallery case "no-such-case"/);
  } finally {
    await other.close();
  }
});

test('a file of one\'s own leaves the case: the hint goes and the URL no longer names it', async () => {
  const { page } = app;
  await openCase(page, 'cad-part');
  const s = await openFile(page, 'mine.off', 'OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n');
  assert.equal(s.state, 'ok', s.text);
  assert.equal(await page.getByTestId('gallery-hint').isVisible(), false);
  assert.doesNotMatch(await page.evaluate(() => decodeURIComponent(location.hash)), /case=/);
  // Back returns to the case.
  await page.goBack();
  await waitForStatusAbout(page, 'fandisk-noisy.glb');
  assert.equal(await page.getByTestId('gallery-hint').isVisible(), true);
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
