// Builds the package into package/dist: the TypeScript sources compiled by tsc (ES modules and
// declarations), and the module's two flavours copied from the wasm build (wasm/CMakeLists.txt).
//   node package/scripts/build.mjs        (scripts/bootstrap.sh runs it after the wasm build)
// GEOSHIFT_WASM_DIR: another wasm build directory (default build/wasm-release/wasm).
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const packageDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const repoRoot = path.resolve(packageDir, '..');
const wasmDir = path.resolve(process.env.GEOSHIFT_WASM_DIR ?? path.join(repoRoot, 'build/wasm-release/wasm'));
const dist = path.join(packageDir, 'dist');

// The flavours the package ships; the threaded one's pthread script goes in as .cjs for Node
// (src/node-worker.ts says why) and as text for browsers (src/worker.ts).
const FILES = ['geoshift_web.js', 'geoshift_web.wasm', 'geoshift_web_mt.js', 'geoshift_web_mt.wasm', 'geoshift_web_mt.worker.js'];

function fail(message) {
  console.error(`package/scripts/build.mjs: ${message}`);
  process.exit(1);
}

const { version } = JSON.parse(fs.readFileSync(path.join(packageDir, 'package.json'), 'utf8'));
const source = fs.readFileSync(path.join(packageDir, 'src/version.ts'), 'utf8');
if (!source.includes(`'${version}'`)) fail(`src/version.ts does not say package.json's version ${version}: change both together`);
for (const file of FILES) {
  if (!fs.existsSync(path.join(wasmDir, file))) fail(`${path.join(wasmDir, file)} is missing: build the wasm module first (scripts/bootstrap.sh)`);
}

fs.rmSync(dist, { recursive: true, force: true });
const tsc = path.join(repoRoot, 'node_modules/typescript/bin/tsc');
try {
  execFileSync(process.execPath, [tsc, '-p', path.join(packageDir, 'tsconfig.json')], { stdio: 'inherit' });
} catch {
  fail('tsc failed');
}
fs.mkdirSync(path.join(dist, 'wasm'));
for (const file of FILES.filter((f) => !f.endsWith('.worker.js'))) fs.copyFileSync(path.join(wasmDir, file), path.join(dist, 'wasm', file));
// Node starts the pthread workers from a file, with worker_threads: a CommonJS copy (src/node-worker.ts).
fs.copyFileSync(path.join(wasmDir, 'geoshift_web_mt.worker.js'), path.join(dist, 'wasm', 'geoshift_web_mt.worker.cjs'));
// Browsers start them from a blob of this text (src/worker.ts).
const pthread = fs.readFileSync(path.join(wasmDir, 'geoshift_web_mt.worker.js'), 'utf8');
fs.writeFileSync(path.join(dist, 'pthread-worker.js'), `// geoshift_web_mt.worker.js of the wasm build, as text (src/worker.ts says why).\nexport default ${JSON.stringify(pthread)};\n`);
console.log(`package/dist: geoshift ${version} built (wasm from ${path.relative(repoRoot, wasmDir) || wasmDir})`);
