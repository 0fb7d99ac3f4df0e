// Makes web/screenshots/app-compare.png, the README's picture, headlessly: the app's sample scan
// with noise added, denoised with the Denoise preset, before | after in the split view.
//
//   node scripts/screenshot.mjs        (after scripts/bootstrap.sh has built the wasm module)
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { createServer } from 'vite';
import { CHROMIUM } from '../tests/e2e/harness.mjs';

const webRoot = fileURLToPath(new URL('../web/', import.meta.url));
const out = fileURLToPath(new URL('../web/screenshots/app-compare.png', import.meta.url));

const server = await createServer({
  root: webRoot, configFile: `${webRoot}vite.config.ts`, logLevel: 'warn', clearScreen: false,
  server: { host: '127.0.0.1', port: 0, strictPort: true, hmr: false, watch: null },
});
await server.listen();
const browser = await chromium.launch(CHROMIUM);
try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 700 } });
  await page.goto(`http://127.0.0.1:${server.httpServer.address().port}/`);
  await page.evaluate(() => window.__geoshift.ready);
  await page.evaluate(() => window.__geoshift.workerReady());
  await page.getByTestId('add-noise-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  await page.getByTestId('preset-select').selectOption('denoise');
  await page.getByTestId('run-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  const error = await page.evaluate(() => window.__geoshift.lastError());
  if (error) throw new Error(`denoise failed: ${error}`);
  await page.getByTestId('split-slider').fill('50');
  await page.evaluate(() => window.__geoshift.settled());
  await page.screenshot({ path: out });
  console.log(`wrote ${out}`);
} finally {
  await browser.close();
  await server.close();
}
