// Latency of the live preview (the module's preview(): an op on a coarse wavelet level of at most
// 25,000 ... 750 vertices, brought back to every vertex) per mesh size, in Chromium with
// the threaded web flavour (a module worker of a cross-origin-isolated page, as the app runs it)
// and in Node with the single-threaded flavour. For each size: the first call (which analyses the mesh once), then
// the median of the following calls (the analysis reused), as a slider moving would make them.
// Issue 21 asks for previews within 200 ms in the threaded build on 2 cores, up to 1M vertices.
//
//   node bench/wasm/preview.mjs [--sizes 30000,100000,300000,1000000] [--levels 25000,12000,6000,3000,1500,750]
//                               [--repetitions 5] [--app-trials 5]
//
// The mesh: a terrain-like grid (hills and noise) with its height as the scalar _H. The jobs: the
// Terrain preset's filter of _H (mean shift, h_s 5, h_r 5, r 15), the Filter curvature preset (two
// wavelet levels), the Denoise preset and Taubin smoothing (10 steps). The web app's first-preview
// level comes from these (web/src/live-preview.ts, costPerVertex).
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';

import { loadGeoshift, wasmDir } from '../../tests/wasm/support.mjs';

const argv = process.argv.slice(2);
const option = (name, fallback) => {
  const i = argv.indexOf(name);
  return i >= 0 ? argv[i + 1] : fallback;
};
const sizes = option('--sizes', '30000,100000,300000,1000000').split(',').map(Number);
const repetitions = Number(option('--repetitions', 5));
// Fresh pages per gallery case for the app's first-drag latency.
const appTrials = Number(option('--app-trials', 5));
// The coarse-level sizes the web app steps through (web/src/live-preview.ts, PREVIEW_SIZES).
const LEVEL_SIZES = option('--levels', '25000,12000,6000,3000,1500,750').split(',').map(Number);
const CHROMIUM = '/usr/bin/chromium';

// Shared by Node and the browser worker (as source text): the grid, and the timing loop.
const SHARED = String.raw`
function terrainGrid(vertices) {
  const n = Math.max(4, Math.round(Math.sqrt(vertices)));
  const positions = new Float32Array(3 * n * n);
  const height = new Float32Array(n * n);
  let s = 7;
  const rand = () => ((s = (Math.imul(s, 1664525) + 1013904223) >>> 0) / 2 ** 32 - 0.5);
  for (let j = 0; j < n; ++j) {
    for (let i = 0; i < n; ++i) {
      const x = i / (n - 1) * 100, y = j / (n - 1) * 100;
      const z = 8 * Math.sin(x / 9) * Math.cos(y / 13) + 0.3 * rand() + (Math.hypot(x - 50, y - 50) < 10 ? 6 : 0);
      positions.set([x, y, z], 3 * (j * n + i));
      height[j * n + i] = z;
    }
  }
  const indices = new Uint32Array(6 * (n - 1) * (n - 1));
  let k = 0;
  for (let j = 0; j + 1 < n; ++j) {
    for (let i = 0; i + 1 < n; ++i) {
      const a = j * n + i;
      indices.set([a, a + 1, a + n + 1, a, a + n + 1, a + n], k);
      k += 6;
    }
  }
  return { positions, indices, height };
}
const JOBS = [
  { name: 'terrain filter', op: 'filter', params: { signal: '_H', mode: 'ms', hs: 5, hr: 5, radius: 15, kmax: 5 } },
  { name: 'curvature', op: 'filter', params: { signal: 'curvature', mode: 'ms', hs: 3, hr: 0.3, levels: 2, alpha: 0 } },
  { name: 'denoise', op: 'denoise', params: { method: 'meanshift' } },
  { name: 'taubin', op: 'smooth', params: { iterations: 10 } },
];
function measure(m, vertices, repetitions, levelSizes) {
  const mesh = terrainGrid(vertices);
  const loaded = m.loadMesh(mesh.positions, mesh.indices);
  if (!loaded.ok) throw new Error(loaded.error);
  const set = m.setAttribute(loaded.handle, '_H', 1, mesh.height);
  if (!set.ok) throw new Error(set.error);
  const rows = [];
  for (const job of JOBS) for (const maxVertices of levelSizes) {
    const times = [];
    const opTimes = [];
    let first = null;
    let stats = null;
    for (let k = 0; k <= repetitions; ++k) {
      const t0 = performance.now();
      const r = m.preview(loaded.handle, job.op, job.params, maxVertices);
      const ms = performance.now() - t0;
      if (!r.ok) throw new Error(job.name + ': ' + r.error);
      if (first === null) first = { ms, analysisMs: r.stats.analysisMs };
      else {
        times.push(ms);
        opTimes.push(r.stats.coarseOpMs);
      }
      stats = r.stats;
    }
    times.sort((a, b) => a - b);
    opTimes.sort((a, b) => a - b);
    rows.push({ job: job.name, vertices: loaded.vertexCount, maxVertices, coarse: stats.previewVertices, levels: stats.levels,
      firstMs: first.ms, analysisMs: first.analysisMs, medianMs: times[times.length >> 1], opMs: opTimes[opTimes.length >> 1], threads: stats.threadsAvailable });
  }
  m.freeMesh(loaded.handle);
  return rows;
}`;

