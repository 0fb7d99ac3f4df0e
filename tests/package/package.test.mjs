// The npm package as its users meet it: packed with `npm pack`, installed offline into a fresh
// project outside the repository (three and the type packages from the npm cache that the
// bootstrap's `npm ci` filled), type-checked against the packed declarations (mistakes in options
// must not compile), run under Node, and bundled with Vite into a page that denoises a three.js
// BufferGeometry in Chromium, cross-origin isolated (threads) and not (one thread). Results are
// compared with the native CLI's on the same input (1e-5, as the other parity tests).
//
//   node --test tests/package/       (needs the wasm build, package/dist and the native CLI)
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { gzipSync } from 'node:zlib';
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { chromium } from 'playwright-core';
import { build, createServer, preview } from 'vite';

import { CHROMIUM } from '../e2e/harness.mjs';
import { repoRoot } from '../wasm/support.mjs';
import { assertClose, box, jiggle, runNative, twoColorSphere, writeCoff } from '../wasm/filter-support.mjs';

const userDir = path.join(repoRoot, 'tests/package/user');
const tsc = path.join(repoRoot, 'node_modules/typescript/bin/tsc');

const noisy = jiggle(box(6), 0.06);
let dir;          // the user's project
let tarball;
let packed;       // npm pack's report: files and sizes
let cli;          // the native CLI's positions: { default, taubin }
let browser;

/**
 * package.json and package-lock.json of a user's project that depends on the tarball and on
 * `others` at the versions of the repository's lock, with their dependencies: `npm ci --offline`
 * then takes every tarball from the npm cache, which the bootstrap's `npm ci` filled (a plain
 * `npm install three --offline` would need the registry's package metadata, which npm ci does not
 * cache).
 */
function userProject(into, pack, others) {
  const lock = JSON.parse(fs.readFileSync(path.join(repoRoot, 'package-lock.json'), 'utf8')).packages;
  const packages = {};
  // Node's lookup: the dependency beside the dependent, else in each enclosing node_modules.
  const resolve = (from, name) => {
    for (let at = from; ; at = at.slice(0, at.lastIndexOf('/node_modules/'))) {
      const candidate = `${at ? `${at}/` : ''}node_modules/${name}`;
      if (lock[candidate]) return candidate;
      if (!at.includes('/node_modules/')) {
        if (at === '') throw new Error(`package-lock.json has no ${name} (needed by ${from || 'the project'})`);
        at = '';
        if (lock[`node_modules/${name}`]) return `node_modules/${name}`;
        throw new Error(`package-lock.json has no ${name} (needed by ${from})`);
      }
    }
  };
  const add = (where) => {
    if (packages[where]) return;
    const { dev, devOptional, peer, optional, ...entry } = lock[where];
    packages[where] = entry;
    for (const name of Object.keys(entry.dependencies ?? {})) add(resolve(where, name));
  };
  const dependencies = { geoshift: `file:${pack.filename}` };
  for (const name of others) {
    add(`node_modules/${name}`);
    dependencies[name] = lock[`node_modules/${name}`].version;
  }
  const manifest = JSON.parse(fs.readFileSync(path.join(repoRoot, 'package/package.json'), 'utf8'));
  packages['node_modules/geoshift'] = {
    version: pack.version, resolved: `file:${pack.filename}`, integrity: pack.integrity, license: manifest.license,
    engines: manifest.engines, peerDependencies: manifest.peerDependencies, peerDependenciesMeta: manifest.peerDependenciesMeta,
  };
  const project = { name: 'geoshift-user', version: '1.0.0', private: true, type: 'module', dependencies };
  fs.writeFileSync(path.join(into, 'package.json'), JSON.stringify(project, null, 2));
  fs.writeFileSync(path.join(into, 'package-lock.json'), JSON.stringify({
    name: project.name, version: project.version, lockfileVersion: 3, requires: true,
    packages: { '': { name: project.name, version: project.version, dependencies }, ...packages },
  }, null, 2));
}

