// docs/api is the package's API reference as TypeDoc (with typedoc-plugin-markdown) makes it from
// the declarations of package/src: committed so that it reads on GitHub and in reviews, and
// regenerated here to fail when a declaration or doc comment changed without it.
// Regenerate with: npm run docs:api
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { test } from 'node:test';

import { repoRoot } from '../wasm/support.mjs';

function files(dir) {
  return fs.readdirSync(dir, { recursive: true }).filter((f) => fs.statSync(path.join(dir, f)).isFile()).sort();
}

test('docs/api matches what TypeDoc makes of package/src now', () => {
  const out = fs.mkdtempSync(path.join(os.tmpdir(), 'geoshift-api-'));
  try {
    execFileSync(process.execPath, [path.join(repoRoot, 'node_modules/typedoc/bin/typedoc'), '--options', path.join(repoRoot, 'package/typedoc.json'),
      '--out', out, '--logLevel', 'Warn'], { stdio: 'pipe' });
    const committed = path.join(repoRoot, 'docs/api');
    assert.deepEqual(files(committed), files(out), 'docs/api has other files than TypeDoc makes: npm run docs:api');
    for (const f of files(out)) {
      assert.equal(fs.readFileSync(path.join(committed, f), 'utf8'), fs.readFileSync(path.join(out, f), 'utf8'), `docs/api/${f} is out of date: npm run docs:api`);
    }
    assert.match(fs.readFileSync(path.join(out, 'index.md'), 'utf8'), /### Geoshift\b[\s\S]*denoise\(\)/, 'the reference documents the API');
  } finally {
    fs.rmSync(out, { recursive: true, force: true });
  }
});
