// The threaded build (cross-origin-isolated page) and the single-threaded fallback give the same
// result, bit for bit, for the same runs on the same mesh.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { positions, runPreset, useApp } from './harness.mjs';

const threaded = useApp({ query: '?build=threaded' });
const single = useApp({ query: '?build=single' });

async function noiseSmoothCurvature(page) {
  await page.getByTestId('noise-amount').fill('0.4');
  await page.getByTestId('add-noise-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  await runPreset(page, 'taubin', { iterations: 7, weights: 'cotangent' });
  await runPreset(page, 'curvature', { kind: 'mean' });
  return page.evaluate(() => ({
    positions: window.__geoshift.positions(),
    run: window.__geoshift.lastRun(),
    error: window.__geoshift.lastError(),
  }));
}

test('the two builds give identical positions and curvature', async () => {
  assert.equal((await threaded.page.evaluate(() => window.__geoshift.workerReady())).threaded, true);
  assert.equal((await single.page.evaluate(() => window.__geoshift.workerReady())).threaded, false);
  const a = await noiseSmoothCurvature(threaded.page);
  const b = await noiseSmoothCurvature(single.page);
  assert.equal(a.error, null);
  assert.equal(b.error, null);
  assert.ok(a.positions[0].length === 30000);
  assert.deepEqual(a.positions, b.positions);
  const curvature = (page) => page.evaluate(() => window.__geoshift.scalar('_curvature'));
  assert.deepEqual(await curvature(threaded.page), await curvature(single.page));
  assert.equal(a.run.stats[0].threadsAvailable >= 1, true);
  assert.equal(b.run.stats[0].threadsAvailable, 1);
  await threaded.page.screenshot({ path: 'test-output/e2e/builds-threaded.png' });
  await single.page.screenshot({ path: 'test-output/e2e/builds-single.png' });
});

test('no uncaught errors in either page', () => {
  assert.deepEqual([...threaded.pageErrors, ...single.pageErrors].map(String), []);
});
