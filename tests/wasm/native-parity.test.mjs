// The wasm module and the native CLI compute the same curvature (to 1e-5 relative) from the same
// positions: `geoshift curvature IN.off -o OUT.glb --kind K` writes the per-vertex values as the
// float attribute _CURVATURE in the input's vertex order.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import {
  firstMismatch, loadGeoshift, nativeCli, readGlbAttribute, readOff, saddle, sphereOff, writeOff,
  scratchDir,
} from './support.mjs';

const kinds = { mean: 'meanCurvature', gauss: 'gaussianCurvature', abs: 'absoluteCurvature' };

let geoshift;
let dir;
before(async () => {
  geoshift = await loadGeoshift();
  dir = scratchDir('geoshift-wasm-');
});

function nativeCurvature(offFile, kind) {
  if (!fs.existsSync(nativeCli)) {
    throw new Error(`the native CLI ${nativeCli} is missing: build it with ` +
      '`cmake --build build/native-release --target geoshift` (npm test builds it first)');
  }
  const glb = offFile.replace(/\.off$/, `.${kind}.glb`);
  execFileSync(nativeCli, ['curvature', offFile, '-o', glb, '--kind', kind], { stdio: 'pipe' });
  return { curvature: readGlbAttribute(glb, '_CURVATURE'), positions: readGlbAttribute(glb, 'POSITION') };
}

const meshes = [
  ['jittered saddle (boundary, both signs of K)', () => saddle(16)],
  ['sphere.off', () => readOff(sphereOff), !fs.existsSync(sphereOff) && `${sphereOff} is not present`],
];

for (const [name, make, skip] of meshes) {
  test(`wasm and native agree: ${name}`, { skip }, () => {
    const mesh = make();
    const off = path.join(dir, `${name.split(' ')[0].replace(/\W/g, '_')}.off`);
    writeOff(off, mesh);
    const loaded = geoshift.loadMesh(mesh.positions, mesh.indices);
    assert.equal(loaded.ok, true, loaded.error);
    const wasm = {};
    for (const [kind, field] of Object.entries(kinds)) {
      const r = geoshift.run(loaded.handle, 'curvature', { kind });
      assert.equal(r.ok, true, r.error);
      wasm[field] = r.scalars._CURVATURE;
    }
    geoshift.freeMesh(loaded.handle);

    for (const [kind, field] of Object.entries(kinds)) {
      const native = nativeCurvature(off, kind);
      // If the CLI reordered or split vertices the comparison below would be meaningless.
      assert.deepEqual([...native.positions], [...mesh.positions], `${kind}: the CLI changed the vertex layout`);
      assert.equal(native.curvature.length, wasm[field].length, kind);
      const i = firstMismatch(wasm[field], native.curvature);
      assert.equal(i, -1, i < 0 ? '' : `${kind} curvature at vertex ${i}: wasm ${wasm[field][i]}, native ${native.curvature[i]}`);
    }
  });
}
