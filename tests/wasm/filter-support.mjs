// Helpers of the filter and denoise tests: small procedural meshes with signals, COFF writing so the
// native CLI gets the same colors, and running the CLI on them.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import { firstMismatch, jitter, nativeCli, readGlbAttribute } from './support.mjs';

// An icosphere of radius 1: 12 * 4^k / ... vertices (k = 2: 162, k = 3: 642), outward-facing.
export function icosphere(subdivisions = 2) {
  const t = (1 + Math.sqrt(5)) / 2;
  let points = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
    [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]];
  let faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
    [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11],
    [6, 2, 10], [8, 6, 7], [9, 8, 1]];
  const unit = ([x, y, z]) => {
    const n = Math.hypot(x, y, z);
    return [x / n, y / n, z / n];
  };
  points = points.map(unit);
  for (let s = 0; s < subdivisions; ++s) {
    const middle = new Map();
    const mid = (a, b) => {
      const key = a < b ? `${a},${b}` : `${b},${a}`;
      if (!middle.has(key)) {
        points.push(unit(points[a].map((v, k) => (v + points[b][k]) / 2)));
        middle.set(key, points.length - 1);
      }
      return middle.get(key);
    };
    faces = faces.flatMap(([a, b, c]) => {
      const [ab, bc, ca] = [mid(a, b), mid(b, c), mid(c, a)];
      return [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]];
    });
  }
  return { positions: new Float32Array(points.flat()), indices: new Uint32Array(faces.flat()) };
}

// The sphere with a red upper and a blue lower half, every channel jittered by up to ±noise.
export function twoColorSphere(subdivisions = 2, noise = 0.12, seed = 3) {
  const mesh = icosphere(subdivisions);
  const rand = jitter(seed);
  const colors = new Float32Array(mesh.positions.length);
  for (let v = 0; v < mesh.positions.length / 3; ++v) {
    const base = mesh.positions[3 * v + 2] > 0 ? [0.8, 0.15, 0.1] : [0.1, 0.2, 0.75];
    for (let c = 0; c < 3; ++c) colors[3 * v + c] = Math.min(1, Math.max(0, base[c] + noise * rand()));
  }
  return { ...mesh, colors };
}

// Moves every vertex by up to ±amount along each axis; coincident vertices move alike, so a mesh
// whose faces have their own corners stays closed.
export function jiggle(mesh, amount, seed = 9) {
  const rand = jitter(seed);
  const offsets = new Map();
  const positions = Float32Array.from(mesh.positions);
  for (let v = 0; v < positions.length / 3; ++v) {
    const key = `${positions[3 * v]},${positions[3 * v + 1]},${positions[3 * v + 2]}`;
    if (!offsets.has(key)) offsets.set(key, [rand(), rand(), rand()].map((r) => amount * r));
    for (let c = 0; c < 3; ++c) positions[3 * v + c] += offsets.get(key)[c];
  }
  return { ...mesh, positions };
}

// The surface of the cube [-1, 1]^3 as an n x n grid per side, each side with its own vertices
// (the module and the CLI weld them): sharp edges and corners for the denoiser.
export function box(n = 6) {
  const positions = [];
  const indices = [];
  const sides = [[0, 1, 2], [1, 2, 0], [2, 0, 1]];
  for (const [a, b, c] of sides) {
    for (const sign of [1, -1]) {
      const start = positions.length / 3;
      for (let j = 0; j <= n; ++j) {
        for (let i = 0; i <= n; ++i) {
          const p = [0, 0, 0];
          p[a] = (2 * i) / n - 1;
          p[b] = (2 * j) / n - 1;
          p[c] = sign;
          positions.push(...p);
        }
      }
      const at = (i, j) => start + j * (n + 1) + i;
      for (let j = 0; j < n; ++j) {
        for (let i = 0; i < n; ++i) {
          // (a, b, c) is a right-handed frame, so i, j counter-clockwise seen from +c.
          const quad = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
          if (sign < 0) quad.reverse();
          indices.push(quad[0], quad[1], quad[2], quad[0], quad[2], quad[3]);
        }
      }
    }
  }
  return { positions: new Float32Array(positions), indices: new Uint32Array(indices) };
}

// Decimal with a point, so the OFF reader takes colors as 0-1 floats even when one is exactly 0 or 1.
const decimal = (x) => (Number.isInteger(x) ? x.toFixed(1) : String(x));

// OFF (or COFF with mesh.colors, 0-1 floats) with the float32 values written exactly.
export function writeCoff(file, { positions, indices, colors }) {
  const lines = [colors ? 'COFF' : 'OFF', `${positions.length / 3} ${indices.length / 3} 0`];
  for (let v = 0; v < positions.length / 3; ++v) {
    const xyz = [positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]].map(String);
    if (colors) xyz.push(colors[3 * v], colors[3 * v + 1], colors[3 * v + 2], 1);
    lines.push(xyz.map((x) => (typeof x === 'number' ? decimal(x) : x)).join(' '));
  }
  for (let i = 0; i < indices.length; i += 3) lines.push(`3 ${indices[i]} ${indices[i + 1]} ${indices[i + 2]}`);
  fs.writeFileSync(file, `${lines.join('\n')}\n`);
}

// `geoshift COMMAND IN -o OUT.glb ARGS...`; returns a reader of the output's attributes.
export function runNative(dir, command, input, args) {
  if (!fs.existsSync(nativeCli)) {
    throw new Error(`the native CLI ${nativeCli} is missing: build it (cmake --build build/native-release ` +
      '--target geoshift) or point GEOSHIFT_NATIVE_CLI at one');
  }
  const glb = path.join(dir, `${path.basename(input, '.off')}-${command}-${args.join('_').replace(/\W/g, '')}.glb`);
  execFileSync(nativeCli, [command, input, '-o', glb, ...args], { stdio: 'pipe' });
  return (attribute) => {
    const values = readGlbAttribute(glb, attribute);
    // COLOR_0 may be RGBA in the file; run() gives RGB.
    if (attribute === 'COLOR_0' && values.length === (4 * readGlbAttribute(glb, 'POSITION').length) / 3) {
      return values.filter((_, i) => i % 4 !== 3);
    }
    return values;
  };
}

export function assertClose(assert, actual, expected, what, relative = 1e-5) {
  assert.ok(actual, `${what}: missing from the result`);
  assert.equal(actual.length, expected.length, `${what}: lengths differ`);
  const i = firstMismatch(actual, expected, relative);
  assert.equal(i, -1, i < 0 ? '' : `${what} at ${i}: wasm ${actual[i]}, native ${expected[i]}`);
}

export function sameBits(a, b) {
  return Buffer.from(a.buffer, a.byteOffset, a.byteLength).equals(Buffer.from(b.buffer, b.byteOffset, b.byteLength));
}
