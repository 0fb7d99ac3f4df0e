// Files that cannot be shown produce an error in plain words in the status line, and the mesh that
// was on screen stays there. The core's readers (the CLI's) answer first, in the worker; a
// compressed glTF, which they cannot decode, is left to three's loaders and the app's checks.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { glb, tetraGlb } from './fixtures.mjs';
import { assertMeshVisible, openFile, shoot, stats, useApp } from './harness.mjs';
import { differenceFraction } from './png.mjs';

const app = useApp();
const SAMPLE = { file: 'ChineseDragon-10kv.off', vertices: 10000, triangles: 19994 };

const validGlb = tetraGlb();
const truncatedGlb = validGlb.subarray(0, validGlb.length - 40);
const tetraJson = JSON.parse(validGlb.subarray(20, 20 + validGlb.readUInt32LE(12)).toString());

const cases = [
  { name: 'broken.glb', contents: Buffer.from('this is not a binary glTF file at all'), reason: /not a GLB|damaged/ },
  { name: 'truncated.glb', contents: truncatedGlb, reason: /truncated/ },
  {
    name: 'bad-json.glb',
    contents: Buffer.concat([validGlb.subarray(0, 20), Buffer.from('{"asset": '), validGlb.subarray(30)]),
    reason: /cannot read glTF: \[json\.exception\.parse_error/,
  },
  {
    // Draco is supported (three's decoder, served by the app); damaged Draco data is an error.
    name: 'draco.glb',
    contents: tetraGlb({
      extraJson: {
        extensionsUsed: ['KHR_draco_mesh_compression'],
        extensionsRequired: ['KHR_draco_mesh_compression'],
        meshes: [{
          primitives: [{
            attributes: { POSITION: 0 },
            extensions: { KHR_draco_mesh_compression: { bufferView: 0, attributes: { POSITION: 0 } } },
          }],
        }],
      },
    }),
    reason: /damaged/,
  },
  {
    name: 'external.gltf',
    contents: JSON.stringify({ ...tetraJson, buffers: [{ uri: 'tetra%20data.bin', byteLength: 480 }] }),
    reason: /File not found : tetra data\.bin/,
  },
  { name: 'empty-bin.glb', contents: glb({ asset: { version: '2.0' } }, Buffer.alloc(0)), reason: /the GLB has an empty BIN chunk \(0 bytes\)/ },
  { name: 'no-mesh.gltf', contents: JSON.stringify({ asset: { version: '2.0' } }), reason: /no triangles/ },
  { name: 'model.fbx', contents: 'Kaydara FBX Binary', reason: /unknown file extension '\.fbx'; geoshift reads and writes/ },
  {
    name: 'points.ply',
    contents: 'ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 1 1\n',
    reason: /no triangles/,
  },
  { name: 'bad-index.off', contents: 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n', reason: /bad-index\.off:6: face 0 index 7 out of range \(3 vertices\)/ },
  { name: 'binary.obj', contents: Buffer.from([0x7f, 0x45, 0x4c, 0x46, 0, 0, 1, 2]), reason: /not a text OBJ file: it holds NUL bytes/ },
  { name: 'nan.obj', contents: 'v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n', reason: /nan\.obj:3: vertex 3 has a non-finite coordinate/ },
];

test('errors leave the sample on screen', async (t) => {
  const { page } = app;
  const before = await shoot(page, 'errors-before');
  for (const c of cases) {
    await t.test(c.name, async () => {
      const s = await openFile(page, c.name, c.contents);
      assert.equal(s.state, 'error', `${c.name} was accepted: ${s.text}`);
      assert.ok(s.text.startsWith(`Could not read ${c.name}:`), s.text);
      assert.match(s.text, c.reason);
      assert.match(s.text, /Still showing ChineseDragon-10kv\.off\.$/);
      assert.deepEqual(await stats(page), SAMPLE);
    });
  }
  const after = await shoot(page, 'errors-after');
  assertMeshVisible(after, 'after errors');
  assert.ok(differenceFraction(before, after) < 0.01, 'the view changed although every file was rejected');
});

test('the error is styled as an error and cleared by the next good file', async () => {
  const { page } = app;
  await openFile(page, 'broken.glb', 'garbage');
  const errorColour = await page.getByTestId('status').evaluate((el) => getComputedStyle(el).color);
  const s = await openFile(page, 'good.glb', validGlb);
  assert.equal(s.state, 'ok');
  const okColour = await page.getByTestId('status').evaluate((el) => getComputedStyle(el).color);
  assert.notEqual(errorColour, okColour);
  await page.getByTestId('status').screenshot({ path: 'test-output/e2e/errors-status-ok.png' });
});

// A file the core reads with a repair is shown, and the status line says what the filters'
// reading of it repairs (docs/denoising.md#bad-input): here a tetrahedron with one face written
// the other way round. A file without a defect gets no such clause.
test('the status line says what reading the file repaired', async () => {
  const { page } = app;
  const tetra = (flip) => 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n' +
    ['0 2 1', '0 1 3', flip ? '0 2 3' : '0 3 2', '1 2 3'].map((f) => `3 ${f}\n`).join('');
  let s = await openFile(page, 'tetra.off', tetra(false));
  assert.equal(s.state, 'ok', s.text);
  assert.doesNotMatch(s.text, /repaired/);
  s = await openFile(page, 'tetra-flipped.off', tetra(true));
  assert.equal(s.state, 'ok', s.text);
  assert.match(s.text, /^tetra-flipped\.off: 4 vertices, 4 triangles; repaired for the filters: re-oriented 1 face\(s\) to agree with their neighbours \(each piece keeps the orientation of most of its faces\)$/);
  const title = await page.getByTestId('status').getAttribute('title');
  assert.match(title, /re-oriented 1 face\(s\) to agree with their neighbours \(each piece keeps the orientation of most of its faces\): face 2 \(0, 2, 3\)$/);
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
