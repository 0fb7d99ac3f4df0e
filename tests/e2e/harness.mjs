// Shared set-up for the end-to-end tests: a Vite dev server for web/ on a free port and Debian's
// Chromium driven by playwright-core, both closed when the test file ends.
//
//   const app = useApp();            // registers before/after hooks
//   test('...', async () => { await app.page.... });
import { mkdirSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { after, before } from 'node:test';
import assert from 'node:assert/strict';
import { chromium } from 'playwright-core';
import { createServer } from 'vite';
import { analyze, decodePng } from './png.mjs';

const webRoot = fileURLToPath(new URL('../../web/', import.meta.url));
export const outputDir = fileURLToPath(new URL('../../test-output/e2e/', import.meta.url));

// Debian's Chromium through playwright-core, with the flags docs/testing.md#the-browser explains.
export const CHROMIUM = {
  executablePath: '/usr/bin/chromium',
  args: [
    '--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update',
    '--disable-sync', '--no-first-run', '--disable-quic',
  ],
};

/**
 * Starts server and browser before the file's tests and opens the app with its startup sample
 * loaded. The returned object is filled in by then: { url, page, pageErrors }. `query` is appended
 * to the page's URL (e.g. '?build=single' forces the single-threaded wasm build); `viewport` and
 * `hasTouch` make a phone of it.
 */
export function useApp({ query = '', viewport = { width: 800, height: 540 }, hasTouch = false } = {}) {
  const app = { url: '', page: null, pageErrors: [] };
  let server = null;
  let browser = null;
  before(async () => {
    mkdirSync(outputDir, { recursive: true });
    server = await createServer({
      root: webRoot,
      configFile: `${webRoot}vite.config.ts`,
      logLevel: 'warn',
      clearScreen: false,
      // No watcher and no HMR: files written under web/ by other builds must not reload the page
      // in the middle of a test.
      server: { host: '127.0.0.1', port: 0, strictPort: true, hmr: false, watch: null },
    });
    await server.listen();
    app.url = `http://127.0.0.1:${server.httpServer.address().port}/`;
    browser = await chromium.launch(CHROMIUM);
    app.page = await browser.newPage({ viewport, hasTouch });
    app.page.on('pageerror', (error) => app.pageErrors.push(error));
    await app.page.goto(app.url + query);
    await app.page.evaluate(() => window.__geoshift.ready);
  });
  after(async () => {
    await browser?.close();
    await server?.close();
  });
  return app;
}

/** The status line: { state: 'ok' | 'loading' | 'error', text }. */
export async function status(page) {
  return page.getByTestId('status').evaluate((el) => ({ state: el.dataset.state, text: el.textContent }));
}

export async function stats(page) {
  return page.evaluate(() => window.__geoshift.stats());
}

/** Gives a file to the file picker and waits until it is shown or rejected, and drawn. */
export async function openFile(page, name, contents) {
  await page.getByTestId('file-input').setInputFiles({
    name,
    mimeType: 'application/octet-stream',
    buffer: Buffer.isBuffer(contents) ? contents : Buffer.from(contents),
  });
  await waitForStatusAbout(page, name);
  return status(page);
}

export async function waitForStatusAbout(page, name) {
  await page.waitForFunction((n) => {
    const el = document.querySelector('[data-testid="status"]');
    return el.dataset.state !== 'loading' && el.textContent.includes(n);
  }, name, { timeout: 15_000 });
  await page.evaluate(() => window.__geoshift.settled());
}

/** Screenshots the 3D view into test-output/e2e/NAME.png and returns the decoded image. */
export async function shoot(page, name) {
  // The view's buttons and run state float over the canvas; they are not part of the picture.
  const png = await page.getByTestId('canvas').screenshot({ path: `${outputDir}${name}.png`, style: '.view-tools, .view-status { visibility: hidden; }' });
  return decodePng(png);
}

/** Asserts that the view shows a lit, centred mesh of reasonable size, and returns its analysis. */
export function assertMeshVisible(image, what) {
  const a = analyze(image);
  assert.ok(a.box, `${what}: the view shows only background`);
  assert.ok(a.distinctColours >= 8, `${what}: only ${a.distinctColours} distinct colours, is it lit?`);
  assert.ok(Math.abs(a.box.centreX - 0.5) < 0.15 && Math.abs(a.box.centreY - 0.5) < 0.15,
    `${what}: mesh not centred (${JSON.stringify(a.box)})`);
  assert.ok(Math.max(a.box.width, a.box.height) > 0.4, `${what}: mesh too small (${JSON.stringify(a.box)})`);
  return a;
}

/** Selects a preset, sets parameters (by key), runs it and waits until the run is over. */
export async function runPreset(page, presetId, values = {}) {
  await page.getByTestId('preset-select').selectOption(presetId);
  await setParams(page, values);
  await page.getByTestId('run-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  await page.evaluate(() => window.__geoshift.settled());
}

/**
 * Types numbers into the lil-gui fields of the current preset; choices (shown by label, sent by
 * value) are set through the page's hook. Live preview is off meanwhile: an entered value would
 * start a preview and a full run of its own (live-preview.ts), and these tests run when they say.
 */
export async function setParams(page, values) {
  const live = page.getByTestId('live-preview');
  const wasLive = await live.isChecked();
  if (wasLive) await live.uncheck();
  try {
    await typeParams(page, values);
  } finally {
    if (wasLive) await live.check();
  }
}

async function typeParams(page, values) {
  for (const [key, value] of Object.entries(values)) {
    const field = page.locator(`[data-param="${key}"]`);
    // Expert parameters sit in a folded folder: unfold it, as a person would.
    const folderTitle = page.locator(`.lil-gui.lil-closed:has([data-param="${key}"]) > .lil-title`);
    if (await folderTitle.count()) await folderTitle.first().click();
    if (typeof value === 'string') await page.evaluate(([k, v]) => window.__geoshift.setParam(k, v), [key, value]);
    else {
      const input = field.locator('input').first();
      await input.fill(String(value));
      await input.press('Enter');
    }
  }
}

export async function positions(page) {
  return page.evaluate(() => window.__geoshift.positions());
}

export async function lastRun(page) {
  return page.evaluate(() => window.__geoshift.lastRun());
}

/** The GLB that Export would download, as a Buffer. */
export async function exportedGlb(page) {
  return Buffer.from(await page.evaluate(() => window.__geoshift.exportGlb()), 'base64');
}
