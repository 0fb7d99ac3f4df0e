// run(handle, 'filter', ...) agrees with `geoshift filter` (to 1e-5 relative) on the same input: colors
// of a noisy two-colored sphere, normals and absolute curvature of a bumpy sphere, mean shift and
// blurring mean shift, segments, the hybrid filter; the threaded build gives the same bits for any thread count; bad
// parameters are refused with messages that name them.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import { loadGeoshift, scratchDir } from './support.mjs';
import { assertClose, icosphere, jiggle, runNative, sameBits, twoColorSphere, writeCoff } from './filter-support.mjs';

let geoshift;
let threaded;
let dir;
before(async () => {
  geoshift = await loadGeoshift();
  dir = scratchDir('geoshift-filter-');
});
after(() => threaded?.close());

const colored = twoColorSphere(3);
const bumpy = jiggle(icosphere(3), 0.03);

// cli: the arguments of `geoshift filter`; check: result field -> the GLB attribute it must equal.
const cases = [
  { mesh: 'colored', params: { signal: 'color', mode: 'ms' }, cli: ['--signal', 'color', '--mode', 'ms'], check: { colors: 'COLOR_0' } },
  { mesh: 'colored', params: { signal: 'color', mode: 'bms', passes: 3, hr: 0.15, hs: 2, kmax: 20, rangeUpdate: 'sampled' },
    cli: ['--signal', 'color', '--mode', 'bms', '--passes', '3', '--hr', '0.15', '--hs', '2', '--kmax', '20', '--range-update', 'sampled'], check: { colors: 'COLOR_0' } },
  { mesh: 'colored', params: { signal: 'color', segments: true, radius: 5, eps: 0.1 },
    cli: ['--signal', 'color', '--segments', '--radius', '5', '--eps', '0.1'], check: { colors: 'COLOR_0', _SEGMENT: '_SEGMENT' } },
  { mesh: 'bumpy', params: { signal: 'normal', mode: 'ms' }, cli: ['--signal', 'normal', '--mode', 'ms'], check: { normals: 'NORMAL' } },
  { mesh: 'bumpy', params: { signal: 'normal', mode: 'bms', passes: 2 }, cli: ['--signal', 'normal', '--mode', 'bms', '--passes', '2'], check: { normals: 'NORMAL' } },
  { mesh: 'bumpy', params: { signal: 'curvature', mode: 'ms' }, cli: ['--signal', 'curvature', '--mode', 'ms'], check: { _CURVATURE: '_CURVATURE', colors: 'COLOR_0' } },
  { mesh: 'bumpy', params: { signal: 'curvature', mode: 'bms', hr: 0.5 }, cli: ['--signal', 'curvature', '--mode', 'bms', '--hr', '0.5'], check: { _CURVATURE: '_CURVATURE' } },
  // The hybrid filter (Algorithm 2): the mean shift on a mesh one or two wavelet levels coarser. On
  // the jiggled sphere at two levels a one-rounding difference in the coarse mesh moves modes, so
  // this case needs Eigen's scalar 3-vector sums natively as in wasm (core/CMakeLists.txt).
  { mesh: 'colored', params: { signal: 'curvature', levels: 2, alpha: 0 }, cli: ['--signal', 'curvature', '--levels', '2', '--alpha', '0'], check: { _CURVATURE: '_CURVATURE' } },
  { mesh: 'bumpy', params: { signal: 'curvature', levels: 1, alpha: 0 }, cli: ['--signal', 'curvature', '--levels', '1', '--alpha', '0'], check: { _CURVATURE: '_CURVATURE' } },
  { mesh: 'bumpy', params: { signal: 'curvature', levels: 2, alpha: 0 }, cli: ['--signal', 'curvature', '--levels', '2', '--alpha', '0'], check: { _CURVATURE: '_CURVATURE' } },
  { mesh: 'colored', params: { signal: 'color', levels: 1, alpha: 0.5, filterGeometry: true },
    cli: ['--signal', 'color', '--levels', '1', '--alpha', '0.5', '--filter-geometry'], check: { colors: 'COLOR_0', positions: 'POSITION' } },
];

const meshes = { colored, bumpy };


function load(module, mesh) {
  const loaded = module.loadMesh(mesh.positions, mesh.indices, mesh.colors ? { colors: mesh.colors } : undefined);
  assert.equal(loaded.ok, true, loaded.error);
  return loaded.handle;
}

for (const c of cases) {
  test(`filter ${JSON.stringify(c.params)} on the ${c.mesh} sphere: wasm agrees with the native CLI`, () => {
    const mesh = meshes[c.mesh];
    const off = path.join(dir, `${c.mesh}.off`);
    writeCoff(off, mesh);
    const handle = load(geoshift, mesh);
    const r = geoshift.run(handle, 'filter', c.params);
    geoshift.freeMesh(handle);
    assert.equal(r.ok, true, r.error);
    const native = runNative(dir, 'filter', off, c.cli);
    for (const [field, attribute] of Object.entries(c.check)) {
      const actual = field.startsWith('_') ? r.scalars[field] : r[field];
      assertClose(assert, actual, native(attribute), `${field}`);
    }
    // The filter did something: colors and normals moved off their input.
    if (c.check.colors && c.params.signal === 'color') assert.ok(r.colors.some((v, i) => Math.abs(v - mesh.colors[i]) > 1e-3));
    assert.ok(r.stats.meanIterations > 0 && r.stats.maxIterations >= 1 && r.stats.convergedFraction > 0, JSON.stringify(r.stats));
  });
}

