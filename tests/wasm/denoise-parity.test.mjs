// run(handle, 'denoise', ...) agrees with `geoshift denoise` (to 1e-5 relative) on a small noisy box
// for every method, brings the box back toward its flat sides, gives the same bits for any thread
// count, reports what the CLI reports of the planes sparse outliers leave untouched, and refuses bad
// parameters with messages that name them.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import { loadGeoshift, nativeCli, scratchDir } from './support.mjs';
import { assertClose, box, jiggle, runNative, sameBits, writeCoff } from './filter-support.mjs';

let geoshift;
let threaded;
let dir;
before(async () => {
  geoshift = await loadGeoshift();
  dir = scratchDir('geoshift-denoise-');
});
after(() => threaded?.close());

const clean = box(6);
const noisy = jiggle(clean, 0.06);

function denoised(module, params, mesh = noisy) {
  const { handle, ok, error } = module.loadMesh(mesh.positions, mesh.indices);
  assert.equal(ok, true, error);
  const r = module.run(handle, 'denoise', params);
  module.freeMesh(handle);
  assert.equal(r.ok, true, r.error);
  return r;
}

const cases = [
  { params: { passes: 1 }, cli: ['--passes', '1'] },
  { params: {}, cli: [] },  // the default: noise estimated, smoothing chosen by SURE
  { params: { strength: 2, noise: 0.2, hr: 0.3 }, cli: ['--strength', '2', '--noise', '0.2', '--hr', '0.3'] },
  { params: { preset: 'paper', passes: 1 }, cli: ['--preset', 'paper', '--passes', '1'] },
  { params: { preset: 'paper', passes: 2, hs: 2, hr: 0.35, radius: 3, kmax: 20, eps: 0.1, vertexIterations: 8, rangeUpdate: 'sampled' },
    cli: ['--preset', 'paper', '--passes', '2', '--hs', '2', '--hr', '0.35', '--radius', '3', '--kmax', '20', '--eps', '0.1',
      '--vertex-iterations', '8', '--range-update', 'sampled'] },
  { params: { preset: 'paper', passes: 1, faceNormals: 'mean', rangeUpdate: 'joint' },
    cli: ['--preset', 'paper', '--passes', '1', '--face-normals', 'mean', '--range-update', 'joint'] },
  { params: { method: 'bilateral', normalIterations: 5, sigmaS: 0.3 }, cli: ['--method', 'bilateral', '--normal-iterations', '5', '--sigma-s', '0.3'] },
  { params: { method: 'taubin', iterations: 4 }, cli: ['--method', 'taubin', '--taubin-iterations', '4'] },
];

for (const c of cases) {
  test(`denoise ${JSON.stringify(c.params)}: wasm agrees with the native CLI`, () => {
    const off = path.join(dir, 'box.off');
    writeCoff(off, noisy);
    const r = denoised(geoshift, c.params);
    assertClose(assert, r.positions, runNative(dir, 'denoise', off, c.cli)('POSITION'), 'positions');
    assert.equal(r.stats.method, c.params.method ?? 'meanshift');
  });
}

// Distance of each vertex from the box surface (the largest coordinate's magnitude is 1 there).
function offSurfaceRms(positions) {
  let sum = 0;
  for (let v = 0; v < positions.length / 3; ++v) {
    sum += (Math.max(Math.abs(positions[3 * v]), Math.abs(positions[3 * v + 1]), Math.abs(positions[3 * v + 2])) - 1) ** 2;
  }
  return Math.sqrt(sum / (positions.length / 3));
}

test('the mean shift denoiser brings the noisy box back toward its sides and says what it measured', () => {
  const r = denoised(geoshift, {});
  const before = offSurfaceRms(noisy.positions);
  const afterDenoise = offSurfaceRms(r.positions);
  assert.ok(afterDenoise < 0.7 * before, `off-surface RMS ${before} -> ${afterDenoise}`);
  assert.ok(r.positions.every(Number.isFinite));
  assert.equal(r.positions.length, noisy.positions.length);
  assert.equal(r.stats.preset, 'default');
  assert.equal(r.stats.noiseEstimated, 'yes');
  assert.ok(r.stats.noiseLevel > 0 && r.stats.passes >= 1 && r.stats.passesRun >= 2 * r.stats.passes, JSON.stringify(r.stats));
  assert.ok(r.stats.threads === 1, JSON.stringify(r.stats));
  const paper = denoised(geoshift, { preset: 'paper' });
  assert.ok(offSurfaceRms(paper.positions) < 0.7 * before);
  assert.ok(paper.stats.meanIterations > 0 && paper.stats.convergedFraction > 0, JSON.stringify(paper.stats));
});

