// One table of denoise requests (tests/data/denoise-requests.json), good and bad, through the three
// front ends that take them: the CLI (`geoshift denoise --kebab-case ...`), the wasm op and Python
// (geoshift.denoise(mesh, snake_case=...)). What a request means is the core's alone
// (denoise_request.hpp), so all three must accept and refuse alike, with the same message, and
// give the same positions when they accept (1e-5 relative; the module loads float32 positions).
import { test, before } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import { loadGeoshift, nativeCli, readOff, repoRoot, scratchDir } from './support.mjs';
import { assertClose, box, jiggle, writeCoff } from './filter-support.mjs';

const table = JSON.parse(fs.readFileSync(path.join(repoRoot, 'tests/data/denoise-requests.json'), 'utf8')).requests;
const python = path.join(repoRoot, 'build/venv/bin/python');
const noisy = jiggle(box(4), 0.05);

let geoshift;
let dir;
let input;
before(async () => {
  geoshift = await loadGeoshift();
  dir = scratchDir('geoshift-denoise-requests-');
  input = path.join(dir, 'noisy.off');
  writeCoff(input, noisy);
});

// The CLI's spelling (cliOptionName in params.hpp): kebab-case, and the one option named otherwise.
const cliName = (name) => (name === 'iterations' ? '--taubin-iterations' : `--${name.replace(/[A-Z]/g, (c) => `-${c.toLowerCase()}`)}`);
const snakeName = (name) => (name === 'lambda' ? 'lambda_' : name.replace(/[A-Z]/g, (c) => `_${c.toLowerCase()}`));

function throughCli(params, index) {
  const args = [];
  for (const [name, value] of Object.entries(params)) {
    if (value === true) args.push(cliName(name));
    else args.push(cliName(name), Array.isArray(value) ? value.join(',') : String(value));
  }
  const out = path.join(dir, `cli-${index}.off`);
  const r = spawnSync(nativeCli, ['denoise', input, '-o', out, ...args], { encoding: 'utf8' });
  if (r.status === 0) return { ok: true, positions: readOff(out).positions };
  const line = r.stderr.split('\n').find((l) => l.startsWith('geoshift: error: '));
  return { ok: false, error: line ? line.slice('geoshift: error: '.length) : r.stderr };
}

function throughWasm(params) {
  const { handle, ok, error } = geoshift.loadMesh(noisy.positions, noisy.indices);
  assert.equal(ok, true, error);
  const r = geoshift.run(handle, 'denoise', params);
  geoshift.freeMesh(handle);
  return r.ok ? { ok: true, positions: r.positions } : { ok: false, error: r.error };
}

// Every request in one Python process: the file read as the CLI reads it, each request's keywords
// in Python's spelling; JSON out.
function throughPython() {
  const script = `
import json, sys
import geoshift
mesh = geoshift.read(sys.argv[1]).mesh
out = []
for kwargs in json.loads(sys.argv[2]):
    try:
        r = geoshift.denoise(mesh, **kwargs)
        out.append({"ok": True, "positions": r.mesh.positions.ravel().tolist()})
    except geoshift.InputError as e:
        out.append({"ok": False, "error": str(e)})
print(json.dumps(out))
`;
  const requests = table.map(({ params }) => Object.fromEntries(Object.entries(params).map(([k, v]) => [snakeName(k), v])));
  const stdout = execFileSync(python, ['-c', script, input, JSON.stringify(requests)], { encoding: 'utf8', maxBuffer: 1 << 28 });
  return JSON.parse(stdout);
}

test('the table holds good and bad requests', () => {
  assert.ok(table.filter((r) => r.refused).length >= 10 && table.filter((r) => !r.refused).length >= 10);
});

test('the CLI, the wasm op and Python accept and refuse every request alike, with the same message and result', (t) => {
  const viaPython = fs.existsSync(python) ? throughPython() : null;
  if (!viaPython) t.diagnostic(`${python} is missing (bootstrap without Python): CLI and wasm only`);
  table.forEach(({ params, refused }, i) => {
    const what = JSON.stringify(params);
    const cli = throughCli(params, i);
    const wasm = throughWasm(params);
    const answers = { cli, wasm, ...(viaPython ? { python: viaPython[i] } : {}) };
    for (const [front, r] of Object.entries(answers)) {
      assert.equal(r.ok, !refused, `${what} through ${front}: ${r.ok ? 'accepted' : r.error}`);
      if (refused) {
        assert.ok(r.error.includes(refused), `${what} through ${front}: "${r.error}" does not say "${refused}"`);
        assert.equal(r.error, cli.error, `${what}: ${front} and the CLI word the refusal differently`);
      }
    }
    if (!refused) {
      assertClose(assert, wasm.positions, cli.positions, `${what}: wasm against the CLI`);
      if (viaPython) assertClose(assert, Float32Array.from(viaPython[i].positions), cli.positions, `${what}: Python against the CLI`);
    }
  });
});