test('the color filter removes the noise and keeps the border between the halves', () => {
  const handle = load(geoshift, colored);
  const r = geoshift.run(handle, 'filter', { signal: 'color', mode: 'bms', passes: 3, segments: true });
  geoshift.freeMesh(handle);
  assert.equal(r.ok, true, r.error);
  const spread = (colors, upper) => {
    const reds = [];
    for (let v = 0; v < colored.positions.length / 3; ++v) {
      if ((colored.positions[3 * v + 2] > 0.3) === upper && Math.abs(colored.positions[3 * v + 2]) > 0.3) reds.push(colors[3 * v]);
    }
    const mean = reds.reduce((a, b) => a + b, 0) / reds.length;
    return { mean, sd: Math.sqrt(reds.reduce((a, b) => a + (b - mean) ** 2, 0) / reds.length) };
  };
  for (const upper of [true, false]) {
    const before = spread(colored.colors, upper);
    const afterFilter = spread(r.colors, upper);
    assert.ok(afterFilter.sd < before.sd / 3, `${upper ? 'upper' : 'lower'} half: spread ${before.sd} -> ${afterFilter.sd}`);
    assert.ok(Math.abs(afterFilter.mean - (upper ? 0.8 : 0.1)) < 0.05, `${upper ? 'upper' : 'lower'} half: mean red ${afterFilter.mean}`);
  }
  // Two halves, two big segments (a few border vertices may form their own).
  assert.ok(r.stats.segmentCount >= 2, `segments: ${r.stats.segmentCount}`);
  assert.equal(r.scalars._SEGMENT.length, colored.positions.length / 3);
});

test('a filtered color signal is kept: a second run starts from the first one\'s colors', () => {
  const handle = load(geoshift, colored);
  const first = geoshift.run(handle, 'filter', { mode: 'ms' });
  const again = geoshift.run(handle, 'filter', { mode: 'ms', kmax: 1, hs: 0.01, radius: 0.01 });
  geoshift.freeMesh(handle);
  assert.equal(again.ok, true, again.error);
  // A tiny neighbourhood leaves every color as it is: the input of the second run was the first's output.
  assertClose(assert, again.colors, first.colors, 'colors after a null filter');
});

test('a named scalar attribute is filtered under its own name; a step keeps its step', () => {
  const handle = load(geoshift, bumpy);
  const n = bumpy.positions.length / 3;
  const step = Float32Array.from({ length: n }, (_, v) => (bumpy.positions[3 * v] > 0 ? 10 : 0) + 0.5 * Math.sin(7 * v));
  assert.equal(geoshift.setAttribute(handle, '_height', 1, step).ok, true);
  const r = geoshift.run(handle, 'filter', { signal: 'height', mode: 'bms', passes: 3, hr: 2 });
  geoshift.freeMesh(handle);
  assert.equal(r.ok, true, r.error);
  const out = r.scalars._height;
  assert.ok(out, `scalars: ${Object.keys(r.scalars)}`);
  for (let v = 0; v < n; ++v) {
    const side = bumpy.positions[3 * v] > 0 ? 10 : 0;
    assert.ok(Math.abs(out[v] - side) < Math.abs(step[v] - side) + 1e-6 || Math.abs(out[v] - side) < 0.3, `vertex ${v}: ${step[v]} -> ${out[v]}`);
  }
});

test('the threaded build gives the same bits for 1 and 4 threads, and as the single-threaded build', async () => {
  threaded = await loadGeoshift({ threads: true });
  const params = { signal: 'color', mode: 'bms', passes: 2, segments: true };
  const run = (module, threads) => {
    const handle = load(module, colored);
    const r = module.run(handle, 'filter', { ...params, threads });
    module.freeMesh(handle);
    assert.equal(r.ok, true, r.error);
    return r;
  };
  const one = run(threaded, 1);
  const four = run(threaded, 4);
  const single = run(geoshift, 0);
  assert.equal(one.stats.threads, 1);
  // What the module can start: the pool holds 4, Node reports the machine's cores.
  assert.equal(four.stats.threads, Math.min(4, os.cpus().length));
  for (const other of [four, single]) {
    assert.ok(sameBits(other.colors, one.colors), 'colors differ in their bits');
    assert.ok(sameBits(other.scalars._SEGMENT, one.scalars._SEGMENT), 'segments differ');
  }
  const normalsOne = (() => {
    const handle = load(threaded, bumpy);
    const r = threaded.run(handle, 'filter', { signal: 'curvature', threads: 1 });
    threaded.freeMesh(handle);
    return r;
  })();
  const handle = load(threaded, bumpy);
  const normalsFour = threaded.run(handle, 'filter', { signal: 'curvature', threads: 4 });
  threaded.freeMesh(handle);
  assert.ok(sameBits(normalsFour.scalars._CURVATURE, normalsOne.scalars._CURVATURE), 'curvature differs in its bits');
});

