// Writes docs/screenshot.png, the README's picture: a gallery case mid-demo (the Autzen terrain,
// its height above ground filtered, before | after in the split view with the legend), taken in
// headless Chromium from the app served by Vite. Run after the wasm build: node scripts/readme-screenshot.mjs
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { createServer } from 'vite';

const webRoot = fileURLToPath(new URL('../web/', import.meta.url));
const out = fileURLToPath(new URL('../docs/screenshot.png', import.meta.url));
const server = await createServer({
  root: webRoot, configFile: `${webRoot}vite.config.ts`, logLevel: 'warn',
  server: { host: '127.0.0.1', port: 0, hmr: false, watch: null },
});
await server.listen();
const browser = await chromium.launch({ executablePath: '/usr/bin/chromium', args: ['--no-sandbox', '--disable-gpu', '--no-first-run'] });
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  await page.goto(`http://127.0.0.1:${server.httpServer.address().port}/#case=terrain&preset=terrain&signal=_height_above_ground`);
  await page.evaluate(() => window.__geoshift.ready);
  await page.getByTestId('run-button').click();
  await page.evaluate(() => window.__geoshift.idle());
  const error = await page.evaluate(() => window.__geoshift.lastError());
  if (error) throw new Error(`the run failed: ${error}`);
  await page.getByTestId('split-slider').fill('50');
  // The gallery and its hint at the top of the panel, as someone opening the link sees it.
  await page.evaluate(() => document.querySelector('.panel').scrollTo(0, 0));
  await page.evaluate(() => window.__geoshift.settled());
  await page.screenshot({ path: out });
  console.log(`wrote ${out}`);
} finally {
  await browser.close();
  await server.close();
}
