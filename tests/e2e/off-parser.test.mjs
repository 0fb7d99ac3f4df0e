// Unit tests of web/src/off.ts and web/src/weld.ts, run in the browser through the Vite dev server
// (which compiles the TypeScript on request), so they test exactly the code the app runs.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { useApp } from './harness.mjs';

const app = useApp();

/** Parses OFF text in the page; returns plain arrays, or { error } with the message. */
function parseOff(text) {
  return app.page.evaluate(async (t) => {
    const { parseOff } = await import('/src/off.ts');
    try {
      const m = parseOff(t);
      return {
        positions: [...m.positions], indices: [...m.indices], faceCount: m.faceCount,
        normals: m.normals && [...m.normals], colors: m.colors && [...m.colors].map((c) => Math.round(c * 1000) / 1000),
      };
    } catch (e) {
      return { error: `${e.name}: ${e.message}` };
    }
  }, text);
}

test('plain OFF with comments, blank lines and counts on the header line', async () => {
  const m = await parseOff('# a triangle\nOFF 3 1 0\n\n0 0 0 # origin\n1 0 0\n0 1 0\n3 0 1 2\n');
  assert.deepEqual(m.positions, [0, 0, 0, 1, 0, 0, 0, 1, 0]);
  assert.deepEqual(m.indices, [0, 1, 2]);
  assert.equal(m.normals, null);
  assert.equal(m.colors, null);
});

test('polygons are fan-triangulated; points and edges are skipped', async () => {
  const m = await parseOff('OFF\n5 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 0\n4 0 1 2 3\n2 0 4\n3 1 4 2\n');
  assert.deepEqual(m.indices, [0, 1, 2, 0, 2, 3, 1, 4, 2]);
  assert.equal(m.faceCount, 3);
});

test('files without the OFF keyword start with the counts', async () => {
  const m = await parseOff('3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0\n');
  assert.deepEqual(m.indices, [2, 1, 0]);
});

test('COFF colours: integers are 0..255, decimals 0..1, alpha is dropped', async () => {
  const m = await parseOff('COFF\n3 1 0\n0 0 0 255 0 51 255\n1 0 0 0.5 1.0 0\n0 1 0 0 0 255\n3 0 1 2 255 255 255\n');
  assert.deepEqual(m.colors, [1, 0, 0.2, 0.5, 1, 0, 0, 0, 1]);
});

test('NOFF normals and CNOFF normals followed by colours', async () => {
  const n = await parseOff('NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 -1\n3 0 1 2\n');
  assert.deepEqual(n.normals, [0, 0, 1, 0, 0, 1, 0, 0, -1]);
  const cn = await parseOff('CNOFF\n1 0 0\n0 0 0 0 1 0 255 128 0\n');
  assert.deepEqual(cn.normals, [0, 1, 0]);
  assert.deepEqual(cn.colors, [1, 0.502, 0]);
});

test('errors name the problem and the line', async () => {
  const cases = [
    ['', /the file is empty/],
    ['OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n', /line 6: face 0 refers to vertex 3, but the file has 3 vertices/],
    ['OFF\n3 1 0\n0 0 0\n1 0 0\n', /announces 3 vertices, but the file ends after 2/],
    ['OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n', /announces 2 faces, but the file ends after 1/],
    ['OFF\n1 0 0\n0 zero 0\n', /line 3: expected 3 vertex coordinates, but found "zero"/],
    ['OFF\n1 0 0\n0 0\n', /line 3: expected 3 vertex coordinates, but the line ends/],
    ['OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n', /expected 3 vertex indices/],
    ['OFF BINARY\n', /binary OFF files are not supported/],
    ['4OFF\n1 0 0\n0 0 0 0\n', /more than three coordinates/],
    ['PLY\n', /expected the OFF keyword/],
    ['OFF\n-3 1 0\n', /number of vertices must be a whole number/],
  ];
  for (const [text, message] of cases) {
    const m = await parseOff(text);
    assert.ok(m.error, `accepted: ${JSON.stringify(text)}`);
    assert.match(m.error, /^OffError: /);
    assert.match(m.error, message);
  }
});

test('weld merges identical corners only, across all attributes', async () => {
  const result = await app.page.evaluate(async () => {
    // The page cannot import 'three' by name; take the URL Vite rewrote it to in weld.ts, so that
    // both use the same module instance (weld checks attributes with instanceof).
    const source = await (await fetch('/src/weld.ts')).text();
    const threeUrl = /from\s*["']([^"']*\/deps\/three\.js[^"']*)["']/.exec(source)[1];
    const { BufferAttribute, BufferGeometry } = await import(threeUrl);
    const { weld } = await import('/src/weld.ts');
    // Triangles 0 and 1 share all corners (1 = 3, 2 = 5, and corner 4 is -0, which equals 0);
    // triangle 2 starts at the same place as corner 0 but with another colour: a seam to keep.
    const white = [1, 1, 1];
    const g = new BufferGeometry();
    g.setAttribute('position', new BufferAttribute(new Float32Array([
      0, 0, 0, 1, 0, 0, 0, 1, 0,
      1, 0, 0, -0, 0, 0, 0, 1, 0,
      0, 0, 0, 1, 0, 0, 0, 0, 1,
    ]), 3));
    g.setAttribute('color', new BufferAttribute(new Float32Array([
      ...white, ...white, ...white, ...white, ...white, ...white, 0, 0, 0, ...white, ...white,
    ]), 3));
    const w = weld(g);
    return { count: w.getAttribute('position').count, index: [...w.index.array] };
  });
  assert.deepEqual(result, { count: 5, index: [0, 1, 2, 1, 0, 2, 3, 1, 4] });
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors.map(String), []);
});
