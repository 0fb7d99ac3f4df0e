// The same denoise job natively (the CLI, one thread and all cores), in Node wasm (the
// single-threaded flavour) and in Chromium wasm with threads (the threaded web flavour in a module
// worker of a cross-origin-isolated page), as a table of median times and the wasm/native speed
// ratio (issue 7: wasm on one thread should reach 0.6x native).
//
//   node bench/wasm/denoise.mjs [--vertices N] [--repetitions R] [--preset default|paper]
//                               [--only native|node|chromium]
//
// GEOSHIFT_NATIVE_CLI and GEOSHIFT_WASM_DIR pick other builds (defaults: build/native-release,
// build/wasm-release). The job: a torus of about N vertices (default 10k) with noise of 0.3 average
// edge lengths in random directions, denoised with the op's defaults (or --preset paper). Natively
// it also prints the peak memory per vertex (docs/denoising.md#speed-and-memory has the targets).
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';

import { loadGeoshift, median, nativeCli, wasmDir, writeOff } from '../../tests/wasm/support.mjs';

const argv = process.argv.slice(2);
const option = (name, fallback) => {
  const i = argv.indexOf(name);
  return i >= 0 ? Number(argv[i + 1]) : fallback;
};
const targetVertices = option('--vertices', 10000);
// --preset paper: the paper's pipeline (the default denoiser before docs/denoising.md's rebuild).
const presetIndex = argv.indexOf('--preset');
const preset = presetIndex >= 0 ? argv[presetIndex + 1] : 'default';
if (!['default', 'paper'].includes(preset)) throw new Error(`--preset must be default or paper (got ${preset})`);
const repetitions = option('--repetitions', 3);
// --only: one of the three flavours (for comparing two builds of it, run after run).
const onlyIndex = argv.indexOf('--only');
const only = onlyIndex >= 0 ? argv[onlyIndex + 1] : undefined;
if (only !== undefined && !['native', 'node', 'chromium'].includes(only)) {
  throw new Error(`--only must be native, node or chromium (got ${only})`);
}
const runs = (flavour) => only === undefined || only === flavour;
const CHROMIUM = '/usr/bin/chromium';

// A closed torus (no seam copies), about `vertices` vertices, with seeded noise.
function noisyTorus(vertices) {
  const m = Math.max(8, Math.round(Math.sqrt(vertices / 2.8)));
  const n = Math.max(8, Math.round(vertices / m));
  const R = 1;
  const r = 0.35;
  const positions = new Float32Array(3 * n * m);
  for (let j = 0; j < m; ++j) {
    for (let i = 0; i < n; ++i) {
      const u = (2 * Math.PI * i) / n;
      const v = (2 * Math.PI * j) / m;
      positions.set([Math.cos(u) * (R + r * Math.cos(v)), Math.sin(u) * (R + r * Math.cos(v)), r * Math.sin(v)], 3 * (j * n + i));
    }
  }
  const indices = [];
  const at = (i, j) => (j % m) * n + (i % n);
  for (let j = 0; j < m; ++j) {
    for (let i = 0; i < n; ++i) indices.push(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1));
  }
  // Noise: 0.3 x the mean edge length (about the circumference over n), random directions.
  const amount = 0.3 * ((2 * Math.PI * R) / n + (2 * Math.PI * r) / m) / 2;
  let s = 12345;
  const rand = () => ((s = (Math.imul(s, 1664525) + 1013904223) >>> 0) / 2 ** 31 - 1);
  for (let k = 0; k < positions.length; k += 3) {
    let d;
    do d = [rand(), rand(), rand()]; while (Math.hypot(...d) > 1 || Math.hypot(...d) < 1e-3);
    const len = Math.hypot(...d);
    for (let c = 0; c < 3; ++c) positions[k + c] += (amount * d[c]) / len;
  }
  return { positions, indices: new Uint32Array(indices) };
}

