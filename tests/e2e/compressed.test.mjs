// Draco- and meshopt-compressed glTF open (three's decoders, served by the app itself), filter and
// export like any other file. The fixtures are the procedural torus of fixtures.mjs, compressed by
// data/make-compressed.mjs; the meshopt one is also quantized (int16 positions, node scale).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { test } from 'node:test';
import { parseGlb } from './fixtures.mjs';
import { assertMeshVisible, exportedGlb, lastRun, openFile, positions, runPreset, shoot, stats, useApp } from './harness.mjs';

const app = useApp();
const requests = [];

for (const name of ['torus-draco.glb', 'torus-meshopt.glb']) {
  test(`${name} opens, filters and exports`, async () => {
    const { page } = app;
    page.on('request', (r) => requests.push(r.url()));
    const s = await openFile(page, name, readFileSync(new URL(`./data/${name}`, import.meta.url)));
    assert.equal(s.state, 'ok', s.text);
    assert.deepEqual(await stats(page), { file: name, vertices: 1225, triangles: 2304 });
    assertMeshVisible(await shoot(page, `compressed-${name}`), name);
    const before = await positions(page);
    await runPreset(page, 'taubin', { iterations: 3 });
    assert.ok(await lastRun(page), await page.evaluate(() => window.__geoshift.lastError()));
    const after = await positions(page);
    assert.notDeepEqual(after, before);
    const exported = parseGlb(await exportedGlb(page));
    const p = exported.accessor(exported.json.meshes[0].primitives[0].attributes.POSITION);
    assert.equal(p.length, 1225 * 3);
    assert.ok(p.every(Number.isFinite));
  });
}

test('the decoders came from the app itself', () => {
  const origin = new URL(app.url).origin;
  const foreign = requests.filter((url) => !url.startsWith(origin) && !url.startsWith('blob:') && !url.startsWith('data:'));
  assert.deepEqual(foreign, []);
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