test('the threaded build denoises to the same bits with 1 and 4 threads, and as the single-threaded build', async () => {
  threaded = await loadGeoshift({ threads: true });
  const one = denoised(threaded, { threads: 1 });
  const four = denoised(threaded, { threads: 4 });
  const single = denoised(geoshift, {});
  assert.equal(four.stats.threads, Math.min(4, os.cpus().length));
  assert.ok(sameBits(four.positions, one.positions), '4 threads differ from 1');
  assert.ok(sameBits(single.positions, one.positions), 'the threaded build differs from the single-threaded one');
});

test('presets() gives the default denoiser\'s settings: sent as parameters they give what `geoshift denoise` gives', () => {
  const entry = geoshift.presets().find((p) => p.name === 'denoise');
  assert.ok(entry, 'presets() has no denoise entry');
  const { name, description, signal, ...params } = entry;
  assert.ok(description.length > 0 && signal === 'normal', name);
  assert.equal(params.noise, 0);   // measured on the mesh
  assert.equal(params.passes, 0);  // chosen by SURE
  assert.equal(params.hr, 0);      // the default candidates, SURE picks one
  assert.equal(params.impulse, 'auto');  // outliers corrected when the result says the noise is impulsive
  assert.equal(params.lightStart, 1);  // a light start of one Taubin step where the ladder ranks least at its first rung
  const off = path.join(dir, 'box.off');
  writeCoff(off, noisy);
  const r = denoised(geoshift, params);
  assertClose(assert, r.positions, runNative(dir, 'denoise', off, [])('POSITION'), 'positions');
});

test('impulse "on" corrects outliers under dense noise as `geoshift denoise --impulse on` does; "off" never', () => {
  const off = path.join(dir, 'box-impulse.off');
  writeCoff(off, noisy);
  const auto = denoised(geoshift, {});
  const on = denoised(geoshift, { impulse: 'on' });
  const never = denoised(geoshift, { impulse: 'off' });
  assert.equal(auto.stats.impulseGarrote, 'no');  // noise on every vertex: not impulsive
  assert.equal(on.stats.impulseGarrote, 'yes');
  assert.equal(never.stats.impulseGarrote, 'no');
  // The two kurtoses the trigger reads, both below their thresholds under dense noise (the highest
  // frequencies' 0, not read: no vertex of the box is three rings from a crease).
  assert.equal(auto.stats.spectrumKurtosis, 0);
  assert.ok(auto.stats.displacementKurtosis > 0 && auto.stats.displacementKurtosis < 6, String(auto.stats.displacementKurtosis));
  assert.ok(sameBits(never.positions, auto.positions), 'off differs from auto where auto does not fire');
  assert.ok(!sameBits(on.positions, auto.positions), 'on changed nothing');
  assertClose(assert, on.positions, runNative(dir, 'denoise', off, ['--impulse', 'on'])('POSITION'), 'positions');
});

// The light start (docs/denoising.md#a-light-start) races where the Taubin-only ladder estimates
// least at its first rung; a ladder of one rung forces that. On a finer box with less noise its
// winner stands: lightStart reaches the op as --light-start reaches the CLI, and 0 turns it off.
test('lightStart races a light start where the ladder ranks least at its first rung, as `geoshift denoise --light-start` does', () => {
  const light = jiggle(box(8), 0.02);
  const off = path.join(dir, 'box-light.off');
  writeCoff(off, light);
  const one = denoised(geoshift, { taubinOnly: [200] }, light);
  const two = denoised(geoshift, { taubinOnly: [200], lightStart: 2 }, light);
  const none = denoised(geoshift, { taubinOnly: [200], lightStart: 0 }, light);
  assert.equal(denoised(geoshift, {}, light).stats.lightStart, 'no');  // the default ladder ranks least further up
  for (const [r, steps] of [[one, 1], [two, 2]]) {
    assert.equal(r.stats.lightStart, 'raced', JSON.stringify(r.stats));
    assert.equal(r.stats.presmoothingSteps, steps, JSON.stringify(r.stats));  // its winner stood
  }
  assert.equal(none.stats.lightStart, 'no');
  assert.equal(none.stats.presmoothingSteps, 3);
  for (const [r, n] of [[one, '1'], [two, '2'], [none, '0']]) {
    assertClose(assert, r.positions, runNative(dir, 'denoise', off, ['--taubin-only', '200', '--light-start', n])('POSITION'), `positions, --light-start ${n}`);
  }
  assert.ok(!sameBits(one.positions, none.positions) && !sameBits(two.positions, one.positions), 'lightStart changed nothing');
});