async function main() {
  const mesh = noisyTorus(targetVertices);
  const vertexCount = mesh.positions.length / 3;
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'geoshift-bench-'));
  const off = path.join(dir, 'torus.off');
  writeOff(off, mesh);
  const job = preset === 'paper'
    ? "the paper preset: 3 passes, h_s 3, r 4, h_r 0.45, k_max 50, 20 vertex steps"
    : 'the default: noise estimated, face-normal mean shift, smoothing chosen by SURE';
  console.log(`job: denoise (${job}) of a noisy torus, ${vertexCount} vertices; median of ${repetitions} runs; ` +
    `${os.cpus().length} cores`);
  const rows = [];

  // Native: the CLI's own timing of the filter (file reading and writing excluded).
  for (const threads of runs('native') ? [1, 0] : []) {
    if (!fs.existsSync(nativeCli)) {
      rows.push({ what: `native CLI, ${threads || 'all'} thread(s)`, note: `skipped: ${nativeCli} is missing` });
      continue;
    }
    const times = [];
    for (let k = 0; k < repetitions; ++k) {
      const r = spawnSync(nativeCli, ['denoise', off, '-o', path.join(dir, 'native.glb'), '--preset', preset,
        '--threads', String(threads)], { encoding: 'utf8' });
      if (r.status !== 0) throw new Error(`native denoise failed: ${r.stderr}`);
      const ms = /filter (\d+) ms/.exec(r.stderr);
      if (!ms) throw new Error(`no timing in the CLI's output: ${r.stderr}`);
      times.push(Number(ms[1]));
    }
    rows.push({ what: `native CLI, ${threads ? '1 thread' : `all cores (${os.cpus().length})`}`, ms: median(times), native: threads === 1 });
  }
  // Peak memory of the whole native process (reading and writing included), when GNU time is there.
  if (runs('native') && fs.existsSync(nativeCli) && fs.existsSync('/usr/bin/time')) {
    const r = spawnSync('/usr/bin/time', ['-f', 'peak %M KB', nativeCli, 'denoise', off, '-o', path.join(dir, 'native.glb'),
      '--preset', preset], { encoding: 'utf8' });
    const kb = /peak (\d+) KB/.exec(r.stderr);
    if (kb) console.log(`native peak memory: ${(Number(kb[1]) / 1024).toFixed(0)} MB, ` +
      `${((Number(kb[1]) * 1024) / vertexCount).toFixed(0)} bytes per vertex`);
  }

  if (runs('native')) scanMemory(dir);

  if (runs('node')) rows.push(await nodeRow(mesh));
  if (runs('chromium')) rows.push(await chromiumRow(mesh));

  const native1 = rows.find((r) => r.native)?.ms;
  const wasm1 = rows.find((r) => r.wasm1)?.ms;
  const width = Math.max(...rows.map((r) => r.what.length));
  console.log(`${'run'.padEnd(width)}  ${'median ms'.padStart(10)}  speed vs native 1 thread`);
  for (const r of rows) {
    if (r.ms === undefined) {
      console.log(`${r.what.padEnd(width)}  ${'-'.padStart(10)}  ${r.note}`);
      continue;
    }
    const ratio = native1 ? `${(native1 / r.ms).toFixed(2)}x` : '-';
    console.log(`${r.what.padEnd(width)}  ${r.ms.toFixed(0).padStart(10)}  ${ratio}${r.note ? `  (${r.note})` : ''}`);
  }
  if (native1 && wasm1) {
    const ratio = native1 / wasm1;
    console.log(`wasm (1 thread) / native (1 thread) speed: ${ratio.toFixed(2)} (target >= 0.60: ${ratio >= 0.6 ? 'met' : 'NOT met'})`);
  }
  fs.rmSync(dir, { recursive: true, force: true });
}

// Node wasm, single-threaded flavour: time inside run(), the copy of the result included.
async function nodeRow(mesh) {
  try {
    const geoshift = await loadGeoshift();
    const times = [];
    for (let k = 0; k < repetitions; ++k) {
      const { handle } = geoshift.loadMesh(mesh.positions, mesh.indices);
      const r = geoshift.run(handle, 'denoise', { preset });
      geoshift.freeMesh(handle);
      if (!r.ok) throw new Error(r.error);
      times.push(r.stats.timeMs);
    }
    return { what: 'Node wasm, 1 thread', ms: median(times), wasm1: true };
  } catch (e) {
    return { what: 'Node wasm, 1 thread', note: `skipped: ${e.message.split('\n')[0]}` };
  }
}