function run(command, args, options = {}) {
  const r = spawnSync(command, args, { encoding: 'utf8', ...options });
  if (r.status !== 0) throw new Error(`${command} ${args.join(' ')} failed (${r.status}):\n${r.stdout}\n${r.stderr}`);
  return r.stdout;
}

before(async () => {
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'geoshift-user-'));
  // The tarball of package/ as built by package/scripts/build.mjs (scripts/bootstrap.sh runs it).
  assert.ok(fs.existsSync(path.join(repoRoot, 'package/dist/wasm/geoshift_web.wasm')), 'package/dist is not built: run scripts/bootstrap.sh');
  [packed] = JSON.parse(run('npm', ['pack', '--json', '--pack-destination', dir, '--loglevel=error'], { cwd: path.join(repoRoot, 'package') }));
  tarball = path.join(dir, packed.filename);

  fs.cpSync(userDir, dir, { recursive: true });
  userProject(dir, packed, ['three', '@types/three', '@types/node']);
  run('npm', ['ci', '--offline', '--no-audit', '--no-fund', '--loglevel=error'], { cwd: dir });

  const off = path.join(dir, 'box.off');
  writeCoff(off, noisy);
  writeCoff(path.join(dir, 'sphere.off'), twoColorSphere(3));
  cli = {
    default: runNative(dir, 'denoise', off, [])('POSITION'),
    taubin: runNative(dir, 'denoise', off, ['--method', 'taubin', '--taubin-iterations', '4'])('POSITION'),
    wavelet: runNative(dir, 'wavelet', off, ['--levels', '2', '--alpha', '0,0.5'])('POSITION'),
    colors: runNative(dir, 'filter', path.join(dir, 'sphere.off'), ['--signal', 'color', '--hr', '0.15'])('COLOR_0'),
  };
  browser = await chromium.launch(CHROMIUM);
});

after(async () => {
  await browser?.close();
  if (dir) fs.rmSync(dir, { recursive: true, force: true });
});

test('the tarball holds the entries, both wasm flavours, the declarations, README and license, and nothing else', (t) => {
  const files = packed.files.map((f) => f.path).sort();
  for (const f of ['package.json', 'README.md', 'LICENSE', 'THIRD_PARTY_NOTICES.md', 'dist/index.js', 'dist/index.d.ts', 'dist/node.js', 'dist/three.js',
    'dist/three.d.ts', 'dist/worker.js', 'dist/node-worker.js', 'dist/wasm/geoshift_web.js', 'dist/wasm/geoshift_web.wasm',
    'dist/wasm/geoshift_web_mt.js', 'dist/wasm/geoshift_web_mt.wasm', 'dist/pthread-worker.js', 'dist/wasm/geoshift_web_mt.worker.cjs']) {
    assert.ok(files.includes(f), `${f} is not in the tarball`);
  }
  assert.deepEqual(files.filter((f) => !/^(package\.json|README\.md|LICENSE|THIRD_PARTY_NOTICES\.md|dist\/.*\.(js|cjs|d\.ts|wasm))$/.test(f)), [], 'unexpected files');
  assert.equal(packed.version, JSON.parse(fs.readFileSync(path.join(repoRoot, 'package/package.json'), 'utf8')).version);
  const gz = (f) => gzipSync(fs.readFileSync(path.join(repoRoot, 'package', f))).length;
  const js = files.filter((f) => /^dist\/.*\.(js|cjs)$/.test(f));
  t.diagnostic(`tarball ${(packed.size / 1024).toFixed(0)} KB (unpacked ${(packed.unpackedSize / 1024).toFixed(0)} KB, ${files.length} files); ` +
    `gzipped: single-threaded wasm ${(gz('dist/wasm/geoshift_web.wasm') / 1024).toFixed(0)} KB + its glue ${(gz('dist/wasm/geoshift_web.js') / 1024).toFixed(0)} KB, ` +
    `threaded wasm ${(gz('dist/wasm/geoshift_web_mt.wasm') / 1024).toFixed(0)} KB, all JS ${(js.reduce((s, f) => s + gz(f), 0) / 1024).toFixed(0)} KB`);
});

