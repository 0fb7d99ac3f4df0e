// Files the CLI writes stay true to the result (docs/io.md#normals): every command that writes a
// mesh, on inputs in every format with and without normals, writes .glb files the Khronos
// glTF-Validator finds no error in, and normals (glTF NORMAL, OBJ vn, PLY nx ny nz) that are unit
// length and those of the written positions: angle-weighted vertex normals of the written faces,
// as the core computes them (geometry.hpp). Inputs carry their own normals scaled by 2.5 (OBJ, PLY
// and OFF files do not require unit normals; the Fandisk OBJ of the shared data has such vn lines),
// so a writer that passed them through, or kept them after the vertices moved, fails here.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import validator from 'gltf-validator';

import { nativeCli, scratchDir } from './support.mjs';
import { box, jiggle } from './filter-support.mjs';

let dir;
before(() => {
  dir = scratchDir('geoshift-written-');
});

function cli(...args) {
  const r = spawnSync(nativeCli, args.map(String), { encoding: 'utf8' });
  assert.equal(r.status, 0, `geoshift ${args.join(' ')}: ${r.stderr}`);
  return r;
}

// --- normals of a triangle mesh, as the core's vertexNormals ---------------------------------

function angleWeightedNormals(positions, indices) {
  const n = new Float64Array(positions.length);
  const p = (v) => [positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]];
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const norm = (a) => Math.hypot(a[0], a[1], a[2]);
  for (let t = 0; t < indices.length; t += 3) {
    const corners = [indices[t], indices[t + 1], indices[t + 2]];
    const c = cross(sub(p(corners[1]), p(corners[0])), sub(p(corners[2]), p(corners[0])));
    const length = norm(c);
    if (!(length > 0)) continue;
    for (let k = 0; k < 3; ++k) {
      const at = p(corners[k]);
      const u = sub(p(corners[(k + 1) % 3]), at);
      const w = sub(p(corners[(k + 2) % 3]), at);
      const angle = Math.atan2(norm(cross(u, w)), u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
      for (let d = 0; d < 3; ++d) n[3 * corners[k] + d] += (angle * c[d]) / length;
    }
  }
  for (let v = 0; v < n.length; v += 3) {
    const length = Math.hypot(n[v], n[v + 1], n[v + 2]);
    for (let d = 0; d < 3; ++d) n[v + d] /= length;
  }
  return n;
}

// Every written normal of unit length (1e-4; not asked of an OBJ written back into its own file
// with the vn lines the command did not change, which OBJ allows) and, unless the normals are the
// filtered signal itself, within 0.5° of the written geometry's.
function assertNormalsOfPositions({ positions, indices, normals }, what, { signal = false, unit = true } = {}) {
  const expected = angleWeightedNormals(positions, indices);
  for (let v = 0; v < normals.length / 3; ++v) {
    const [x, y, z] = [normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]];
    const length = Math.hypot(x, y, z);
    if (unit) assert.ok(Math.abs(length - 1) < 1e-4, `${what}: normal ${v} has length ${length}`);
    if (signal) continue;
    const cos = (x * expected[3 * v] + y * expected[3 * v + 1] + z * expected[3 * v + 2]) / length;
    assert.ok(cos > Math.cos((0.5 * Math.PI) / 180), `${what}: normal ${v} is ${(Math.acos(Math.min(1, cos)) * 180) / Math.PI}° off the written surface's`);
  }
}

// --- the written files, read back ------------------------------------------------------------

const componentArrays = { 5121: Uint8Array, 5123: Uint16Array, 5125: Uint32Array, 5126: Float32Array };
const typeSizes = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };

