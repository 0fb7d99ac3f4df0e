// Writes the catalogue of damaged and awkward mesh files, tests/data/damaged/, from the cases
// below: each file's bytes are built here (by hand, from the format specs), and the message every
// front end must give for it is in tests/data/damaged/manifest.json, written by hand.
//
//   node scripts/make-damaged.mjs            rewrite the files (they are committed; tiny)
//   node scripts/make-damaged.mjs --check    exit 1 when a committed file differs from this script
//
// The catalogue runs through the CLI and the wasm module (tests/wasm/damaged.test.mjs) and the
// page (tests/e2e/damaged.test.mjs); docs/io.md#the-damaged-catalogue.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const dir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../tests/data/damaged');

// --- building blocks ---------------------------------------------------------------------------

const TRIANGLE = [0, 0, 0, 1, 0, 0, 0, 1, 0];
const f32 = (values) => Buffer.from(new Float32Array(values).buffer);
const u16 = (values) => Buffer.from(new Uint16Array(values).buffer);
const u32 = (values) => Buffer.from(new Uint32Array(values).buffer);

/** A GLB container around `json` and `bin` (chunks padded to 4 bytes), as the glTF 2.0 spec lays it out. */
function glb(json, bin = Buffer.alloc(0), { version = 2, emptyBin = false } = {}) {
  const pad = (buffer, byte) => Buffer.concat([buffer, Buffer.alloc((4 - (buffer.length % 4)) % 4, byte)]);
  const jsonChunk = pad(Buffer.from(typeof json === 'string' ? json : JSON.stringify(json)), 0x20);
  const binChunk = pad(bin, 0);
  const chunk = (data, type) => {
    const h = Buffer.alloc(8);
    h.writeUInt32LE(data.length, 0);
    h.writeUInt32LE(type, 4);
    return Buffer.concat([h, data]);
  };
  const body = Buffer.concat([chunk(jsonChunk, 0x4e4f534a), bin.length || emptyBin ? chunk(binChunk, 0x004e4942) : Buffer.alloc(0)]);
  const header = Buffer.alloc(12);
  header.writeUInt32LE(0x46546c67, 0);
  header.writeUInt32LE(version, 4);
  header.writeUInt32LE(12 + body.length, 8);
  return Buffer.concat([header, body]);
}

/**
 * One triangle as a GLB: POSITION (view 0) and uint16 indices (view 1). `edit(json)` damages the
 * JSON; `positions` and `indices` replace the data.
 */
function triangleGlb({ positions = TRIANGLE, indices = [0, 1, 2], edit = () => undefined } = {}) {
  const pos = f32(positions);
  const idx = u16(indices.length % 2 ? [...indices, 0] : indices); // views start on 4-byte boundaries
  const bin = Buffer.concat([pos, idx]);
  const json = {
    asset: { version: '2.0', generator: 'geoshift scripts/make-damaged.mjs' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ name: 'Tri', primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: positions.length / 3, type: 'VEC3' },
      { bufferView: 1, componentType: 5123, count: indices.length, type: 'SCALAR' },
    ],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: pos.length },
      { buffer: 0, byteOffset: pos.length, byteLength: indices.length * 2 },
    ],
    buffers: [{ byteLength: bin.length }],
  };
  edit(json);
  return glb(json, bin);
}

/** The same triangle as a .gltf with its buffer embedded as a data: URI. */
function triangleGltf(edit = () => undefined) {
  const bin = Buffer.concat([f32(TRIANGLE), u16([0, 1, 2, 0])]);
  const json = {
    asset: { version: '2.0' },
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: 3, type: 'VEC3' },
      { bufferView: 1, componentType: 5123, count: 3, type: 'SCALAR' },
    ],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: 36 },
      { buffer: 0, byteOffset: 36, byteLength: 6 },
    ],
    buffers: [{ byteLength: bin.length, uri: `data:application/octet-stream;base64,${bin.toString('base64')}` }],
  };
  edit(json);
  return JSON.stringify(json, null, 1);
}

const plyHeader = (format, vertices, faces, { vertexType = 'float', indexType = 'int' } = {}) =>
  [
    'ply', `format ${format} 1.0`, 'comment geoshift scripts/make-damaged.mjs',
    `element vertex ${vertices}`, `property ${vertexType} x`, `property ${vertexType} y`, `property ${vertexType} z`,
    `element face ${faces}`, `property list uchar ${indexType} vertex_indices`, 'end_header',
  ].join('\n') + '\n';

