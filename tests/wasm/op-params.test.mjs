// The module's parameter tables (paramSpecs(), the core's params.hpp: what the ops accept) and the
// npm package's TypeScript options (package/src/options.ts, generated from those tables by
// package/scripts/generate-options.mjs) say the same: the committed file is what the generator
// makes of the tables now, so an op or parameter added or changed in the core fails here until the
// file is regenerated (npm run generate:options). tests/package compiles programs against the
// packed types (a wrong option name or type must not compile). The tables also hold what the ops
// do: an unknown name is refused, each default is accepted.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { before, test } from 'node:test';

import { optionsFile, render } from '../../package/scripts/generate-options.mjs';
import { loadGeoshift } from './support.mjs';
import { box } from './filter-support.mjs';

let geoshift;
before(async () => {
  geoshift = await loadGeoshift();
});

test('every op has a parameter table, and package/src/options.ts is what the generator makes of the tables', () => {
  const specs = geoshift.paramSpecs();
  assert.ok(Object.keys(specs).length >= 7, `ops: ${Object.keys(specs)}`);
  assert.deepEqual([...geoshift.ops()].sort(), Object.keys(specs).sort(), 'ops() against paramSpecs()');
  assert.equal(readFileSync(optionsFile, 'utf8'), render(specs), 'package/src/options.ts is out of date: npm run generate:options');
});

test('the generated options carry each table\'s names, types, choices, defaults and renames', () => {
  const specs = geoshift.paramSpecs();
  const text = render(specs);
  for (const [op, { params }] of Object.entries(specs)) {
    const start = text.indexOf(`export interface ${op[0].toUpperCase()}${op.slice(1)}Options {`);
    assert.ok(start >= 0, `no interface for ${op}`);
    const body = text.slice(start, text.indexOf('\n}\n', start));
    for (const [name, spec] of Object.entries(params)) {
      const declared = op === 'filter' && name === 'signal' ? 'field' : name;
      const type = body.match(new RegExp(`\\n  ${declared}\\?: ([^;]+);`))?.[1];
      assert.ok(type, `${op}.${name} is not declared`);
      if (spec.type === 'enum') assert.deepEqual(type.split(' | ').map((t) => t.slice(1, -1)).sort(), [...spec.values].sort(), `choices of ${op}.${name}`);
      else assert.equal(type, { number: 'number', integer: 'number', boolean: 'boolean', string: 'string' }[spec.type] + (spec.list ? ' | number[]' : ''), `type of ${op}.${name}`);
    }
  }
  // A parameter added to a table appears; a choice added to an enum too.
  const changed = structuredClone(specs);
  changed.curvature.params.extra = { type: 'integer', doc: 'An extra.', default: 3, min: 1 };
  changed.curvature.params.kind.values.push('extraKind');
  const again = render(changed);
  assert.match(again, /\n  extra\?: number;/);
  assert.match(again, /Default: `3`\. A whole number ≥ 1\./);
  assert.match(again, /'extraKind'/);
  assert.match(text, /export const coreNames[^]*filter: \{ field: 'signal' \}/);
});

test('each op accepts every default of its table and refuses a name it does not have, listing the accepted ones', () => {
  const mesh = box(3);
  const { handle } = geoshift.loadMesh(mesh.positions, mesh.indices, { colors: new Float32Array(mesh.positions.length).fill(0.5) });
  for (const [op, { params }] of Object.entries(geoshift.paramSpecs())) {
    const unknown = geoshift.run(handle, op, { notAParameter: 1 });
    assert.equal(unknown.ok, false);
    assert.match(unknown.error, new RegExp(`^${op}: unknown parameter "notAParameter" \\(accepted: ${Object.keys(params).join(', ')}\\)$`));
    // Only the parameters that apply without a condition: the others belong to another method.
    const defaults = Object.fromEntries(Object.entries(params).filter(([, s]) => 'default' in s && !s.when).map(([n, s]) => [n, s.default]));
    if (op === 'denoise') Object.assign(defaults, { method: 'taubin' });  // the cheapest method
    const r = geoshift.run(handle, op, defaults);
    assert.equal(r.ok, true, `${op} ${JSON.stringify(defaults)}: ${r.error}`);
  }
  geoshift.freeMesh(handle);
});