// POSITION, NORMAL (or null) and indices of the first primitive of a .glb.
function readGlb(file) {
  const bytes = fs.readFileSync(file);
  const data = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  let json;
  let bin;
  for (let at = 12; at < bytes.length;) {
    const length = data.getUint32(at, true);
    const chunk = bytes.subarray(at + 8, at + 8 + length);
    if (data.getUint32(at + 4, true) === 0x4e4f534a) json = JSON.parse(new TextDecoder().decode(chunk));
    else bin = Uint8Array.from(chunk);
    at += 8 + length;
  }
  const accessor = (index) => {
    const a = json.accessors[index];
    const view = json.bufferViews[a.bufferView];
    const Type = componentArrays[a.componentType];
    const size = typeSizes[a.type];
    const stride = view.byteStride ?? size * Type.BYTES_PER_ELEMENT;
    const start = (view.byteOffset ?? 0) + (a.byteOffset ?? 0);
    const out = new Float64Array(a.count * size);
    for (let i = 0; i < a.count; ++i) {
      const element = new Type(bin.slice(start + i * stride, start + i * stride + size * Type.BYTES_PER_ELEMENT).buffer);
      for (let k = 0; k < size; ++k) out[i * size + k] = element[k];
    }
    return out;
  };
  const primitive = json.meshes[0].primitives[0];
  return {
    positions: accessor(primitive.attributes.POSITION),
    normals: primitive.attributes.NORMAL === undefined ? null : accessor(primitive.attributes.NORMAL),
    indices: accessor(primitive.indices),
  };
}

// v, vn and f lines; normals per vertex through the faces' vn references (null without them).
function readObj(file) {
  const v = [];
  const vn = [];
  const faces = [];  // [[vertex, normal or -1], x3]
  for (const line of fs.readFileSync(file, 'utf8').split('\n')) {
    const t = line.trim().split(/\s+/);
    if (t[0] === 'v') v.push(Number(t[1]), Number(t[2]), Number(t[3]));
    if (t[0] === 'vn') vn.push(Number(t[1]), Number(t[2]), Number(t[3]));
    if (t[0] === 'f') faces.push(t.slice(1).map((c) => { const [a, , n] = c.split('/'); return [Number(a) - 1, n ? Number(n) - 1 : -1]; }));
  }
  const indices = faces.flatMap((f) => f.map(([a]) => a));
  const referenced = faces.some((f) => f.some(([, n]) => n >= 0));
  let normals = null;
  if (referenced) {
    normals = new Float64Array(v.length);
    for (const f of faces) {
      for (const [a, n] of f) {
        assert.ok(n >= 0 && n < vn.length / 3, `${file}: a face corner without a valid vn reference`);
        for (let d = 0; d < 3; ++d) normals[3 * a + d] = vn[3 * n + d];
      }
    }
  }
  return { positions: Float64Array.from(v), indices, normals };
}

// A binary little endian PLY as geoshift writes it: scalar uchar/float/double vertex properties,
// faces as `list uchar int`.
function readPly(file) {
  const bytes = fs.readFileSync(file);
  const end = bytes.indexOf('end_header\n') + 'end_header\n'.length;
  const header = bytes.subarray(0, end).toString('latin1').split('\n');
  const props = [];
  let vertices = 0;
  let faces = 0;
  let element = '';
  for (const line of header) {
    const t = line.split(' ');
    if (t[0] === 'element') [element] = [t[1], t[1] === 'vertex' ? (vertices = Number(t[2])) : (faces = Number(t[2]))];
    if (t[0] === 'property' && element === 'vertex') props.push([t[1], t[2]]);
  }
  const data = new DataView(bytes.buffer, bytes.byteOffset + end);
  const size = { uchar: 1, float: 4, double: 8 };
  const get = { uchar: (at) => data.getUint8(at) / 255, float: (at) => data.getFloat32(at, true), double: (at) => data.getFloat64(at, true) };
  let at = 0;
  const columns = Object.fromEntries(props.map(([, name]) => [name, new Float64Array(vertices)]));
  for (let i = 0; i < vertices; ++i) {
    for (const [type, name] of props) {
      columns[name][i] = get[type](at);
      at += size[type];
    }
  }
  const indices = [];
  for (let f = 0; f < faces; ++f) {
    const n = data.getUint8(at);
    for (let k = 0; k < n; ++k) indices.push(data.getInt32(at + 1 + 4 * k, true));
    at += 1 + 4 * n;
  }
  const interleave = (a, b, c) => Float64Array.from({ length: 3 * vertices }, (_, i) => [a, b, c][i % 3][Math.floor(i / 3)]);
  return {
    positions: interleave(columns.x, columns.y, columns.z),
    indices,
    normals: columns.nx ? interleave(columns.nx, columns.ny, columns.nz) : null,
  };
}