// The box with two vertices inside each side pushed along the side's normal (one out by half an edge,
// one in by 0.3 of an edge), every other vertex where it was: sparse outliers on flat faces, where
// the spectrum reads too few vertices (docs/denoising.md#the-noise-level, "Planes left untouched").
function withOutliers(n) {
  const mesh = box(n);
  const positions = Float32Array.from(mesh.positions);
  const edge = 2 / n;
  for (let v = 0; v < positions.length / 3; ++v) {
    const p = positions.subarray(3 * v, 3 * v + 3);
    const sides = [0, 1, 2].filter((c) => Math.abs(p[c]) === 1);
    if (sides.length !== 1) continue;  // on an edge of the box, shared by two sides
    const c = sides[0];
    const [i, j] = [(c + 1) % 3, (c + 2) % 3].map((a) => Math.round((p[a] + 1) / edge));
    if (i === 2 && j === 2) p[c] += Math.sign(p[c]) * 0.5 * edge;
    else if (i === n - 2 && j === n - 3) p[c] -= Math.sign(p[c]) * 0.3 * edge;
  }
  return { ...mesh, positions };
}

// `geoshift denoise IN ARGS...`'s report line (its standard error).
function nativeReport(input, args = []) {
  const glb = path.join(dir, `${path.basename(input, '.off')}-report.glb`);
  const run = spawnSync(nativeCli, ['denoise', input, '-o', glb, ...args], { encoding: 'utf8' });
  assert.equal(run.status, 0, run.stderr || String(run.error));
  return run.stderr;
}

test('sparse outliers on a box: the level read against the untouched planes and the vertices on them kept, as the CLI reports', () => {
  // docs/denoising.md#impulsive-noise ("Vertices on untouched planes")
  const spiky = withOutliers(6);
  const off = path.join(dir, 'box-outliers.off');
  writeCoff(off, spiky);
  const r = denoised(geoshift, {}, spiky);
  assertClose(assert, r.positions, runNative(dir, 'denoise', off, [])('POSITION'), 'positions');
  const report = nativeReport(off);
  assert.equal(r.stats.impulseGarrote, 'yes', JSON.stringify(r.stats));
  assert.equal(r.stats.planarLevel, 'yes', JSON.stringify(r.stats));
  assert.match(report, /estimated from the mesh, against the planes the noise left/);
  const kept = report.match(/; (\d+) vertices on untouched planes kept at their input positions/);
  assert.ok(kept, report);
  assert.ok(r.stats.planarKept > 0, JSON.stringify(r.stats));
  assert.equal(r.stats.planarKept, Number(kept[1]));
});

test('dense noise reads no level against planes and keeps no vertex on them, with the impulse correction on too', () => {
  const off = path.join(dir, 'box-dense.off');
  writeCoff(off, noisy);
  for (const [params, cli] of [[{}, []], [{ impulse: 'on' }, ['--impulse', 'on']]]) {
    const r = denoised(geoshift, params);
    assert.equal(r.stats.planarLevel, 'no', JSON.stringify(r.stats));
    assert.equal(r.stats.planarKept, 0, JSON.stringify(r.stats));
    const report = nativeReport(off, cli);
    assert.doesNotMatch(report, /against the planes|untouched planes/);
  }
});