const { measure } = new Function(`${SHARED}; return { measure };`)();

function print(title, rows) {
  console.log(`\n${title}`);
  console.log('job             vertices  max coarse  coarse  levels  first call ms (analysis)  next calls median ms (op on the coarse level)');
  for (const r of rows) {
    if (r.note) {
      console.log(`${r.job.padEnd(14)}  ${String(r.vertices ?? '-').padStart(8)}  ${r.note}`);
      continue;
    }
    console.log(`${r.job.padEnd(14)}  ${String(r.vertices).padStart(8)}  ${String(r.maxVertices).padStart(10)}  ${String(r.coarse).padStart(6)}  ${String(r.levels).padStart(6)}  ` +
      `${r.firstMs.toFixed(0).padStart(13)} (${r.analysisMs.toFixed(0).padStart(6)})  ${r.medianMs.toFixed(0).padStart(21)} (${r.opMs.toFixed(0).padStart(5)})`);
  }
}

async function chromiumRows() {
  const js = path.join(wasmDir, 'geoshift_web_mt.js');
  if (!fs.existsSync(CHROMIUM)) return [{ job: 'all', note: `skipped: ${CHROMIUM} is not installed` }];
  if (!fs.existsSync(js)) return [{ job: 'all', note: `skipped: ${js} is missing (build the wasm module)` }];
  const { chromium } = await import('playwright-core');
  const worker = `
    import create from '/wasm/geoshift_web_mt.js';
    ${SHARED}
    onmessage = async ({ data }) => {
      try {
        const cores = Math.min(navigator.hardwareConcurrency || 4, 8);
        Object.defineProperty(navigator, 'hardwareConcurrency', { value: cores, configurable: true });
        const m = await create({ mainScriptUrlOrBlob: new URL('/wasm/geoshift_web_mt.js', location.href).href });
        postMessage({ rows: measure(m, data.vertices, data.repetitions, data.levelSizes) });
      } catch (e) {
        postMessage({ error: String((e && e.message) || e) });
      }
    };`;
  const page = `<!doctype html><script type="module">
    window.bench = (data) => new Promise((resolve) => {
      const w = new Worker('/worker.js', { type: 'module' });
      w.onmessage = (e) => { resolve(e.data); w.terminate(); };
      w.onerror = (e) => resolve({ error: e.message || 'worker failed to start' });
      w.postMessage(data);
    });</script>`;
  const server = http.createServer((req, res) => {
    const headers = { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' };
    const url = new URL(req.url, 'http://localhost');
    let body;
    let type = 'text/javascript';
    if (url.pathname === '/') [body, type] = [page, 'text/html'];
    else if (url.pathname === '/worker.js') body = worker;
    else if (url.pathname.startsWith('/wasm/') && /^[\w.]+$/.test(path.basename(url.pathname))) {
      const file = path.join(wasmDir, path.basename(url.pathname));
      if (fs.existsSync(file)) {
        body = fs.readFileSync(file);
        if (file.endsWith('.wasm')) type = 'application/wasm';
      }
    }
    if (body === undefined) return res.writeHead(404, headers).end();
    res.writeHead(200, { ...headers, 'Content-Type': type }).end(body);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const browser = await chromium.launch({ executablePath: CHROMIUM, args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--no-first-run'] });
  const rows = [];
  try {
    const tab = await browser.newPage();
    await tab.goto(`http://127.0.0.1:${server.address().port}/`);
    for (const vertices of sizes) {
      const result = await tab.evaluate((data) => window.bench(data), { vertices, repetitions, levelSizes: LEVEL_SIZES });
      if (result.error) rows.push({ job: 'all', vertices, note: `failed: ${result.error}` });
      else rows.push(...result.rows);
    }
  } finally {
    await browser.close();
    server.close();
  }
  return rows;
}

/**
 * The app itself (Vite dev server, threaded build): for each gallery case, a fresh page, the case
 * opened and left to settle (the live preview analyses its levels then), then one drag of a slider
 * with a step every 20 ms. Measures the time from the first step that changed the value ("computing
 * preview…" shown) to the first preview on screen, and the previews' own times during the drag.
 * Includes drawing, which headless Chromium does in software on the same cores.
 */
async function appRows() {
  if (!fs.existsSync(CHROMIUM)) return [{ job: 'app', note: `skipped: ${CHROMIUM} is not installed` }];
  const { chromium } = await import('playwright-core');
  const { createServer } = await import('vite');
  const webRoot = new URL('../../web/', import.meta.url).pathname;
  const server = await createServer({ root: webRoot, configFile: `${webRoot}vite.config.ts`, logLevel: 'warn', server: { host: '127.0.0.1', port: 0, hmr: false, watch: null } });
  await server.listen();
  const url = `http://127.0.0.1:${server.httpServer.address().port}/`;
  const browser = await chromium.launch({ executablePath: CHROMIUM, args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--no-first-run'] });
  const rows = [];
  try {
    for (const [caseId, param] of [['noisy-scan', 'strength'], ['cad-part', 'hr'], ['colored-mesh', 'hr'], ['terrain', 'hr']]) {
      const first = [], during = [];
      let vertices = 0, coarse = 0;
      for (let k = 0; k < appTrials; k++) {
        const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
        await page.goto(`${url}#case=${caseId}`);
        await page.evaluate(() => window.__geoshift.ready);
        await page.evaluate(() => window.__geoshift.settled());
        vertices = (await page.evaluate(() => window.__geoshift.stats())).vertices;
        await page.evaluate(() => {
          const kind = document.querySelector('[data-testid="result-kind"]');
          window.__computing = null;
          new MutationObserver(() => { if (kind.dataset.kind === 'computing' && window.__computing === null) window.__computing = performance.now(); }).observe(kind, { attributes: true });
        });
        const box = await page.locator(`[data-param="${param}"] .lil-slider`).boundingBox();
        const y = box.y + box.height / 2;
        await page.mouse.move(box.x + box.width * 0.3, y);
        await page.mouse.down();
        for (let i = 1; i <= 60; i++) {
          await page.mouse.move(box.x + box.width * (0.3 + (i % 30) * 0.01), y);
          await page.waitForTimeout(20);
        }
        await page.waitForFunction(() => window.__geoshift.previewEvents().some((e) => e.kind === 'preview'), null, { timeout: 60_000 });
        const [events, computing] = await page.evaluate(() => [window.__geoshift.previewEvents(), window.__computing]);
        const previews = events.filter((e) => e.kind === 'preview');
        first.push(previews[0].at - computing);
        during.push(...previews.map((e) => e.ms));
        coarse = previews[0].vertices;
        await page.mouse.up();
        await page.close();
      }
      const median = (a) => [...a].sort((x, y) => x - y)[a.length >> 1];
      rows.push({ caseId, vertices, coarse, first: median(first), during: median(during), trials: appTrials });
    }
  } finally {
    await browser.close();
    await server.close();
  }
  return rows;
}

console.log(`live preview latency: preview() on a coarse level of at most ${LEVEL_SIZES.join(' / ')} vertices; ${os.cpus().length} cores; ` +
  `${repetitions} calls after the first`);
const appResult = await appRows();
console.log(`\nThe app in Chromium (gallery cases, ${appTrials} fresh pages each, medians): first drag`);
console.log('case            vertices  coarse  first preview after the first step ms  preview ms during the drag');
for (const r of appResult) {
  if (r.note) console.log(`${r.job.padEnd(14)}  ${r.note}`);
  else console.log(`${r.caseId.padEnd(14)}  ${String(r.vertices).padStart(8)}  ${String(r.coarse).padStart(6)}  ${r.first.toFixed(0).padStart(37)}  ${r.during.toFixed(0).padStart(26)}`);
}
print('Chromium, threaded web build', await chromiumRows());
try {
  const m = await loadGeoshift();
  const rows = [];
  for (const vertices of sizes) rows.push(...measure(m, vertices, repetitions, LEVEL_SIZES));
  print('Node, single-threaded build', rows);
} catch (e) {
  console.log(`\nNode, single-threaded build: skipped (${e.message.split('\n')[0]})`);
}