/** tsc's errors as { file, line, code }. */
function typeErrors(output) {
  return [...output.matchAll(/^(.+?)\((\d+),\d+\): error (TS\d+)/gm)].map((m) => ({ file: path.basename(m[1]), line: Number(m[2]), code: m[3] }));
}

test('a Node program and a page type-check against the packed declarations', () => {
  run(process.execPath, [tsc, '-p', path.join(dir, 'tsconfig.json')]);
  run(process.execPath, [tsc, '-p', path.join(dir, 'tsconfig.page.json')]);
});

test('wrong option names and types, and a call the API does not have, fail to compile where they are written', () => {
  const source = fs.readFileSync(path.join(dir, 'bad-options.ts'), 'utf8').split('\n');
  const expected = source.flatMap((line, i) => {
    const m = line.match(/\/\/ @error (TS\d+)/);
    return m ? [{ file: 'bad-options.ts', line: i + 1, code: m[1] }] : [];
  });
  assert.ok(expected.length >= 6, 'the file names the errors it expects');
  const r = spawnSync(process.execPath, [tsc, '-p', path.join(dir, 'tsconfig.bad.json')], { encoding: 'utf8' });
  assert.notEqual(r.status, 0, 'bad-options.ts compiled');
  assert.deepEqual(typeErrors(r.stdout), expected, r.stdout);
});

test('under Node: read, denoise with progress, wavelet, filter colors, cancel, errors; the CLI\'s numbers, and the same bits with one thread', (t) => {
  const program = path.join(dir, 'out/node/denoise.js');
  const runs = ['auto', '1'].map((threads) => JSON.parse(execFileSync(process.execPath,
    [program, path.join(dir, 'box.off'), path.join(dir, 'sphere.off'), ...(threads === 'auto' ? [] : [threads])], { encoding: 'utf8' })));
  const [threaded, single] = runs;
  t.diagnostic(`Node: ${JSON.stringify(threaded.info.threaded)} threaded with ${threaded.info.threads} threads; denoise stages: ${threaded.stages.join(', ')}`);
  assert.equal(single.info.threaded, false);
  assert.equal(single.info.threads, 1);
  assert.equal(threaded.info.threaded, os.availableParallelism() > 1);
  assert.equal(threaded.info.version, packed.version);
  assert.ok(threaded.info.ops.includes('denoise'));
  for (const r of runs) {
    assertClose(assert, Float32Array.from(r.positions), cli.default, 'denoise positions (Node vs CLI)');
    assertClose(assert, Float32Array.from(r.taubin), cli.taubin, 'taubin positions (Node vs CLI)');
    assertClose(assert, Float32Array.from(r.colors), cli.colors, 'filtered colors (Node vs CLI)');
    assertClose(assert, Float32Array.from(r.wavelet), cli.wavelet, 'wavelet positions (Node vs CLI)');
    assert.ok(r.stages.length >= 2, `stages: ${r.stages}`);
    assert.equal(r.inputUnchanged, true);
    assert.equal(r.cancel.kind, 'cancelled');
    assert.deepEqual(r.afterCancel, ['_CURVATURE']);
    assert.equal(r.badIndex.kind, 'input');
    assert.match(r.badIndex.message, /face 0.*100000/);
    assert.equal(r.badOption.kind, 'input');
    assert.match(r.badOption.message, /unknown parameter "iteratons"/);
  }
  assert.deepEqual(single.positions, threaded.positions, 'threads changed the result');
});

