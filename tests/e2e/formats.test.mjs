// Each supported format, given through the file picker (or dropped on the page), is shown with the
// vertex and triangle counts a user would expect from the file.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { tetraCoff, tetraGlb, tetraObj, tetraPly, tetraStl } from './fixtures.mjs';
import { assertMeshVisible, openFile, shoot, stats, useApp, waitForStatusAbout } from './harness.mjs';

const app = useApp();

const viewMode = () => app.page.getByTestId('view-mode').inputValue();

// Expected counts: the GLB has flat faces (three own vertices per face, as glTF exporters write
// them); OBJ and STL corners are welded into the 4 shared vertices; PLY and OFF are indexed.
const cases = [
  { name: 'tetra.glb', contents: tetraGlb(), vertices: 12, colours: true },
  { name: 'tetra.obj', contents: tetraObj(), vertices: 4, colours: false },
  { name: 'tetra.stl', contents: tetraStl(), vertices: 4, colours: false },
  { name: 'tetra.ply', contents: tetraPly(), vertices: 4, colours: true },
  { name: 'tetra.off', contents: tetraCoff(), vertices: 4, colours: true },
];

for (const c of cases) {
  test(`${c.name} opened with the file picker is shown with its counts`, async () => {
    const s = await openFile(app.page, c.name, c.contents);
    assert.equal(s.state, 'ok', s.text);
    assert.equal(s.text, `${c.name}: ${c.vertices} vertices, 4 triangles`);
    assert.deepEqual(await stats(app.page), { file: c.name, vertices: c.vertices, triangles: 4 });
    // A file with vertex colours is shown in colour; one without falls back to shaded.
    assert.equal(await viewMode(), c.colours ? 'colors' : 'shaded');
    const a = assertMeshVisible(await shoot(app.page, `format-${c.name.replace('.', '-')}`), c.name);
    if (c.colours) assert.ok(a.saturatedFraction > 0.3, `${c.name}: vertex colours not visible`);
    else assert.ok(a.saturatedFraction < 0.05, `${c.name}: colours where none were given`);
  });
}

test('a binary STL is read and welded as well', async () => {
  // 80-byte header, triangle count, then per triangle: normal, 3 corners, attribute byte count.
  const { TETRA } = await import('./fixtures.mjs');
  const stl = Buffer.alloc(84 + 50 * 4);
  stl.writeUInt32LE(4, 80);
  TETRA.triangles.forEach((t, f) => {
    t.forEach((i, k) => TETRA.positions[i].forEach((v, d) => stl.writeFloatLE(v, 84 + 50 * f + 12 + 12 * k + 4 * d)));
  });
  const s = await openFile(app.page, 'binary.stl', stl);
  assert.equal(s.text, 'binary.stl: 4 vertices, 4 triangles');
});

test('a file dropped on the page is opened, with an overlay while dragging', async () => {
  const { page } = app;
  const dataTransfer = await page.evaluateHandle((text) => {
    const transfer = new DataTransfer();
    transfer.items.add(new File([text], 'dropped.obj'));
    return transfer;
  }, tetraObj());
  const overlay = page.getByTestId('drop-overlay');
  await page.dispatchEvent('main', 'dragenter', { dataTransfer });
  assert.equal(await overlay.isVisible(), true, 'no drop overlay while dragging a file');
  await page.dispatchEvent('main', 'drop', { dataTransfer });
  assert.equal(await overlay.isVisible(), false, 'drop overlay stays after the drop');
  await waitForStatusAbout(page, 'dropped.obj');
  assert.deepEqual(await stats(page), { file: 'dropped.obj', vertices: 4, triangles: 4 });
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
