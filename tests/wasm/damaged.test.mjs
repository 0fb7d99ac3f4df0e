// The catalogue of damaged and awkward files (tests/data/damaged, manifest.json) through the native
// CLI (`geoshift info FILE`, run beside the file) and the wasm module's readFile: each gives the
// message the manifest names, and the two give the same message. The page's side is
// tests/e2e/damaged.test.mjs.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import { loadGeoshift, nativeCli, repoRoot } from './support.mjs';

const dir = path.join(repoRoot, 'tests/data/damaged');
const { cases } = JSON.parse(fs.readFileSync(path.join(dir, 'manifest.json'), 'utf8'));
// The CLI's default (ReadOptions::maxVertices); the app passes the same.
const MAX_VERTICES = 50_000_000;

let geoshift;
before(async () => { geoshift = await loadGeoshift(); });

/** `geoshift info FILE` in the catalogue's directory: { status, error (after "geoshift: error: "), stdout, notes }. */
function cli(file) {
  const r = spawnSync(nativeCli, ['info', file], { cwd: dir, encoding: 'utf8', timeout: 60_000 });
  const lines = r.stderr.split('\n');
  const error = lines.find((l) => l.startsWith('geoshift: error: '))?.slice('geoshift: error: '.length) ?? null;
  const notes = lines.filter((l) => l.startsWith('geoshift: note: ')).join('\n');
  return { status: r.status, error, stdout: r.stdout, notes, stderr: r.stderr };
}

function read(file) {
  return geoshift.readFile(file, new Uint8Array(fs.readFileSync(path.join(dir, file))), MAX_VERTICES);
}

test('the catalogue holds at least 30 damaged files, each named once, and every file is in it', () => {
  const names = cases.map((c) => c.file);
  assert.equal(new Set(names).size, names.length, 'a file is listed twice');
  assert.ok(cases.filter((c) => c.error).length >= 30);
  const onDisk = fs.readdirSync(dir).filter((f) => f !== 'manifest.json').sort();
  assert.deepEqual(onDisk, [...names].sort());
  for (const ext of ['.glb', '.gltf', '.obj', '.off', '.ply', '.stl']) {
    assert.ok(names.some((n) => n.endsWith(ext) && cases.find((c) => c.file === n).error), `no damaged ${ext}`);
  }
});

test('the committed files are what scripts/make-damaged.mjs writes', () => {
  execFileSync(process.execPath, [path.join(repoRoot, 'scripts/make-damaged.mjs'), '--check'], { stdio: 'pipe' });
});

for (const c of cases) {
  test(`${c.file}: ${c.what}`, () => {
    const native = cli(c.file);
    const wasm = read(c.file);
    if (c.error) {
      assert.notEqual(native.status, 0, `the CLI accepted ${c.file}`);
      assert.ok(native.error, `the CLI gave no error line: ${native.stderr}`);
      assert.ok(native.error.includes(c.error), `CLI: ${native.error}`);
      assert.equal(wasm.ok, false, `wasm accepted ${c.file}`);
      assert.ok(wasm.error.includes(c.error), `wasm: ${wasm.error}`);
      // One message: the module's is the CLI's (the module may name the file and part where the
      // CLI's mesh building does not).
      assert.ok(wasm.error.includes(native.error), `CLI and wasm differ:\n  ${native.error}\n  ${wasm.error}`);
      assert.ok(wasm.error.startsWith(`${c.file}:`), `the message does not name the file first: ${wasm.error}`);
    } else {
      assert.equal(native.status, 0, `the CLI refused ${c.file}: ${native.stderr}`);
      assert.equal(wasm.ok, true, `wasm refused ${c.file}: ${wasm.error}`);
      assert.equal(wasm.vertices, c.opens.vertices);
      assert.equal(wasm.triangles, c.opens.triangles);
      assert.match(native.stdout, new RegExp(`^  vertices +${c.opens.vertices} `, 'm'));
      assert.match(native.stdout, new RegExp(`^  faces +${c.opens.triangles} `, 'm'));
      if (c.opens.report) {
        assert.ok(native.notes.includes(c.opens.report), `CLI notes: ${native.notes}`);
        const messages = wasm.parts.flatMap((p) => p.report.messages).join('\n');
        assert.ok(messages.includes(c.opens.report), `wasm report: ${messages}`);
      }
    }
  });
}

test('readFile leaves nothing behind and keeps working after failures', () => {
  const good = read('ply-big-endian.ply');
  for (const c of cases) read(c.file);
  assert.deepEqual(read('ply-big-endian.ply'), good);
});

test('readFile checks its arguments at the edge', () => {
  assert.match(geoshift.readFile('a.obj', [1, 2, 3], 10).error, /Uint8Array/);
  assert.match(geoshift.readFile('a.obj', new Uint8Array(3), 0).error, /maxVertices/);
  // A name with directories is read under its last part: messages never show a path of the caller.
  const r = geoshift.readFile('some/dir/empty.obj', new Uint8Array(0), 10);
  assert.equal(r.error, 'empty.obj: the file is empty (0 bytes)');
});

test('the vertex limit the caller gives is the one the readers apply', () => {
  const bytes = new Uint8Array(fs.readFileSync(path.join(dir, 'ply-big-endian.ply')));
  assert.equal(geoshift.readFile('ply-big-endian.ply', bytes, 3).ok, true);
  const r = geoshift.readFile('t.obj', new TextEncoder().encode('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n'), 2);
  assert.equal(r.ok, false);
  assert.match(r.error, /3 vertices, more than the limit of 2/);
});