/** Builds the page with Vite from the installed package; returns the output directory. */
let bundled;
let bundledSizes;
async function bundle() {
  bundled ??= (async () => {
    const outDir = path.join(dir, 'dist');
    // The single-threaded flavour also under /cdn/, where the page's locateFile points a second worker.
    fs.mkdirSync(path.join(dir, 'page/public/cdn'), { recursive: true });
    for (const f of ['geoshift_web.js', 'geoshift_web.wasm']) fs.copyFileSync(path.join(dir, 'node_modules/geoshift/dist/wasm', f), path.join(dir, 'page/public/cdn', f));
    await build({ root: path.join(dir, 'page'), configFile: false, logLevel: 'warn', build: { outDir, emptyOutDir: true } });
    // What a page downloads, gzipped: its code, the package's worker and one flavour.
    const assets = fs.readdirSync(path.join(outDir, 'assets'));
    const gz = (re) => assets.filter((f) => re.test(f)).reduce((sum, f) => sum + gzipSync(fs.readFileSync(path.join(outDir, 'assets', f))).length, 0);
    const code = gz(/^(index|worker)-.*\.js$/);
    bundledSizes = { code, single: code + gz(/^geoshift_web-/), threaded: code + gz(/^geoshift_web_mt-/) };
    return outDir;
  })();
  return bundled;
}