/** A binary PLY of one triangle; `bigEndianData` writes the numbers big endian whatever the header says. */
function binaryPly(format, { bigEndianData = format === 'binary_big_endian', vertices = 3, faces = 1 } = {}) {
  const data = Buffer.alloc(9 * 4 + 1 + 3 * 4);
  TRIANGLE.forEach((v, i) => (bigEndianData ? data.writeFloatBE(v, 4 * i) : data.writeFloatLE(v, 4 * i)));
  data.writeUInt8(3, 36);
  [0, 1, 2].forEach((v, i) => (bigEndianData ? data.writeInt32BE(v, 37 + 4 * i) : data.writeInt32LE(v, 37 + 4 * i)));
  return Buffer.concat([Buffer.from(plyHeader(format, vertices, faces)), data]);
}

/** A binary STL: 80-byte header, count, 50 bytes per triangle (normal, 3 corners, attribute word). */
function binaryStl(triangles, { declared = triangles.length } = {}) {
  const b = Buffer.alloc(84 + 50 * triangles.length);
  b.write('geoshift scripts/make-damaged.mjs', 0);
  b.writeUInt32LE(declared, 80);
  triangles.forEach((t, f) => t.forEach((v, k) => b.writeFloatLE(v, 84 + 50 * f + 12 + 4 * k)));
  return b;
}

const asciiStl = (body) => `solid damaged\n${body}endsolid damaged\n`;
const facet = (a, b, c) =>
  ` facet normal 0 0 1\n  outer loop\n   vertex ${a}\n   vertex ${b}\n   vertex ${c}\n  endloop\n endfacet\n`;

// --- the catalogue -------------------------------------------------------------------------------
// File name -> bytes. What each must produce is in manifest.json.

