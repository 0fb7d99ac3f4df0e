// Makes the before/after pictures of docs/denoising.md#real-scans headlessly: each real scan of
// ../shared/data (no ground truth) opened in the app, denoised with the Denoise preset's defaults,
// and shown in the split view (input left, result right). Prints what the denoiser measured and
// chose for each, as a Markdown table.
//
//   node scripts/denoise-figures.mjs      (after scripts/bootstrap.sh has built the wasm module)
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { createServer } from 'vite';
import { CHROMIUM, openFile } from '../tests/e2e/harness.mjs';
import { analyze, decodePng } from '../tests/e2e/png.mjs';

const root = fileURLToPath(new URL('../', import.meta.url));
const webRoot = path.join(root, 'web/');
const data = process.env.GEOSHIFT_SHARED_DATA || path.join(root, '../shared/data');
const scans = ['angel/angel.obj', 'rabbit/rabbit.obj', 'iron/iron.ply']
  .map((f) => path.join(data, 'guided_denoising_bldeng/models/RealData', f));
const outDir = path.join(root, 'docs/images');

const present = scans.filter((f) => fs.existsSync(f));
if (present.length === 0) {
  console.log(`skipped: no real scans under ${data} (../shared/data absent)`);
  process.exit(0);
}
fs.mkdirSync(outDir, { recursive: true });
const server = await createServer({
  root: webRoot, configFile: `${webRoot}vite.config.ts`, logLevel: 'warn', clearScreen: false,
  server: { host: '127.0.0.1', port: 0, strictPort: true, hmr: false, watch: null },
});
await server.listen();
const browser = await chromium.launch(CHROMIUM);
const rows = [];
try {
  for (const file of present) {
    const name = path.basename(file, path.extname(file));
    // The app's desktop layout; the picture is the 3D view only, the mesh framed to fill it
    // (viewer.ts: tight framing, the scan's front), so that a reader sees the surface, not a
    // small mesh far away (issue 30).
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    await page.goto(`http://127.0.0.1:${server.httpServer.address().port}/`);
    await page.evaluate(() => window.__geoshift.ready);
    await page.evaluate(() => window.__geoshift.workerReady());
    await openFile(page, path.basename(file), fs.readFileSync(file));
    await page.getByTestId('preset-select').selectOption('denoise');
    await page.getByTestId('run-button').click();
    await page.evaluate(() => window.__geoshift.idle());
    const error = await page.evaluate(() => window.__geoshift.lastError());
    if (error) throw new Error(`${name}: denoise failed: ${error}`);
    const report = await page.evaluate(() => window.__geoshift.lastRun());
    await page.getByTestId('split-slider').fill('50');
    await page.evaluate(() => window.__geoshift.settled());
    const out = path.join(outDir, `denoise-${name}.png`);
    await page.getByTestId('canvas').screenshot({ path: out, style: '.view-tools, .view-status { visibility: hidden; }' });
    // The share of the view the mesh fills, measured without the split line.
    const { box } = analyze(decodePng(await page.getByTestId('canvas').screenshot({ style: '.view-tools, .view-status, .split-line { visibility: hidden; }' })));
    console.error(`${name}: the mesh spans ${(100 * box.width).toFixed(0)}% × ${(100 * box.height).toFixed(0)}% of the view; ${(fs.statSync(out).size / 1024).toFixed(0)} KiB`);
    const s = report.stats[0];
    rows.push(`| ${name} | ${report.vertices} | ${Number(s.noiseLevel).toFixed(3)} | ${s.presmoothingSteps}${s.taubinOnly === 'yes' ? ' (Taubin only)' : ` + ${s.passes}`} ` +
      `| ${(report.computeMs / 1000).toFixed(1)} s | ![${name}](images/denoise-${name}.png) |`);
    console.error(`wrote ${out}`);
    await page.close();
  }
} finally {
  await browser.close();
  await server.close();
}
console.log('| scan | vertices | noise level (AEL, measured) | Taubin steps + passes (SURE) | time in the app | input \\| result |');
console.log('|---|---|---|---|---|---|');
for (const r of rows) console.log(r);