const ISOLATION = { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' };

/** The page as `vite preview` serves the bundle (with or without isolation), or from Vite's dev server. */
async function openPage(isolated, dev = false) {
  const headers = isolated ? ISOLATION : {};
  const listen = { host: '127.0.0.1', port: 0, strictPort: true, headers };
  const root = path.join(dir, 'page');
  const server = dev
    ? await createServer({ root, configFile: false, logLevel: 'warn', server: { ...listen, hmr: false, watch: null } })
    : await preview({ root, configFile: false, logLevel: 'warn', build: { outDir: await bundle() }, preview: listen });
  if (dev) await server.listen();
  const page = await browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
  await page.goto(`http://127.0.0.1:${server.httpServer.address().port}/`);
  await page.waitForFunction(() => document.getElementById('state')?.textContent === 'ready');
  return { page, errors, close: async () => { await page.close(); await server.close(); } };
}

for (const isolated of [true, false]) {
  test(`a Vite page ${isolated ? 'cross-origin isolated (threads)' : 'without isolation (one thread)'}: denoiseGeometry with progress, cancel, bad input`, async (t) => {
    const { page, errors, close } = await openPage(isolated);
    try {
      const info = await page.evaluate((threads) => window.userTest.start(threads), isolated ? 2 : 'auto');
      const kb = (bytes) => `${(bytes / 1024).toFixed(0)} KB`;
      t.diagnostic(`the page downloads ${kb(bundledSizes[isolated ? 'threaded' : 'single'])} gzipped (its code and the worker ${kb(bundledSizes.code)}, three included)`);
      assert.equal(info.threaded, isolated);
      assert.equal(info.threads, isolated ? 2 : 1);
      if (!isolated) assert.match(info.note ?? '', /cross-origin-isolated/);

      const positions = Array.from(noisy.positions);
      const indices = Array.from(noisy.indices);
      const r = await page.evaluate(([p, i]) => window.userTest.denoise(p, i), [positions, indices]);
      assertClose(assert, Float32Array.from(r.positions), cli.default, 'denoised geometry (Chromium vs CLI)');
      assert.ok(r.progress.length >= 2 && r.progress.every(([f, s]) => f >= 0 && f <= 1 && typeof s === 'string' && s), JSON.stringify(r.progress.slice(0, 5)));
      assert.equal(r.normals, positions.length / 3, 'normals recomputed');
      assert.ok(r.uvKept && r.groupsKept && r.inputUnchanged, JSON.stringify(r));

      const c = await page.evaluate(([p, i]) => window.userTest.cancel(p, i), [positions, indices]);
      t.diagnostic(`cancel took ${c.ms.toFixed(0)} ms`);
      assert.deepEqual(c.cancelled, { kind: 'cancelled', message: 'cancelled' });
      assert.deepEqual(c.after, { kind: 'none', message: '' });

      if (!isolated) {
        const requested = [];
        page.on('request', (request) => requested.push(new URL(request.url()).pathname));
        const moved = await page.evaluate(([p, i]) => window.userTest.elsewhere(p, i), [positions, indices]);
        assert.deepEqual(moved, { asked: ['geoshift_web.js', 'geoshift_web.wasm'], curvature: ['_CURVATURE'] });
        assert.ok(requested.includes('/cdn/geoshift_web.js') && requested.includes('/cdn/geoshift_web.wasm'), `locateFile's URLs were not used: ${requested}`);
      }

      const bad = await page.evaluate((p) => window.userTest.badInput(p), positions);
      assert.equal(bad.badIndex.kind, 'input');
      assert.match(bad.badIndex.message, /face 0.*7000000/);
      assert.equal(bad.badValue.kind, 'input');
      assert.match(bad.badValue.message, /iterations/);
      assert.deepEqual(bad.notAnArray, { kind: 'input', message: 'mesh.positions must be a Float32Array (got Array)' });
      assert.deepEqual(errors, []);
    } finally {
      await close();
    }
  });
}

test('the Vite dev server serves the installed package as it is (pre-bundled by Vite), threads and all', async () => {
  const { page, errors, close } = await openPage(true, true);
  try {
    assert.equal((await page.evaluate(() => window.userTest.start(2))).threaded, true);
    const r = await page.evaluate(([p, i]) => window.userTest.denoise(p, i), [Array.from(noisy.positions), Array.from(noisy.indices)]);
    assertClose(assert, Float32Array.from(r.positions), cli.default, 'denoised geometry (dev server vs CLI)');
    assert.deepEqual(errors.filter((e) => !/\[vite\]/.test(e)), []);
  } finally {
    await close();
  }
});

/** A static server of `root` on a free port; `headers` on every answer. */
async function staticServer(root, headers) {
  const types = { '.js': 'text/javascript', '.cjs': 'text/javascript', '.wasm': 'application/wasm', '.html': 'text/html' };
  const server = http.createServer((request, response) => {
    const file = path.join(root, decodeURIComponent(new URL(request.url, 'http://x').pathname));
    if (!file.startsWith(root) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
      response.writeHead(404, headers).end();
      return;
    }
    response.writeHead(200, { 'Content-Type': types[path.extname(file)] ?? 'application/octet-stream', ...headers });
    fs.createReadStream(file).pipe(response);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return { url: `http://127.0.0.1:${server.address().port}`, close: () => new Promise((resolve) => server.close(resolve)) };
}

test('no bundler, the package served from another origin (as from a CDN): a cross-origin-isolated page imports it and denoises', async () => {
  // The CDN: the installed package's files, with CORS and CORP so that a COEP page may use them.
  const cdn = await staticServer(path.join(dir, 'node_modules/geoshift'), { 'Access-Control-Allow-Origin': '*', 'Cross-Origin-Resource-Policy': 'cross-origin' });
  const site = fs.mkdtempSync(path.join(dir, 'site-'));
  fs.writeFileSync(path.join(site, 'index.html'), `<!doctype html><html><head><link rel="icon" href="data:," /></head><body><script type="module">
    import { createGeoshift } from '${cdn.url}/dist/index.js';
    window.denoise = async (positions, indices) => {
      const gs = await createGeoshift({ threads: 2 });
      const r = await gs.denoise({ positions: new Float32Array(positions), indices: new Uint32Array(indices) });
      gs.terminate();
      return { info: gs.info, positions: Array.from(r.positions) };
    };
    document.title = 'ready';
  </script></body></html>`);
  const page = await browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  const host = await staticServer(site, ISOLATION);
  try {
    await page.goto(`${host.url}/index.html`);
    await page.waitForFunction(() => document.title === 'ready');
    const r = await page.evaluate(([p, i]) => window.denoise(p, i), [Array.from(noisy.positions), Array.from(noisy.indices)]);
    assert.equal(r.info.threaded, true);
    assertClose(assert, Float32Array.from(r.positions), cli.default, 'denoised from a CDN (Chromium vs CLI)');
    assert.deepEqual(errors, []);
  } finally {
    await page.close();
    await host.close();
    await cdn.close();
  }
});
