// Live preview: dragging a parameter slider shows the filter on a coarse level at once (result-kind
// says "preview"); releasing it runs at full resolution, whose result replaces the preview.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { useApp, waitForStatusAbout } from './harness.mjs';

const app = useApp();

const events = () => app.page.evaluate(() => window.__geoshift.previewEvents());
const field = (name) => app.page.evaluate((n) => window.__geoshift.scalar(n)[0], name);

test('dragging a slider previews on a coarse level; releasing it replaces the preview by the full result', async () => {
  const { page } = app;
  await page.locator('[data-testid="gallery-item"][data-case="terrain"]').click();
  await waitForStatusAbout(page, 'autzen-terrain.glb');
  const vertices = (await page.evaluate(() => window.__geoshift.stats())).vertices;
  const original = await field('_height_above_ground');
  assert.equal(await page.getByTestId('result-kind').getAttribute('data-kind'), 'none');

  const slider = page.locator('[data-param="hr"] .lil-slider');
  const box = await slider.boundingBox();
  const y = box.y + box.height / 2;
  await page.mouse.move(box.x + 2, y);
  await page.mouse.down();
  for (let i = 1; i <= 6; i++) await page.mouse.move(box.x + (box.width * i) / 40, y, { steps: 2 });
  await page.waitForFunction(() => window.__geoshift.previewEvents().some((e) => e.kind === 'preview'), null, { timeout: 30_000 });
  assert.equal(await page.getByTestId('result-kind').getAttribute('data-kind'), 'preview');
  assert.match(await page.getByTestId('result-kind').textContent(), /^preview \(coarse level, [\d,]+ vertices/);
  const previewed = await field('_height_above_ground');
  assert.notDeepEqual(previewed, original, 'the preview changed nothing');
  const preview = (await events()).at(-1);
  assert.ok(preview.vertices <= 25_000 && preview.vertices < vertices, `preview on ${preview.vertices} of ${vertices} vertices`);
  // Nothing is committed by a preview: no run report, no "before" to compare with.
  assert.equal(await page.evaluate(() => window.__geoshift.lastRun()), null);
  assert.equal(await page.getByTestId('revert-button').isDisabled(), true);

  await page.mouse.up();
  await page.waitForFunction(() => window.__geoshift.previewEvents().at(-1)?.kind === 'full', null, { timeout: 120_000 });
  await page.evaluate(() => window.__geoshift.settled());
  const all = await events();
  const firstFull = all.findIndex((e) => e.kind === 'full');
  assert.ok(firstFull > 0 && all.slice(0, firstFull).every((e) => e.kind === 'preview'), JSON.stringify(all));
  assert.ok(all[0].at < all[firstFull].at, 'the preview came after the full result');
  assert.equal(all[firstFull].vertices, vertices);
  assert.equal(await page.getByTestId('result-kind').getAttribute('data-kind'), 'full');
  assert.match(await page.getByTestId('result-kind').textContent(), /^full result/);
  const full = await field('_height_above_ground');
  assert.notDeepEqual(full, previewed, 'the full result did not replace the preview');
  assert.notDeepEqual(full, original);
  const report = await page.evaluate(() => window.__geoshift.lastRun());
  assert.equal(report.vertices, vertices);
  // The full run used the value the slider was let go at.
  const { params } = await page.evaluate(() => window.__geoshift.params());
  assert.equal(report.stats[0].rangeBandwidth, params.hr);
  // Revert now brings back the file's values (the preview left no trace in the mesh's history).
  await page.getByTestId('revert-button').click();
  assert.deepEqual(await field('_height_above_ground'), original);
});

test('typing a value does not preview or run; unticking Live preview keeps sliders quiet', async () => {
  const { page } = app;
  const before = (await events()).length;
  const input = page.locator('[data-param="hr"] input').first();
  await input.fill('3');
  await input.press('Enter');
  await page.getByTestId('live-preview').uncheck();
  const slider = page.locator('[data-param="hr"] .lil-slider');
  const box = await slider.boundingBox();
  await page.mouse.move(box.x + 5, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + 30, box.y + box.height / 2, { steps: 4 });
  await page.mouse.up();
  await page.waitForTimeout(500);
  await page.evaluate(() => window.__geoshift.settled());
  assert.equal((await events()).length, before);
  await page.getByTestId('live-preview').check();
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
