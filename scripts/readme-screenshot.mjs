// Writes docs/screenshot.png, the README's picture: a gallery case mid-demo, the noisy CAD part's
// curvature filtered, before | after in the split view (the raw field speckled by the noise on the
// left, the filtered one on the right) with the legend and the panel's result, at the app's desktop
// size, taken in headless Chromium from the app served by Vite. Prints how much of the view the
// mesh fills. Run after the wasm build: node scripts/readme-screenshot.mjs
import { statSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { createServer } from 'vite';
import { CHROMIUM } from '../tests/e2e/harness.mjs';
import { analyze, decodePng } from '../tests/e2e/png.mjs';

const webRoot = fileURLToPath(new URL('../web/', import.meta.url));
const out = fileURLToPath(new URL('../docs/screenshot.png', import.meta.url));
const server = await createServer({
  root: webRoot, configFile: `${webRoot}vite.config.ts`, logLevel: 'warn',
  server: { host: '127.0.0.1', port: 0, hmr: false, watch: null },
});
await server.listen();
const browser = await chromium.launch(CHROMIUM);
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  await page.goto(`http://127.0.0.1:${server.httpServer.address().port}/#case=cad-part`);
  await page.evaluate(() => window.__geoshift.ready);
  await page.evaluate(() => window.__geoshift.settled());
  await page.getByTestId('run-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  const error = await page.evaluate(() => window.__geoshift.lastError());
  if (error) throw new Error(`the run failed: ${error}`);
  await page.getByTestId('split-slider').fill('50');
  // The gallery and its hint at the top of the panel, as someone opening the link sees it.
  await page.evaluate(() => document.querySelector('.panel').scrollTo(0, 0));
  await page.evaluate(() => window.__geoshift.settled());
  const view = analyze(decodePng(await page.getByTestId('canvas').screenshot({ style: '.view-tools, .view-status, .legend, .split-line { visibility: hidden; }' })));
  await page.screenshot({ path: out });
  console.log(`wrote ${out} (${(statSync(out).size / 1024).toFixed(0)} KiB); the mesh spans ${(100 * view.box.width).toFixed(0)}% × ${(100 * view.box.height).toFixed(0)}% of the view`);
} finally {
  await browser.close();
  await server.close();
}
