// The catalogue of damaged and awkward files (tests/data/damaged, manifest.json) given to the page:
// each damaged file is refused with the message the manifest names, which is the one the wasm
// module's readFile gives under Node (and tests/wasm/damaged.test.mjs shows that to be the CLI's),
// and the mesh on screen stays. The awkward files open with the core's triangle counts.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { before, test } from 'node:test';
import { openFile, stats, useApp } from './harness.mjs';
import { loadGeoshift, repoRoot } from '../wasm/support.mjs';

const dir = path.join(repoRoot, 'tests/data/damaged');
const { cases } = JSON.parse(fs.readFileSync(path.join(dir, 'manifest.json'), 'utf8'));
const SAMPLE = { file: 'ChineseDragon-10kv.off', vertices: 10000, triangles: 19994 };

const app = useApp();
let geoshift;
before(async () => { geoshift = await loadGeoshift(); });

test('every damaged file of the catalogue is refused with the core\'s message; the sample stays', async (t) => {
  for (const c of cases.filter((x) => x.error)) {
    await t.test(c.file, async () => {
      const bytes = fs.readFileSync(path.join(dir, c.file));
      const s = await openFile(app.page, c.file, bytes);
      assert.equal(s.state, 'error', `${c.file} was accepted: ${s.text}`);
      assert.ok(s.text.startsWith(`Could not read ${c.file}`), s.text);
      assert.ok(s.text.includes(c.error), `${s.text}\n  should hold: ${c.error}`);
      // The same words as the module under Node (one line, without a final period), except that the
      // readers' hint at the CLI's option says in the page whose option it is.
      const moduleError = geoshift.readFile(c.file, new Uint8Array(bytes)).error.replace(/\.+$/, '');
      const hint = / \(raise (?:it|the limit) with --max-vertices\)/;
      const shown = moduleError.replace(hint, " (this page's limit; the command-line tool can raise it with --max-vertices)");
      assert.ok(s.text.includes(`Could not read ${shown}.`), `${s.text}\n  module: ${moduleError}`);
      assert.equal(hint.test(s.text), false, s.text);
      if (c.error.includes('more than the limit of')) assert.match(s.text, /the command-line tool can raise it/);
      assert.match(s.text, /Still showing ChineseDragon-10kv\.off\.$/);
      assert.deepEqual(await stats(app.page), SAMPLE);
    });
  }
});

test('the awkward files of the catalogue open with the core\'s counts', async (t) => {
  for (const c of cases.filter((x) => x.opens)) {
    await t.test(c.file, async () => {
      const s = await openFile(app.page, c.file, fs.readFileSync(path.join(dir, c.file)));
      assert.equal(s.state, 'ok', s.text);
      assert.equal((await stats(app.page)).triangles, c.opens.triangles);
    });
  }
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
