// `npm run build` (vite build web) makes a static bundle that `vite preview` serves with the COOP/COEP
// headers: the page is cross-origin isolated, the threaded WebAssembly build starts in the worker,
// and a filter runs; without the headers the single-threaded build takes over. The bundle is built
// into a temporary folder, not the repository's dist/.
import assert from 'node:assert/strict';
import { existsSync, mkdtempSync, readdirSync, rmSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { after, before, test } from 'node:test';
import { chromium } from 'playwright-core';
import { build, preview } from 'vite';
import { CHROMIUM, outputDir } from './harness.mjs';

const webRoot = fileURLToPath(new URL('../../web/', import.meta.url));
let outDir, server, browser, page, url;
const pageErrors = [];

before(async () => {
  outDir = mkdtempSync(path.join(os.tmpdir(), 'geoshift-dist-'));
  const config = { root: webRoot, configFile: `${webRoot}vite.config.ts`, logLevel: 'warn', build: { outDir, emptyOutDir: true } };
  await build(config);
  server = await preview({ ...config, preview: { host: '127.0.0.1', port: 0, strictPort: true } });
  url = server.resolvedUrls.local[0];
  browser = await chromium.launch(CHROMIUM);
  page = await browser.newPage({ viewport: { width: 800, height: 540 } });
  page.on('pageerror', (error) => pageErrors.push(error));
  await page.goto(url);
  await page.evaluate(() => window.__geoshift.ready);
});

after(async () => {
  await browser?.close();
  await new Promise((resolve) => (server ? server.httpServer.close(resolve) : resolve()));
  if (outDir) rmSync(outDir, { recursive: true, force: true });
});

test('the bundle holds the app and both wasm builds of the geoshift package, and no decoder from elsewhere', () => {
  assert.ok(existsSync(path.join(outDir, 'index.html')), 'index.html is missing from the bundle');
  // The package's files, copied by Vite from its `new URL(..., import.meta.url)` literals (hashed names).
  const assets = readdirSync(path.join(outDir, 'assets'));
  for (const file of [/^geoshift_web-.*\.js$/, /^geoshift_web-.*\.wasm$/, /^geoshift_web_mt-.*\.js$/, /^geoshift_web_mt-.*\.wasm$/, /^worker-.*\.js$/]) {
    assert.ok(assets.some((a) => file.test(a)), `${file} matches nothing in the bundle's assets: ${assets.join(', ')}`);
  }
});

test('vite preview serves it cross-origin isolated, and the threaded build runs a filter', async () => {
  const response = await page.request.get(url);
  assert.equal(response.headers()['cross-origin-opener-policy'], 'same-origin');
  assert.equal(response.headers()['cross-origin-embedder-policy'], 'require-corp');
  assert.equal(await page.evaluate(() => window.crossOriginIsolated), true);
  const info = await page.evaluate(() => window.__geoshift.workerReady());
  assert.equal(info.threaded, true);
  await page.getByTestId('preset-select').selectOption('curvature');
  await page.getByTestId('run-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  const report = await page.evaluate(() => window.__geoshift.lastRun());
  assert.ok(report, await page.evaluate(() => window.__geoshift.lastError()));
  await page.screenshot({ path: `${outputDir}bundle-preview.png` });
});

test('served without the headers, the app falls back to the single-threaded build and still filters', async () => {
  const plain = await browser.newPage({ viewport: { width: 800, height: 540 } });
  plain.on('pageerror', (error) => pageErrors.push(error));
  // As a host that does not send COOP/COEP: the same files, the two headers removed.
  await plain.route('**/*', async (route) => {
    const response = await route.fetch();
    const headers = { ...response.headers() };
    delete headers['cross-origin-opener-policy'];
    delete headers['cross-origin-embedder-policy'];
    await route.fulfill({ response, headers });
  });
  await plain.goto(url);
  await plain.evaluate(() => window.__geoshift.ready);
  assert.equal(await plain.evaluate(() => window.crossOriginIsolated), false);
  assert.equal((await plain.evaluate(() => window.__geoshift.workerReady())).threaded, false);
  await plain.getByTestId('add-noise-button').click();
  await plain.evaluate(() => window.__geoshift.idle());
  assert.ok(await plain.evaluate(() => window.__geoshift.lastRun()), await plain.evaluate(() => window.__geoshift.lastError()));
  await plain.close();
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(pageErrors.map(String), []);
});
