// The op table of wasm/ops.cpp (what the module accepts) and optionNames of package/src/options.ts
// (what TypeScript callers of the package may send) name the same ops with the same parameters. Read from the sources,
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

/** op -> sorted parameter names, from the entries `name: ['a', 'b', ...],` of optionNames. */
function declaredParams(ts) {
  const start = ts.indexOf('export const optionNames');
  const body = ts.slice(ts.indexOf('= {', start), ts.indexOf('\n};', start));
  // coreNames: { op: { packageName: 'coreName' } }, the options the package names differently.
  const renames = ts.slice(ts.indexOf('export const coreNames'));
  const coreName = (op, name) => renames.match(new RegExp(`${op}: \\{[^}]*\\b${name}: '(\\w+)'`))?.[1] ?? name;
  const ops = new Map();
  for (const m of body.matchAll(/^\s*(\w+)\s*:\s*\[([^\]]*)\]/gm)) {
    ops.set(m[1], [...m[2].matchAll(/'(\w+)'/g)].map((p) => coreName(m[1], p[1])).sort());
  }
  return ops;
}

test('the parsers read something (a change of layout must not make the comparison empty)', () => {
  const table = tableParams(source('wasm/ops.cpp'));
  const declared = declaredParams(source('package/src/options.ts'));
  assert.ok(table.size >= 5, `ops.cpp: ${[...table.keys()]}`);
  assert.ok(declared.size >= 5, `options.ts: ${[...declared.keys()]}`);
  assert.ok(table.get('filter')?.includes('signal'), 'ops.cpp filter params');
  assert.ok(declared.get('filter')?.includes('signal'), 'options.ts filter params');
});

test('every op of wasm/ops.cpp is declared in package/src/options.ts with the same parameter names', () => {
  const table = tableParams(source('wasm/ops.cpp'));
  const declared = declaredParams(source('package/src/options.ts'));
  assert.deepEqual([...declared.keys()].sort(), [...table.keys()].sort(), 'ops');
  for (const [op, params] of table) {
    assert.deepEqual(declared.get(op), params, `parameters of op "${op}" (ops.cpp vs options.ts)`);
  }
});

test('the comparison sees a difference (a parameter on one side only)', () => {
  const cpp = source('wasm/ops.cpp').replace('{"kind"}', '{"kind", "extra"}');
  assert.notDeepEqual(tableParams(cpp).get('curvature'), declaredParams(source('package/src/options.ts')).get('curvature'));
});
