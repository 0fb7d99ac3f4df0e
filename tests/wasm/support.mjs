// Shared helpers of the wasm tests: loading the Node flavours, small procedural meshes, OFF
// writing and GLB reading (for comparing with the native CLI).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';

export const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
// GEOSHIFT_WASM_DIR runs the tests against another build (another exception mode, a debug build).
export const wasmDir = path.resolve(process.env.GEOSHIFT_WASM_DIR ?? path.join(repoRoot, 'build/wasm-release/wasm'));
// GEOSHIFT_NATIVE_CLI compares with another native build of the CLI.
export const nativeCli = path.resolve(process.env.GEOSHIFT_NATIVE_CLI ?? path.join(repoRoot, 'build/native-release/cli/geoshift'));
// ../shared/data beside the repository (GEOSHIFT_SHARED_DATA overrides); tests skip when absent.
export const sharedData = process.env.GEOSHIFT_SHARED_DATA || path.join(repoRoot, '../shared/data');
export const sphereOff = path.join(sharedData, 'cgal_debian_libcgal_demo/data/meshes/sphere.off');

const require = createRequire(import.meta.url);

// A fresh directory under the system temp dir for one test file's outputs, removed when the
// process ends (each test file runs in its own process), so that test runs leave nothing behind.
export function scratchDir(prefix) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), prefix));
  process.once('exit', () => fs.rmSync(dir, { recursive: true, force: true }));
  return dir;
}

// The CommonJS flavours; `wasmBinary` because a CommonJS build under Node >= 18 would try to
// fetch() its .wasm by file path. The threaded one keeps its worker pool alive: call `close()`.
export async function loadGeoshift({ threads = false } = {}) {
  const name = threads ? 'geoshift_node_mt' : 'geoshift_node';
  const js = path.join(wasmDir, `${name}.js`);
  if (!fs.existsSync(js)) {
    throw new Error(`${js} is missing: build the wasm module first ` +
      '(emcmake cmake --preset wasm-release && cmake --build build/wasm-release), or run npm test');
  }
  const factory = require(js);
  const module = await factory({ wasmBinary: fs.readFileSync(path.join(wasmDir, `${name}.wasm`)) });
  module.close = () => module.PThread?.terminateAllThreads();
  return module;
}

// The median of some numbers (the mean of the middle two for an even count): benchmarks report it.
export function median(values) {
  const sorted = [...values].sort((a, b) => a - b);
  const mid = sorted.length >> 1;
  return sorted.length % 2 ? sorted[mid] : (sorted[mid - 1] + sorted[mid]) / 2;
}

// --- meshes ----------------------------------------------------------------------------------

