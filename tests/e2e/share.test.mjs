// Shareable state: the preset and its parameters live in the URL hash, a link opens the same
// settings in a fresh page, and Back/Forward restore earlier ones.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { setParams, useApp } from './harness.mjs';

const app = useApp();

const shown = (page) => page.evaluate(() => window.__geoshift.params());
const hashOf = (page) => page.evaluate(() => decodeURIComponent(location.hash));

test('settings go into the hash, and a link opens the same settings', async () => {
  const { page } = app;
  await page.getByTestId('preset-select').selectOption('filter-curvature');
  await setParams(page, { hr: 0.5, passes: 3, mode: 'bms' });
  await page.getByTestId('up-axis-select').selectOption('+z');
  const hash = await hashOf(page);
  assert.match(hash, /preset=filter-curvature/);
  assert.match(hash, /hr=0\.5/);
  assert.match(hash, /mode=bms/);
  assert.match(hash, /up=\+z/);
  const expected = await shown(page);
  assert.equal(expected.params.hr, 0.5);
  assert.equal(expected.params.mode, 'bms');

  const other = await page.context().browser().newPage();
  try {
    await other.goto(page.url());
    await other.evaluate(() => window.__geoshift.ready);
    assert.deepEqual(await shown(other), expected);
    assert.equal(await other.getByTestId('preset-select').inputValue(), 'filter-curvature');
    assert.equal(await other.locator('[data-param="hr"] input').first().inputValue(), '0.5');
    assert.equal(await other.evaluate(() => window.__geoshift.upAxis()), '+z');
  } finally {
    await other.close();
  }
});

test('a link with values the preset does not take keeps the rest and says so', async () => {
  const other = await app.page.context().browser().newPage();
  try {
    await other.goto(`${app.url}#preset=taubin&iterations=7&lambda=abc&bogus=1`);
    await other.evaluate(() => window.__geoshift.ready);
    const { preset, params } = await shown(other);
    assert.equal(preset, 'taubin');
    assert.equal(params.iterations, 7);
    assert.equal(params.lambda, 0.5, 'a malformed number replaced the default');
    assert.match(await other.getByTestId('status').textContent(), /lambda, bogus were not understood/);
  } finally {
    await other.close();
  }
});

test('Back and Forward restore earlier settings', async () => {
  const { page } = app;
  await page.getByTestId('preset-select').selectOption('taubin');
  await setParams(page, { iterations: 11 });
  await setParams(page, { iterations: 22 });
  await page.getByTestId('preset-select').selectOption('curvature');
  await setParams(page, { kind: 'gauss' });

  const step = async (direction) => {
    await (direction === 'back' ? page.goBack() : page.goForward());
    await page.waitForTimeout(100);
    return shown(page);
  };
  assert.deepEqual(await step('back'), { preset: 'curvature', params: { kind: 'abs' } });
  assert.deepEqual((await step('back')).params.iterations, 22);
  assert.deepEqual((await step('back')).params.iterations, 11);
  const forward = await step('forward');
  assert.equal(forward.preset, 'taubin');
  assert.equal(forward.params.iterations, 22);
  assert.deepEqual(await step('forward'), { preset: 'curvature', params: { kind: 'abs' } });
  assert.deepEqual(await step('forward'), { preset: 'curvature', params: { kind: 'gauss' } });
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