async function assertValidGltf(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    externalResourceFunction: (uri) => Promise.resolve(new Uint8Array(fs.readFileSync(path.join(path.dirname(file), decodeURIComponent(uri))))),
  });
  const errors = report.issues.messages.filter((m) => m.severity === 0);
  assert.equal(report.issues.numErrors, 0, `${file}: glTF-Validator: ${errors.slice(0, 5).map((m) => `${m.code} ${m.pointer ?? ''}: ${m.message}`).join('; ')}`);
}

// --- inputs --------------------------------------------------------------------------------------

// A noisy box (sharp edges for the denoiser, a surface that moves under every filter), its vertices
// welded, with per-vertex colors for the color filters.
const mesh = (() => {
  const b = jiggle(box(4), 0.04);
  const key = (v) => `${b.positions[3 * v]},${b.positions[3 * v + 1]},${b.positions[3 * v + 2]}`;
  const index = new Map();
  const positions = [];
  const remap = [];
  for (let v = 0; v < b.positions.length / 3; ++v) {
    if (!index.has(key(v))) {
      index.set(key(v), positions.length / 3);
      positions.push(b.positions[3 * v], b.positions[3 * v + 1], b.positions[3 * v + 2]);
    }
    remap.push(index.get(key(v)));
  }
  const indices = Array.from(b.indices, (v) => remap[v]);
  const normals = Array.from(angleWeightedNormals(positions, indices), (x) => 2.5 * x);
  return { positions, indices, normals };
})();
const vertexCount = mesh.positions.length / 3;
const row = (a, v) => a.slice(3 * v, 3 * v + 3).join(' ');
const triangles = (f) => Array.from({ length: mesh.indices.length / 3 }, (_, t) => f(mesh.indices.slice(3 * t, 3 * t + 3)));

