// What the progress says (issue 30): "sending the mesh — 0%" for 2.2 s, "21%, about 10 s left" for
// a run that ended 0.7 s later, an old "Done in 8.54 s" after another case opened. The bar itself
// is fed made-up stages in the page (progress-bar.ts through Vite), then a real run.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { runPreset, useApp, waitForStatusAbout } from './harness.mjs';

const app = useApp();

test('the progress says what it knows: no percent while preparing, no time left from an open-ended or young stage', async () => {
  const labels = await app.page.evaluate(async () => {
    const { ProgressBar } = await import('/src/progress-bar.ts');
    const element = document.createElement('div');
    element.innerHTML = '<div class="progress-track"><div class="progress-fill"></div></div><div class="progress-label"></div>';
    const bar = new ProgressBar(element);
    const label = () => element.querySelector('.progress-label').textContent;
    const out = {};
    bar.start('Denoise');
    bar.update(0, 'preparing the mesh', null, 0);
    out.preparing = label();
    // The denoiser's passes: a fraction of the most passes it may run; it stopped at 17%.
    for (let t = 0; t <= 3000; t += 250) bar.update(0.1 + 0.017 * (t / 250), 'denoise passes', 0.017 * (t / 250), 1000 + t);
    out.openEnded = label();
    // A steady stage: 10% a second.
    for (let t = 0; t <= 1000; t += 100) bar.update(t / 10_000, 'mean shift', t / 10_000, 10_000 + t);
    out.young = label();
    for (let t = 1100; t <= 3000; t += 100) bar.update(t / 10_000, 'mean shift', t / 10_000, 10_000 + t);
    out.steady = label();
    // The rate jumps fivefold: the estimate from the old rate is not shown.
    bar.update(0.4, 'mean shift', 0.4, 13_200);
    out.jump = label();
    return out;
  });
  assert.equal(labels.preparing, 'preparing the mesh…');
  assert.doesNotMatch(labels.openEnded, /%|left/, labels.openEnded);
  assert.doesNotMatch(labels.young, /left/, labels.young);
  assert.equal(labels.steady, 'mean shift — 30%, about 7 s left');
  assert.doesNotMatch(labels.jump, /left/, labels.jump);
});

test('a finished run\'s "Done in" goes when another mesh opens', async () => {
  const { page } = app;
  await runPreset(page, 'curvature');
  assert.match(await page.locator('[data-testid="progress"] .progress-label').textContent(), /^Done in/);
  await page.locator('[data-testid="gallery-item"][data-case="cad-part"]').click();
  await waitForStatusAbout(page, 'fandisk-noisy.glb');
  assert.equal(await page.locator('[data-testid="progress"] .progress-label').textContent(), '');
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