test('bad parameters are refused, naming what is wrong, and leave the mesh as it was', () => {
  const handle = load(geoshift, colored);
  const expectError = (params, pattern) => {
    const r = geoshift.run(handle, 'filter', params);
    assert.equal(r.ok, false, `${JSON.stringify(params)} was accepted`);
    assert.match(r.error, pattern);
  };
  expectError({ levels: -1 }, /parameter levels/);
  expectError({ alpha: [1, 'x'] }, /parameter alpha must be a number or a list of numbers/);
  expectError({ mode: 'ms', passes: 3 }, /mode "ms" runs one pass/);
  expectError({ mode: 'fast' }, /parameter mode = "fast" is not one of ms, bms/);
  expectError({ signal: 'nope' }, /no attribute 'nope'/);
  expectError({ hs: -1 }, /parameter hs/);
  expectError({ hr: 0 }, /parameter hr/);
  expectError({ kmax: 0 }, /parameter kmax/);
  expectError({ passes: 1.5 }, /passes must be a whole number/);
  expectError({ rangeUpdate: 'both' }, /rangeUpdate/);
  expectError({ segments: 'yes' }, /segments must be true or false/);
  expectError({ bandwidth: 3 }, /unknown parameter "bandwidth"/);
  expectError({ signal: 'terrain' }, /no terrain attribute/);
  // Nothing changed: a null filter still returns the loaded colors.
  const r = geoshift.run(handle, 'filter', { kmax: 1, hs: 0.01, radius: 0.01 });
  assert.equal(r.ok, true, r.error);
  assertClose(assert, r.colors, colored.colors, 'colors after refused runs');
  geoshift.freeMesh(handle);

  const plain = load(geoshift, bumpy);
  const r2 = geoshift.run(plain, 'filter', { signal: 'color' });
  assert.equal(r2.ok, false);
  assert.match(r2.error, /no vertex colors/);
  geoshift.freeMesh(plain);
});

test('progress is reported by stage, and a cancelled filter or denoise changes nothing', () => {
  const handle = load(geoshift, colored);
  const stages = new Set();
  const seen = geoshift.run(handle, 'filter', { signal: 'curvature', mode: 'bms', passes: 2 }, (fraction, stage) => {
    assert.ok(fraction >= 0 && fraction <= 1, `fraction ${fraction}`);
    stages.add(stage);
  });
  assert.equal(seen.ok, true, seen.error);
  assert.ok(stages.size >= 2 && [...stages].every((s) => typeof s === 'string' && s), [...stages].join());
  const r = geoshift.run(handle, 'filter', { mode: 'bms', passes: 2 }, () => true);
  assert.equal(r.ok, false);
  assert.equal(r.cancelled, true);
  const unchanged = geoshift.run(handle, 'filter', { kmax: 1, hs: 0.01, radius: 0.01 });
  assertClose(assert, unchanged.colors, colored.colors, 'colors after a cancelled run');

  const before = geoshift.run(handle, 'noise', { amount: 0 }).positions;
  const d = geoshift.run(handle, 'denoise', {}, () => true);
  assert.equal(d.cancelled, true);
  assert.ok(sameBits(geoshift.run(handle, 'noise', { amount: 0 }).positions, before), 'positions moved');
  geoshift.freeMesh(handle);
});

test('presets() are the CLI\'s --preset values: each, as filter parameters, gives what `geoshift filter --preset` gives', () => {
  const presets = geoshift.presets().filter((p) => p.name !== 'denoise');  // denoise-parity.test.mjs
  assert.deepEqual(presets.map((p) => p.name), ['color', 'curvature-ms', 'curvature-bms', 'terrain-ms', 'terrain-bms']);
  const off = path.join(dir, 'colored.off');
  writeCoff(off, colored);
  for (const p of presets.filter((p) => p.signal === 'color' || p.signal === 'curvature')) {
    const { name, description, signal, ...params } = p;
    assert.ok(description.length > 0, name);
    const handle = load(geoshift, colored);
    const r = geoshift.run(handle, 'filter', { signal, ...params });
    geoshift.freeMesh(handle);
    assert.equal(r.ok, true, `${name}: ${r.error}`);
    assert.equal(r.stats.passes, p.passes, name);
    const native = runNative(dir, 'filter', off, ['--preset', name]);
    if (signal === 'color') assertClose(assert, r.colors, native('COLOR_0'), `${name} colors`);
    else assertClose(assert, r.scalars._CURVATURE, native('_CURVATURE'), `${name} curvature`);
  }
});
