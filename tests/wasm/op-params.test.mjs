// The op table of wasm/ops.cpp (what the module accepts) and OpParams of wasm/geoshift.d.ts (what
// TypeScript callers may send) name the same ops with the same parameters. Read from the sources,
// so that any op added or changed on one side only fails here.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { test } from 'node:test';

const source = (path) => readFileSync(new URL(`../../${path}`, import.meta.url), 'utf8');

/** op -> sorted parameter names, from the entries {"name", runName, {"a", "b", ...}} of opTable(). */
function tableParams(cpp) {
  const body = cpp.slice(cpp.indexOf('opTable()'));
  const table = body.slice(body.indexOf('{'), body.indexOf('};'));
  const ops = new Map();
  for (const m of table.matchAll(/\{\s*"(\w+)"\s*,\s*\w+\s*,\s*\{([^}]*)\}\s*\}/g)) {
    ops.set(m[1], [...m[2].matchAll(/"(\w+)"/g)].map((p) => p[1]).sort());
  }
  return ops;
}

/** op -> sorted parameter names, from the members `name: { a?: ...; b?: ... };` of OpParams. */
function declaredParams(dts) {
  const start = dts.indexOf('export interface OpParams {');
  const body = dts.slice(start, dts.indexOf('\n}\n', start));
  const withoutComments = body.replace(/\/\*[\s\S]*?\*\//g, '').replace(/\/\/.*$/gm, '');
  const ops = new Map();
  for (const m of withoutComments.matchAll(/^\s*(\w+)\s*:\s*\{([^}]*)\}\s*;/gm)) {
    ops.set(m[1], [...m[2].matchAll(/(\w+)\??\s*:/g)].map((p) => p[1]).sort());
  }
  return ops;
}

test('the parsers read something (a change of layout must not make the comparison empty)', () => {
  const table = tableParams(source('wasm/ops.cpp'));
  const declared = declaredParams(source('wasm/geoshift.d.ts'));
  assert.ok(table.size >= 5, `ops.cpp: ${[...table.keys()]}`);
  assert.ok(declared.size >= 5, `geoshift.d.ts: ${[...declared.keys()]}`);
  assert.ok(table.get('filter')?.includes('signal'), 'ops.cpp filter params');
  assert.ok(declared.get('filter')?.includes('signal'), 'geoshift.d.ts filter params');
});

test('every op of wasm/ops.cpp is declared in wasm/geoshift.d.ts with the same parameter names', () => {
  const table = tableParams(source('wasm/ops.cpp'));
  const declared = declaredParams(source('wasm/geoshift.d.ts'));
  assert.deepEqual([...declared.keys()].sort(), [...table.keys()].sort(), 'ops');
  for (const [op, params] of table) {
    assert.deepEqual(declared.get(op), params, `parameters of op "${op}" (ops.cpp vs geoshift.d.ts)`);
  }
});

test('the comparison sees a difference (a parameter on one side only)', () => {
  const cpp = source('wasm/ops.cpp').replace('{"kind"}', '{"kind", "extra"}');
  assert.notDeepEqual(tableParams(cpp).get('curvature'), declaredParams(source('wasm/geoshift.d.ts')).get('curvature'));
});