test('a piece too small to denoise keeps its positions and the box is denoised as alone; minPiece 0 as --min-piece 0', () => {
  // The noisy box and a lone triangle beside it (docs/denoising.md#small-pieces).
  const n = noisy.positions.length / 3;
  const withTriangle = {
    positions: Float32Array.from([...noisy.positions, 3, 0, 0, 3.3, 0, 0, 3, 0.3, 0.05]),
    indices: Uint32Array.from([...noisy.indices, n, n + 1, n + 2]),
  };
  const kept = denoised(geoshift, {}, withTriangle);
  assert.equal(kept.stats.keptPieces, 1);
  assert.equal(kept.stats.keptVertices, 3);
  assert.ok(sameBits(kept.positions.subarray(3 * n), withTriangle.positions.subarray(3 * n)), 'the triangle moved');
  assert.ok(sameBits(kept.positions.subarray(0, 3 * n), denoised(geoshift, {}).positions), 'the box differs from the box alone');
  const every = denoised(geoshift, { minPiece: 0 }, withTriangle);
  assert.equal(every.stats.keptPieces, 0);
  assert.ok(!sameBits(every.positions.subarray(3 * n), withTriangle.positions.subarray(3 * n)), 'the triangle did not move');
  const off = path.join(dir, 'box-triangle.off');
  writeCoff(off, withTriangle);
  assertClose(assert, kept.positions, runNative(dir, 'denoise', off, [])('POSITION'), 'positions');
  assertClose(assert, every.positions, runNative(dir, 'denoise', off, ['--min-piece', '0'])('POSITION'), 'positions, --min-piece 0');
});

test('a denoised box denoised again comes back as it went in, as from `geoshift denoise`', () => {
  // docs/denoising.md#the-input-as-a-candidate: no candidate ranks below the input's own risk. (On
  // the 6 x 6 box nearly every vertex is near a crease and the second run reads a level of 0.09 AEL.)
  const finer = box(8);
  const once = denoised(geoshift, {}, jiggle(finer, 0.06));
  assert.equal(once.stats.keptInput, 'no');
  const again = { positions: once.positions, indices: finer.indices };
  const twice = denoised(geoshift, {}, again);
  assert.equal(twice.stats.keptInput, 'yes');
  assert.equal(twice.stats.passes, 0);
  assert.equal(twice.stats.presmoothingSteps, 0);
  assert.ok(sameBits(twice.positions, once.positions), 'the input moved');
  const off = path.join(dir, 'box-once.off');
  writeCoff(off, again);
  assertClose(assert, twice.positions, runNative(dir, 'denoise', off, [])('POSITION'), 'positions');
});

test('bad denoise parameters are refused, naming what is wrong', () => {
  const { handle } = geoshift.loadMesh(noisy.positions, noisy.indices);
  const expectError = (params, pattern) => {
    const r = geoshift.run(handle, 'denoise', params);
    assert.equal(r.ok, false, `${JSON.stringify(params)} was accepted`);
    assert.match(r.error, pattern);
  };
  expectError({ method: 'median' }, /parameter method = "median" is not one of meanshift, bilateral, taubin/);
  expectError({ method: 'bilateral', levels: 1 }, /parameter levels belongs to method "meanshift"/);
  expectError({ method: 'taubin', hs: 3 }, /parameter hs belongs to method "meanshift"/);
  expectError({ normalIterations: 3 }, /normalIterations belongs to method "bilateral"/);
  expectError({ lightStart: -1 }, /parameter lightStart/);
  expectError({ preset: 'paper', lightStart: 0 }, /parameter lightStart/);
  expectError({ method: 'taubin', vertexIterations: 3 }, /vertexIterations does not apply/);
  expectError({ hr: -0.1 }, /parameter hr/);
  expectError({ passes: -1 }, /parameter passes/);
  expectError({ preset: 'paper', passes: 0 }, /parameter passes/);
  expectError({ kmax: 20 }, /kmax does not apply to preset "default"/);
  expectError({ preset: 'paper', strength: 2 }, /strength does not apply to preset "paper"/);
  expectError({ strength: 0 }, /parameter strength/);
  expectError({ radius: 'far' }, /radius must be a number/);
  expectError({ method: 'taubin', lambda: 0.5, mu: -0.4 }, /mu|lambda/);
  expectError({ sigma: 1 }, /unknown parameter "sigma"/);
  expectError({ impulse: 'sometimes' }, /parameter impulse = "sometimes" is not one of auto, on, off/);
  expectError({ taubinOnly: [8, 5] }, /Taubin-only step counts must ascend/);
  // Nothing moved: a Taubin run with no iterations hands back the loaded positions.
  const r = geoshift.run(handle, 'denoise', { method: 'taubin', iterations: 0 });
  assert.equal(r.ok, true, r.error);
  assert.ok(sameBits(r.positions, noisy.positions));
  geoshift.freeMesh(handle);
});