const files = {
  // glTF / GLB: the container
  'empty.glb': Buffer.alloc(0),
  'not-a-glb.glb': Buffer.from('this is not a binary glTF file at all\n'),
  'glb-version-1.glb': triangleGlb().fill(1, 4, 5),
  'glb-truncated.glb': triangleGlb().subarray(0, triangleGlb().length - 20),
  'glb-empty-bin-chunk.glb': glb({ asset: { version: '2.0' } }, Buffer.alloc(0), { emptyBin: true }),
  'glb-malformed-json.glb': glb('{"asset": {"version": "2.0"}, "meshes": [', Buffer.alloc(4)),
  // glTF / GLB: objects and the references between them
  'glb-accessor-count-beyond-view.glb': triangleGlb({ edit: (j) => (j.accessors[0].count = 300) }),
  'glb-index-count-beyond-view.glb': triangleGlb({ edit: (j) => (j.accessors[1].count = 3000) }),
  'glb-view-outside-buffer.glb': triangleGlb({ edit: (j) => (j.bufferViews[0].byteOffset = 4096) }),
  'glb-stride-too-short.glb': triangleGlb({ edit: (j) => (j.bufferViews[0].byteStride = 8) }),
  'glb-negative-indices.glb': triangleGlb({ edit: (j) => (j.meshes[0].primitives[0].indices = -2) }),
  'glb-primitives-not-array.glb': triangleGlb({ edit: (j) => (j.meshes[0].primitives = 1) }),
  'glb-missing-accessor.glb': triangleGlb({ edit: (j) => (j.meshes[0].primitives[0].attributes.POSITION = 7) }),
  'glb-signed-indices.glb': triangleGlb({ edit: (j) => (j.accessors[1].componentType = 5122) }),
  'glb-index-past-last-vertex.glb': triangleGlb({ indices: [0, 1, 7] }),
  'glb-nan-position.glb': triangleGlb({ positions: [0, 0, 0, 1, 0, 0, 0, NaN, 0] }),
  'glb-huge-declared-count.glb': triangleGlb({
    edit: (j) => {
      // Legal: an accessor without a buffer view reads as zeros. 400 million vertices of zeros.
      j.accessors[0] = { componentType: 5126, count: 400_000_000, type: 'VEC3' };
      delete j.meshes[0].primitives[0].indices;
    },
  }),
  'glb-degenerate-only.glb': triangleGlb({ positions: [0, 0, 0, 1, 1, 1, 2, 2, 2] }),
  'gltf-points-only.gltf': triangleGltf((j) => (j.meshes[0].primitives[0].mode = 0)),
  'gltf-missing-bin.gltf': triangleGltf((j) => (j.buffers[0].uri = 'triangle.bin')),
  'gltf-not-json.gltf': 'solid this is an STL\n',
  // OBJ
  'empty.obj': '',
  'obj-face-past-last-vertex.obj': 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n',
  'obj-relative-index-before-start.obj': 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n',
  'obj-zero-index.obj': 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n',
  'obj-normal-past-last.obj': 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 1\nf 1//1 2//2 3//8\n',
  'obj-nan-vertex.obj': 'v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n',
  'obj-not-a-number.obj': 'v 0 0 0\nv 1 0x 0\nv 0 1 0\nf 1 2 3\n',
  'obj-two-coordinates.obj': 'v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n',
  'obj-vertices-only.obj': 'v 0 0 0\nv 1 0 0\nv 0 1 0\n',
  'obj-is-a-glb.obj': triangleGlb(),
  'obj-binary.obj': Buffer.from([0x7f, 0x45, 0x4c, 0x46, 2, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0]),
  // OFF
  'empty.off': '',
  'off-face-past-last-vertex.off': 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n',
  'off-negative-index.off': 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n',
  'off-fewer-vertices-than-declared.off': 'OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n',
  'off-huge-declared-count.off': 'OFF\n2000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n',
  'off-nan-coordinate.off': 'OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n',
  // PLY
  'empty.ply': '',
  'ply-index-out-of-range.ply': `${plyHeader('ascii', 3, 1)}0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n`,
  'ply-negative-index.ply': `${plyHeader('ascii', 3, 1)}0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n`,
  'ply-nan-coordinate.ply': `${plyHeader('ascii', 3, 1)}0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n`,
  'ply-binary-truncated.ply': binaryPly('binary_little_endian').subarray(0, -6),
  'ply-huge-declared-count.ply': Buffer.concat([
    Buffer.from(plyHeader('binary_little_endian', 4_000_000_000_000, 1)), binaryPly('binary_little_endian').subarray(-49),
  ]),
  'ply-unknown-format.ply': binaryPly('binary_middle_endian', { bigEndianData: false }),
  'ply-big-endian-data-little-header.ply': binaryPly('binary_little_endian', { bigEndianData: true }),
  'ply-points-only.ply': `${plyHeader('ascii', 3, 0)}0 0 0\n1 0 0\n0 1 0\n`,
  // STL
  'empty.stl': '',
  'stl-count-disagrees-with-size.stl': binaryStl([[0, 0, 0, 1, 0, 0, 0, 1, 0]], { declared: 5 }),
  'stl-nan-coordinate.stl': binaryStl([[0, 0, 0, 1, 0, 0, 0, NaN, 0]]),
  'stl-ascii-missing-vertex.stl': asciiStl(' facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n  endloop\n endfacet\n'),
  'stl-ascii-truncated.stl': asciiStl(facet('0 0 0', '1 0 0', '0 1 0')).slice(0, 60),
  'stl-is-a-ply.stl': `${plyHeader('ascii', 3, 1)}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n`,
  // other
  'model.fbx': 'Kaydara FBX Binary  \0',
  // awkward but readable: opened everywhere with the counts in the manifest
  'obj-non-manifold-fin.obj': 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n',
  'ply-big-endian.ply': binaryPly('binary_big_endian'),
  'stl-ascii-two-solids.stl': asciiStl(facet('0 0 0', '1 0 0', '0 1 0')) + asciiStl(facet('1 0 0', '1 1 0', '0 1 0')),
};

const check = process.argv.includes('--check');
fs.mkdirSync(dir, { recursive: true });
let differ = 0;
for (const [name, contents] of Object.entries(files)) {
  const bytes = Buffer.isBuffer(contents) ? contents : Buffer.from(contents);
  const file = path.join(dir, name);
  if (check) {
    if (!fs.existsSync(file) || !fs.readFileSync(file).equals(bytes)) {
      console.error(`${name}: differs from scripts/make-damaged.mjs`);
      differ++;
    }
  } else {
    fs.writeFileSync(file, bytes);
  }
}
if (check) process.exit(differ ? 1 : 0);
console.log(`wrote ${Object.keys(files).length} files to ${path.relative(process.cwd(), dir)}`);
