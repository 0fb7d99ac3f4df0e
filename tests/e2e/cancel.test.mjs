// A long run reports progress as it goes; Cancel stops it long before it would end, leaves the mesh
// as it was, and the next run succeeds. Both ways of cancelling are exercised: the shared flag of
// the threaded build and terminating the worker of the single-threaded one. The rates the app aims
// at (progress 5 times a second, cancel within half a second) are printed as diagnostics, not
// asserted: a loaded 2-core machine may miss them without anything being wrong. The bounds here
// only tell "cancel stopped the run" from "the run ran on" (100,000 Taubin steps take minutes).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { positions, runPreset, setParams, useApp } from './harness.mjs';

for (const build of ['threaded', 'single']) {
  const app = useApp({ query: `?build=${build}` });

  test(`${build}: progress, cancel, then a second run succeeds`, async (t) => {
    const { page } = app;
    const info = await page.evaluate(() => window.__geoshift.workerReady());
    assert.equal(info.threaded, build === 'threaded');
    const before = await positions(page);

    await page.getByTestId('preset-select').selectOption('taubin');
    await setParams(page, { iterations: 100000 });
    await page.getByTestId('run-button').click();
    // Progress keeps arriving while it runs.
    await page.waitForFunction(() => window.__geoshift.progressEvents().filter((e) => e.stage === 'taubin').length >= 5, null,
      { timeout: 60_000 });
    await page.waitForTimeout(1200);
    const rate = await page.evaluate(() => {
      const events = window.__geoshift.progressEvents().filter((e) => e.stage === 'taubin');
      const last = events.at(-1).at;
      return events.filter((e) => e.at > last - 1000).length;
    });
    t.diagnostic(`${build}: ${rate} progress messages in the last second (the app aims at 5 or more)`);
    assert.equal(await page.getByTestId('progress').getAttribute('data-state'), 'running');
    // A long steady stage gets its time left once its rate has settled (progress-bar.ts).
    await page.waitForFunction(() => /left/.test(document.querySelector('[data-testid="progress"]').textContent), null, { timeout: 20_000 });
    assert.match(await page.getByTestId('progress').textContent(), /taubin — \d+%, about .* left/);
    await page.screenshot({ path: `test-output/e2e/cancel-${build}-running.png` });

    const elapsed = await page.evaluate(async () => {
      const t0 = performance.now();
      document.querySelector('[data-testid="cancel-button"]').click();
      await window.__geoshift.idle();
      return performance.now() - t0;
    });
    t.diagnostic(`${build}: cancel took ${elapsed.toFixed(0)} ms (the app aims at under 500)`);
    assert.ok(elapsed < 20_000, `cancel took ${elapsed.toFixed(0)} ms: the run was not stopped`);
    assert.match(await page.evaluate(() => window.__geoshift.lastError()), /Cancelled/);
    assert.equal(await page.getByTestId('cancel-button').isDisabled(), true);
    assert.equal(await page.getByTestId('run-button').isDisabled(), false);
    assert.deepEqual(await positions(page), before, 'a cancelled run changed the mesh');
    await page.screenshot({ path: `test-output/e2e/cancel-${build}-cancelled.png` });

    await runPreset(page, 'taubin', { iterations: 5 });
    const report = await page.evaluate(() => window.__geoshift.lastRun());
    assert.ok(report, await page.evaluate(() => window.__geoshift.lastError()));
    assert.notDeepEqual(await positions(page), before);
  });

  test(`${build}: no uncaught errors in the page`, () => {
    assert.deepEqual(app.pageErrors.map(String), []);
  });
}
