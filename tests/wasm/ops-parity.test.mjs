// The ops of run() agree with the native CLI (to 1e-5 relative) on the same input: noise and smooth
// move the same vertices to the same places, curvature writes the same _CURVATURE and colors.
// `geoshift noise|smooth|curvature IN.off -o OUT.glb` keep the OFF's vertex order in the GLB.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import {
  firstMismatch, loadGeoshift, nativeCli, readGlbAttribute, readOff, saddle, sphereOff, unweldedCube, writeOff,
  scratchDir,
} from './support.mjs';

let geoshift;
let dir;
before(async () => {
  geoshift = await loadGeoshift();
  dir = scratchDir('geoshift-ops-');
});

function native(args, off, attribute) {
  if (!fs.existsSync(nativeCli)) {
    throw new Error(`the native CLI ${nativeCli} is missing: build it (cmake --build build/native-release ` +
      '--target geoshift) or point GEOSHIFT_NATIVE_CLI at one');
  }
  const glb = path.join(dir, `${path.basename(off, '.off')}-${args.join('_').replace(/\W/g, '')}.glb`);
  execFileSync(nativeCli, [args[0], off, '-o', glb, ...args.slice(1)], { stdio: 'pipe' });
  return readGlbAttribute(glb, attribute);
}

function assertClose(actual, expected, what) {
  assert.equal(actual.length, expected.length, `${what}: lengths differ`);
  const i = firstMismatch(actual, expected);
  assert.equal(i, -1, i < 0 ? '' : `${what} at ${i}: wasm ${actual[i]}, native ${expected[i]}`);
}

// The unwelded cube checks that results come back in the caller's layout (36 corners, 8 welded).
const meshes = [
  ['saddle', () => saddle(20)],
  ['cube', () => unweldedCube()],
  ['sphere', () => readOff(sphereOff), !fs.existsSync(sphereOff) && `${sphereOff} is not present`],
];

const cases = [
  { op: 'noise', params: { amount: 0.3, distribution: 'uniform', seed: 7 }, cli: ['noise', '--amount', '0.3', '--dist', 'uniform', '--seed', '7'], field: 'positions', attribute: 'POSITION' },
  { op: 'noise', params: { amount: 0.5, direction: 'normal', distribution: 'gaussian', seed: 3 }, cli: ['noise', '--amount', '0.5', '--direction', 'normal', '--dist', 'gaussian', '--seed', '3'], field: 'positions', attribute: 'POSITION' },
  { op: 'smooth', params: { iterations: 5 }, cli: ['smooth', '--iterations', '5'], field: 'positions', attribute: 'POSITION' },
  { op: 'smooth', params: { iterations: 3, weights: 'cotangent', lambda: 0.4, mu: -0.45 }, cli: ['smooth', '--iterations', '3', '--weights', 'cotangent', '--lambda', '0.4', '--mu', '-0.45'], field: 'positions', attribute: 'POSITION' },
  { op: 'curvature', params: { kind: 'mean' }, cli: ['curvature', '--kind', 'mean'], field: '_CURVATURE', attribute: '_CURVATURE' },
  { op: 'curvature', params: {}, cli: ['curvature'], field: 'colors', attribute: 'COLOR_0' },
];

for (const [name, make, skip] of meshes) {
  for (const c of cases) {
    test(`${c.op} ${JSON.stringify(c.params)} on ${name}: wasm agrees with the native CLI`, { skip }, () => {
      const mesh = make();
      const off = path.join(dir, `${name}.off`);
      writeOff(off, mesh);
      const loaded = geoshift.loadMesh(mesh.positions, mesh.indices);
      assert.equal(loaded.ok, true, loaded.error);
      const r = geoshift.run(loaded.handle, c.op, c.params);
      assert.equal(r.ok, true, r.error);
      let actual = c.field === 'positions' ? r.positions : c.field === 'colors' ? r.colors : r.scalars[c.field];
      let expected = native(c.cli, off, c.attribute);
      if (c.attribute === 'COLOR_0' && expected.length === 4 * mesh.positions.length / 3) {
        expected = expected.filter((_, i) => i % 4 !== 3);  // RGBA in the file, RGB from run()
      }
      assert.ok(actual, `${c.op} returned no ${c.field}`);
      assertClose(actual, expected, `${c.op} ${c.field}`);
      assert.ok(geoshift.freeMesh(loaded.handle));
    });
  }
}

test('ops chain on a kept mesh: noise then smooth equals the CLI doing both', () => {
  const mesh = saddle(16);
  const off = path.join(dir, 'chain.off');
  writeOff(off, mesh);
  const { handle } = geoshift.loadMesh(mesh.positions, mesh.indices);
  assert.equal(geoshift.run(handle, 'noise', { amount: 0.4, seed: 11, direction: 'normal', distribution: 'uniform' }).ok, true);
  const smoothed = geoshift.run(handle, 'smooth', { iterations: 4 });
  assert.equal(smoothed.ok, true, smoothed.error);

  const noisyGlb = path.join(dir, 'chain-noisy.glb');
  execFileSync(nativeCli, ['noise', off, '-o', noisyGlb, '--amount', '0.4', '--seed', '11', '--direction', 'normal', '--dist', 'uniform'], { stdio: 'pipe' });
  // Through OFF again so the CLI welds the noisy positions exactly as the kept mesh has them.
  const noisyOff = path.join(dir, 'chain-noisy.off');
  writeOff(noisyOff, { positions: readGlbAttribute(noisyGlb, 'POSITION'), indices: mesh.indices });
  assertClose(smoothed.positions, native(['smooth', '--iterations', '4'], noisyOff, 'POSITION'), 'noise + smooth');
  geoshift.freeMesh(handle);
});
