// The module's parameter tables (paramSpecs(), the core's params.hpp: what the ops accept) and
// OpParams of wasm/geoshift.d.ts (what TypeScript callers may send) name the same ops with the same
// parameters and choices, so that any op or parameter added or changed on one side only fails here.
// The tables also hold what the ops do: an unknown name is refused, each default is accepted.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { before, test } from 'node:test';

import { loadGeoshift } from './support.mjs';
import { box } from './filter-support.mjs';

const source = (path) => readFileSync(new URL(`../../${path}`, import.meta.url), 'utf8');

let geoshift;
before(async () => {
  geoshift = await loadGeoshift();
});

/** op -> { name -> its declared type text }, from the members `name: { a?: T; b?: U };` of OpParams. */
function declaredParams(dts) {
  const start = dts.indexOf('export interface OpParams {');
  const body = dts.slice(start, dts.indexOf('\n}\n', start));
  const withoutComments = body.replace(/\/\*[\s\S]*?\*\//g, '').replace(/\/\/.*$/gm, '');
  const ops = new Map();
  for (const m of withoutComments.matchAll(/^\s*(\w+)\s*:\s*\{([^}]*)\}\s*;/gm)) {
    ops.set(m[1], new Map([...m[2].matchAll(/(\w+)\??\s*:\s*([^;]+);?/g)].map((p) => [p[1], p[2].trim()])));
  }
  return ops;
}

test('the parsers read something (a change of layout must not make the comparison empty)', () => {
  const declared = declaredParams(source('wasm/geoshift.d.ts'));
  assert.ok(declared.size >= 5, `geoshift.d.ts: ${[...declared.keys()]}`);
  assert.ok(declared.get('filter')?.has('signal'), 'geoshift.d.ts filter params');
  assert.ok(Object.keys(geoshift.paramSpecs()).length >= 5);
});

test('every op has a parameter table, and geoshift.d.ts declares the same ops, names and choices', () => {
  const specs = geoshift.paramSpecs();
  const declared = declaredParams(source('wasm/geoshift.d.ts'));
  assert.deepEqual([...geoshift.ops()].sort(), Object.keys(specs).sort(), 'ops() against paramSpecs()');
  assert.deepEqual([...declared.keys()].sort(), Object.keys(specs).sort(), 'ops');
  for (const [op, { params }] of Object.entries(specs)) {
    assert.deepEqual([...declared.get(op).keys()].sort(), Object.keys(params).sort(), `parameters of op "${op}"`);
    for (const [name, spec] of Object.entries(params)) {
      const type = declared.get(op).get(name);
      if (spec.type === 'enum') {
        const choices = [...type.matchAll(/'([^']*)'/g)].map((m) => m[1]).sort();
        assert.deepEqual(choices, [...spec.values].sort(), `choices of ${op}.${name}`);
      } else {
        const ts = { number: 'number', integer: 'number', boolean: 'boolean', string: 'string' }[spec.type];
        assert.equal(type, spec.list ? `${ts} | ${ts}[]` : ts, `type of ${op}.${name}`);
      }
    }
  }
});

test('the comparison sees a difference (a parameter on one side only)', () => {
  const dts = source('wasm/geoshift.d.ts').replace("kind?: 'abs'", "extra?: number; kind?: 'abs'");
  assert.notDeepEqual([...declaredParams(dts).get('curvature').keys()].sort(), Object.keys(geoshift.paramSpecs().curvature.params).sort());
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