function writeInputs() {
  const files = {};
  const write = (name, text) => {
    files[name] = path.join(dir, name);
    fs.writeFileSync(files[name], text);
  };
  const vs = Array.from({ length: vertexCount }, (_, v) => `v ${row(mesh.positions, v)}`);
  const vns = Array.from({ length: vertexCount }, (_, v) => `vn ${row(mesh.normals, v)}`);
  write('plain.obj', [...vs, ...triangles((t) => `f ${t.map((v) => v + 1).join(' ')}`)].join('\n') + '\n');
  write('normals.obj', ['# normals scaled by 2.5', ...vs, ...vns, ...triangles((t) => `f ${t.map((v) => `${v + 1}//${v + 1}`).join(' ')}`)].join('\n') + '\n');
  const plyHeader = (normals) => ['ply', 'format ascii 1.0', `element vertex ${vertexCount}`, 'property float x', 'property float y', 'property float z',
    ...(normals ? ['property float nx', 'property float ny', 'property float nz'] : []),
    `element face ${mesh.indices.length / 3}`, 'property list uchar int vertex_indices', 'end_header'];
  const plyFaces = triangles((t) => `3 ${t.join(' ')}`);
  write('plain.ply', [...plyHeader(false), ...Array.from({ length: vertexCount }, (_, v) => row(mesh.positions, v)), ...plyFaces].join('\n') + '\n');
  write('normals.ply', [...plyHeader(true), ...Array.from({ length: vertexCount }, (_, v) => `${row(mesh.positions, v)} ${row(mesh.normals, v)}`), ...plyFaces].join('\n') + '\n');
  const offFaces = triangles((t) => `3 ${t.join(' ')}`);
  write('plain.off', ['OFF', `${vertexCount} ${mesh.indices.length / 3} 0`, ...Array.from({ length: vertexCount }, (_, v) => row(mesh.positions, v)), ...offFaces].join('\n') + '\n');
  write('normals.off', ['NOFF', `${vertexCount} ${mesh.indices.length / 3} 0`, ...Array.from({ length: vertexCount }, (_, v) => `${row(mesh.positions, v)} ${row(mesh.normals, v)}`), ...offFaces].join('\n') + '\n');
  write('plain.stl', ['solid box', ...triangles((t) => ['facet normal 0 0 0', 'outer loop', ...t.map((v) => `vertex ${row(mesh.positions, v)}`), 'endloop', 'endfacet'].join('\n')), 'endsolid box'].join('\n') + '\n');
  // glTF inputs by the CLI itself: 0 Taubin steps move nothing; the OBJ with normals gives NORMAL.
  for (const [from, name] of [['plain.obj', 'plain.glb'], ['normals.obj', 'normals.glb'], ['normals.obj', 'normals.gltf']]) {
    files[name] = path.join(dir, name);
    cli('smooth', files[from], '-o', files[name], '--iterations', 0);
  }
  return files;
}

// Every command that writes a mesh from a mesh; `filter --signal normal` writes the filtered normals.
const commands = [
  ['noise', ['--amount', '0.3', '--seed', '4']],
  ['smooth', ['--iterations', '3']],
  ['curvature', []],
  ['geodesic', ['--source', '0']],
  ['filter', ['--signal', 'curvature', '--kmax', '5']],
  ['filter', ['--signal', 'normal', '--kmax', '5']],
  ['filter', ['--signal', 'curvature', '--levels', '1', '--filter-geometry', '--alpha', '0.5', '--kmax', '5']],
  ['denoise', ['--passes', '1']],
  ['denoise', ['--method', 'bilateral', '--normal-iterations', '3']],
  ['wavelet', ['--levels', '1', '--alpha', '0.5']],
];

test('every command, on every input format with and without normals, writes valid glTF and normals of the written surface', async () => {
  const inputs = writeInputs();
  let checked = 0;
  for (const [input, file] of Object.entries(inputs)) {
    const own = path.extname(input);
    for (const [command, args] of commands) {
      const outputs = [...new Set(['.glb', '.obj', '.ply', own === '.stl' || own === '.off' ? '.glb' : own])];
      for (const ext of outputs) {
        const out = path.join(dir, `${path.basename(input, own)}-${own.slice(1)}-${command}-${checked}${ext}`);
        cli(command, file, '-o', out, ...args);
        const what = `${command} ${args.join(' ')}: ${input} -> ${ext}`;
        if (ext === '.glb' || ext === '.gltf') await assertValidGltf(out);
        const written = ext === '.glb' ? readGlb(out) : ext === '.obj' ? readObj(out) : ext === '.ply' ? readPly(out) : null;
        // Normals go where the input had them; with them they are those of the written surface.
        if (written?.normals) assertNormalsOfPositions(written, what, { signal: args.includes('normal'), unit: !(ext === '.obj' && own === '.obj') });
        if (written && input.startsWith('normals')) assert.ok(written.normals, `${what}: the normals were dropped`);
        ++checked;
      }
    }
  }
  assert.ok(checked >= 9 * commands.length * 3, `${checked} files checked`);
});

test('a terrain written in every format is valid glTF with sound normals where it has them', async () => {
  for (const ext of ['.glb', '.gltf', '.obj', '.ply']) {
    const out = path.join(dir, `terrain${ext}`);
    cli('terrain', '--procedural', 17, '--seed', 3, '-o', out);
    if (ext === '.glb' || ext === '.gltf') await assertValidGltf(out);
    const written = ext === '.glb' ? readGlb(out) : ext === '.obj' ? readObj(out) : ext === '.ply' ? readPly(out) : null;
    if (written?.normals) assertNormalsOfPositions(written, `terrain ${ext}`);
  }
});