// Reads an OFF file of triangles into { positions: Float32Array, indices: Uint32Array }.
export function readOff(file) {
  const tokens = fs.readFileSync(file, 'utf8').replace(/#.*$/gm, '').split(/\s+/).filter(Boolean);
  if (tokens[0] !== 'OFF') throw new Error(`${file}: not an OFF file`);
  const [nv, nf] = [Number(tokens[1]), Number(tokens[2])];
  let at = 4;
  const positions = new Float32Array(3 * nv);
  for (let i = 0; i < 3 * nv; ++i) positions[i] = Number(tokens[at++]);
  const indices = [];
  for (let f = 0; f < nf; ++f) {
    const n = Number(tokens[at++]);
    const ring = tokens.slice(at, at + n).map(Number);
    at += n;
    for (let k = 1; k + 1 < n; ++k) indices.push(ring[0], ring[k], ring[k + 1]);
  }
  return { positions, indices: new Uint32Array(indices) };
}

// Writes the float32 values exactly (JS prints the shortest decimal that reads back as the same
// number), so the native CLI, which reads doubles, starts from the very positions wasm gets.
export function writeOff(file, { positions, indices }) {
  const lines = ['OFF', `${positions.length / 3} ${indices.length / 3} 0`];
  for (let i = 0; i < positions.length; i += 3) lines.push(`${positions[i]} ${positions[i + 1]} ${positions[i + 2]}`);
  for (let i = 0; i < indices.length; i += 3) lines.push(`3 ${indices[i]} ${indices[i + 1]} ${indices[i + 2]}`);
  fs.writeFileSync(file, `${lines.join('\n')}\n`);
}

// Deterministic pseudo-random numbers in [-1, 1) (the tests must not change from run to run).
export function jitter(seed) {
  let s = seed >>> 0;
  return () => {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    return s / 2 ** 31 - 1;
  };
}

// A jittered n x n grid on the saddle z = x² - y²: both signs of Gaussian curvature, mean curvature
// near zero in the middle, and a boundary.
export function saddle(n = 12, seed = 7) {
  const rand = jitter(seed);
  const positions = [];
  for (let j = 0; j <= n; ++j) {
    for (let i = 0; i <= n; ++i) {
      const x = (2 * i) / n - 1 + 0.02 * rand();
      const y = (2 * j) / n - 1 + 0.02 * rand();
      positions.push(x, y, x * x - y * y + 0.01 * rand());
    }
  }
  const indices = [];
  const at = (i, j) => j * (n + 1) + i;
  for (let j = 0; j < n; ++j) {
    for (let i = 0; i < n; ++i) {
      indices.push(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return { positions: new Float32Array(positions), indices: new Uint32Array(indices) };
}

// The unit cube as glTF exporters write it: every face has its own four corners (24 vertices) or,
// with `perTriangle`, every triangle its own three (36 vertices). Counter-clockwise from outside.
export const cubeCorners = [
  [0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1],
];
export const cubeTriangles = [
  [0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
  [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7],
];
export function unweldedCube() {
  const positions = [];
  const corner = [];  // caller vertex -> cube corner
  for (const triangle of cubeTriangles) {
    for (const c of triangle) {
      positions.push(...cubeCorners[c]);
      corner.push(c);
    }
  }
  const indices = Uint32Array.from(corner, (_, i) => i);
  return { positions: new Float32Array(positions), indices, corner };
}

// --- GLB -------------------------------------------------------------------------------------

const componentArrays = { 5120: Int8Array, 5121: Uint8Array, 5122: Int16Array, 5123: Uint16Array, 5125: Uint32Array, 5126: Float32Array };
const typeSizes = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };

// Reads one attribute of the first primitive of the first mesh of a .glb (JSON chunk + BIN chunk),
// as a typed array of count × components.
export function readGlbAttribute(file, attribute) {
  const bytes = fs.readFileSync(file);
  const data = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (data.getUint32(0, true) !== 0x46546c67) throw new Error(`${file}: not a GLB file`);
  let json;
  let bin;
  for (let at = 12; at < bytes.length;) {
    const length = data.getUint32(at, true);
    const type = data.getUint32(at + 4, true);
    const chunk = bytes.subarray(at + 8, at + 8 + length);
    if (type === 0x4e4f534a) json = JSON.parse(new TextDecoder().decode(chunk));
    else if (type === 0x004e4942) bin = chunk;
    at += 8 + length;
  }
  const primitive = json.meshes?.[0]?.primitives?.[0];
  const accessorIndex = primitive?.attributes?.[attribute];
  if (accessorIndex === undefined) {
    throw new Error(`${file}: the first primitive has no attribute ${attribute} ` +
      `(it has ${Object.keys(primitive?.attributes ?? {}).join(', ')})`);
  }
  const accessor = json.accessors[accessorIndex];
  const view = json.bufferViews[accessor.bufferView];
  const TypedArray = componentArrays[accessor.componentType];
  const components = typeSizes[accessor.type];
  const stride = view.byteStride ?? components * TypedArray.BYTES_PER_ELEMENT;
  const start = (view.byteOffset ?? 0) + (accessor.byteOffset ?? 0);
  const out = new TypedArray(accessor.count * components);
  // Copied element by element: the BIN chunk offset need not be aligned for a direct view.
  const bin8 = new Uint8Array(bin);
  for (let i = 0; i < accessor.count; ++i) {
    const element = new TypedArray(bin8.slice(start + i * stride, start + i * stride + components * TypedArray.BYTES_PER_ELEMENT).buffer);
    out.set(element, i * components);
  }
  return out;
}

// --- comparisons -----------------------------------------------------------------------------

// Index of the first pair farther apart than `relative` of their magnitude, with an absolute floor
// of `relative` × 1% of the field's RMS for values near zero; -1 when all agree.
export function firstMismatch(actual, expected, relative = 1e-5) {
  let sumSquares = 0;
  for (const x of expected) sumSquares += x * x;
  const floor = 0.01 * Math.sqrt(sumSquares / Math.max(1, expected.length));
  for (let i = 0; i < expected.length; ++i) {
    const a = actual[i];
    const e = expected[i];
    if (!(Math.abs(a - e) <= relative * Math.max(Math.abs(a), Math.abs(e), floor))) return i;
  }
  return -1;
}
