// The view mode select changes how the mesh is drawn: vertex colours, uniform shading, wireframe.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { tetraGlb } from './fixtures.mjs';
import { assertMeshVisible, openFile, shoot, useApp } from './harness.mjs';
import { analyze, differenceFraction } from './png.mjs';

const app = useApp();

async function show(mode) {
  await app.page.getByTestId('view-mode').selectOption(mode);
  await app.page.evaluate(() => window.__geoshift.settled());
  return shoot(app.page, `view-mode-${mode}`);
}

test('a mesh without vertex colours offers no colour mode', async () => {
  const colours = app.page.locator('[data-testid="view-mode"] option[value="colors"]');
  assert.equal(await colours.isDisabled(), true);
});

test('switching between vertex colours, shaded and wireframe changes the pixels', async () => {
  const s = await openFile(app.page, 'coloured.glb', tetraGlb());
  assert.equal(s.state, 'ok', s.text);

  const coloured = await show('colors');
  const shaded = await show('shaded');
  const wireframe = await show('wireframe');
  const c = assertMeshVisible(coloured, 'vertex colours');
  const sh = assertMeshVisible(shaded, 'shaded');
  assert.ok(c.saturatedFraction > 0.5, `vertex colour mode shows few coloured pixels (${c.saturatedFraction})`);
  assert.ok(sh.saturatedFraction < 0.05, `shaded mode shows colour (${sh.saturatedFraction})`);
  assert.ok(differenceFraction(coloured, shaded) > 0.1, 'vertex colours and shaded look the same');
  // Wire lines cover far less of the view than filled triangles do.
  assert.ok(analyze(wireframe).coverage < sh.coverage * 0.5, 'wireframe looks filled');

  // And back: the colours come back, pixel for pixel.
  const again = await show('colors');
  assert.ok(differenceFraction(coloured, again) < 0.01, 'returning to vertex colours does not restore the view');
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