// Peak memory on a scan read from OBJ (issue 27's second case): Julius's clean mesh with every
// triangle split in four (about 144k vertices), 0.3 AEL of fixed noise from `geoshift noise --seed 3`,
// denoised by the CLI into OBJ. Skipped when ../shared/data is absent.
function scanMemory(dir) {
  const data = process.env.GEOSHIFT_SHARED_DATA || path.resolve(import.meta.dirname, '../../../shared/data');
  const julius = path.join(data, 'guided_denoising_bldeng/models/Julius0.2/Original.obj');
  if (!fs.existsSync(julius) || !fs.existsSync(nativeCli) || !fs.existsSync('/usr/bin/time')) {
    console.log('scan peak memory: skipped (needs ../shared/data, the native CLI and /usr/bin/time)');
    return;
  }
  const v = [];
  const f = [];
  for (const line of fs.readFileSync(julius, 'utf8').split('\n')) {
    const t = line.trim().split(/\s+/);
    if (t[0] === 'v') v.push([Number(t[1]), Number(t[2]), Number(t[3])]);
    else if (t[0] === 'f') f.push(t.slice(1, 4).map((s) => Number(s.split('/')[0]) - 1));
  }
  // Midpoints shared by the two faces of an edge.
  const mid = new Map();
  const midpoint = (a, b) => {
    const key = a < b ? `${a},${b}` : `${b},${a}`;
    if (!mid.has(key)) {
      mid.set(key, v.length);
      v.push([0, 1, 2].map((c) => (v[a][c] + v[b][c]) / 2));
    }
    return mid.get(key);
  };
  const faces = [];
  for (const [a, b, c] of f) {
    const ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    faces.push([a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]);
  }
  const clean = path.join(dir, 'julius4.obj');
  fs.writeFileSync(clean, v.map((p) => `v ${p.join(' ')}`).join('\n') + '\n' +
    faces.map((t) => `f ${t[0] + 1} ${t[1] + 1} ${t[2] + 1}`).join('\n') + '\n');
  const noisy = path.join(dir, 'julius4-noisy.obj');
  const n = spawnSync(nativeCli, ['noise', clean, '-o', noisy, '--amount', '0.3', '--dist', 'fixed', '--seed', '3'], { encoding: 'utf8' });
  if (n.status !== 0) throw new Error(`noise failed: ${n.stderr}`);
  const r = spawnSync('/usr/bin/time', ['-f', 'peak %M KB', nativeCli, 'denoise', noisy, '-o', path.join(dir, 'julius4-out.obj')],
    { encoding: 'utf8' });
  const kb = /peak (\d+) KB/.exec(r.stderr);
  if (r.status !== 0 || !kb) throw new Error(`scan denoise failed: ${r.stderr}`);
  console.log(`scan peak memory (Julius split in four, ${v.length} vertices, OBJ in and out): ${(Number(kb[1]) / 1024).toFixed(0)} MB, ` +
    `${((Number(kb[1]) * 1024) / v.length).toFixed(0)} bytes per vertex`);
}

// The threaded web flavour in a module worker of a page served with COOP/COEP (so that
// SharedArrayBuffer and the pthread pool are available), driven by playwright-core.
async function chromiumRow(mesh) {
  const what = 'Chromium wasm, threads';
  const js = path.join(wasmDir, 'geoshift_web_mt.js');
  if (!fs.existsSync(CHROMIUM)) return { what, note: `skipped: ${CHROMIUM} is not installed` };
  if (!fs.existsSync(js)) return { what, note: `skipped: ${js} is missing (build the wasm module)` };
  let chromium;
  try {
    ({ chromium } = await import('playwright-core'));
  } catch {
    return { what, note: 'skipped: playwright-core is not installed (npm ci)' };
  }
  const worker = `
    import create from '/wasm/geoshift_web_mt.js';
    onmessage = async ({ data }) => {
      try {
        const cores = Math.min(navigator.hardwareConcurrency || 4, 8);
        Object.defineProperty(navigator, 'hardwareConcurrency', { value: cores, configurable: true });
        const m = await create({ mainScriptUrlOrBlob: new URL('/wasm/geoshift_web_mt.js', location.href).href });
        const positions = Float32Array.from(data.positions);
        const indices = Uint32Array.from(data.indices);
        const times = [];
        let threads = 0;
        for (let k = 0; k < data.repetitions; ++k) {
          const { handle } = m.loadMesh(positions, indices);
          const r = m.run(handle, 'denoise', { preset: ${JSON.stringify(preset)} });
          m.freeMesh(handle);
          if (!r.ok) throw new Error(r.error);
          times.push(r.stats.timeMs);
          threads = r.stats.threads;
        }
        postMessage({ times, threads });
      } catch (e) {
        postMessage({ error: String(e && e.message || e) });
      }
    };`;
  const page = `<!doctype html><script type="module">
    window.bench = (data) => new Promise((resolve) => {
      const w = new Worker('/worker.js', { type: 'module' });
      w.onmessage = (e) => resolve(e.data);
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
    if (body === undefined) {
      res.writeHead(404, headers).end();
      return;
    }
    res.writeHead(200, { ...headers, 'Content-Type': type }).end(body);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    args: ['--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update',
      '--disable-sync', '--no-first-run', '--disable-quic'],
  });
  try {
    const tab = await browser.newPage();
    await tab.goto(`http://127.0.0.1:${server.address().port}/`);
    const result = await tab.evaluate((data) => window.bench(data),
      { positions: Array.from(mesh.positions), indices: Array.from(mesh.indices), repetitions });
    if (result.error) return { what, note: `failed: ${result.error}` };
    return { what: `${what} (${result.threads})`, ms: median(result.times) };
  } finally {
    await browser.close();
    server.close();
  }
}

await main();
