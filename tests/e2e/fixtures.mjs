// Small meshes built in code, in every format the app opens. The tetrahedron is the smallest closed
// surface: 4 vertices, 4 triangles.

export const TETRA = {
  positions: [
    [1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1],
  ],
  // Outward-facing (counter-clockwise seen from outside).
  triangles: [
    [0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2],
  ],
};

/** Per-face colours that shaded (grey) rendering can never produce. */
const FACE_COLOURS = [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0]];

/**
 * A binary glTF of the tetrahedron with flat faces: 12 vertices (three per face) carrying
 * POSITION, NORMAL and COLOR_0, and 16-bit indices. Written by hand from the glTF 2.0 spec.
 */
export function tetraGlb({ extraJson = {} } = {}) {
  const positions = [], normals = [], colours = [];
  TETRA.triangles.forEach((tri, f) => {
    const [a, b, c] = tri.map((i) => TETRA.positions[i]);
    const u = b.map((v, k) => v - a[k]), w = c.map((v, k) => v - a[k]);
    const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
    const len = Math.hypot(...n);
    for (const p of [a, b, c]) {
      positions.push(...p);
      normals.push(...n.map((v) => v / len));
      colours.push(...FACE_COLOURS[f]);
    }
  });
  const indices = Array.from({ length: 12 }, (_, i) => i);
  const floats = (list) => Buffer.from(new Float32Array(list).buffer);
  const parts = [floats(positions), floats(normals), floats(colours), Buffer.from(new Uint16Array(indices).buffer)];
  const bufferViews = [];
  let offset = 0;
  for (const part of parts) {
    bufferViews.push({ buffer: 0, byteOffset: offset, byteLength: part.length });
    offset += part.length; // every part is a multiple of 4 bytes (12 x 2 bytes for indices)
  }
  const bin = Buffer.concat(parts);
  const json = {
    asset: { version: '2.0', generator: 'geoshift e2e fixtures' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1, COLOR_0: 2 }, indices: 3 }] }],
    accessors: [
      { bufferView: 0, componentType: 5126, count: 12, type: 'VEC3', min: [-1, -1, -1], max: [1, 1, 1] },
      { bufferView: 1, componentType: 5126, count: 12, type: 'VEC3' },
      { bufferView: 2, componentType: 5126, count: 12, type: 'VEC3' },
      { bufferView: 3, componentType: 5123, count: 12, type: 'SCALAR' },
    ],
    bufferViews,
    buffers: [{ byteLength: bin.length }],
    ...extraJson,
  };
  return glb(json, bin);
}

/** Packs JSON and a BIN chunk into a GLB container (chunks padded to 4 bytes). */
export function glb(json, bin) {
  const pad = (buffer, byte) => Buffer.concat([buffer, Buffer.alloc((4 - (buffer.length % 4)) % 4, byte)]);
  const jsonChunk = pad(Buffer.from(JSON.stringify(json)), 0x20);
  const binChunk = pad(bin, 0);
  const header = Buffer.alloc(12);
  header.writeUInt32LE(0x46546c67, 0);
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(12 + 8 + jsonChunk.length + 8 + binChunk.length, 8);
  const chunkHeader = (length, type) => {
    const h = Buffer.alloc(8);
    h.writeUInt32LE(length, 0);
    h.writeUInt32LE(type, 4);
    return h;
  };
  return Buffer.concat([
    header, chunkHeader(jsonChunk.length, 0x4e4f534a), jsonChunk, chunkHeader(binChunk.length, 0x004e4942), binChunk,
  ]);
}

export function tetraObj() {
  return [
    '# tetrahedron',
    ...TETRA.positions.map((p) => `v ${p.join(' ')}`),
    ...TETRA.triangles.map((t) => `f ${t.map((i) => i + 1).join(' ')}`),
  ].join('\n') + '\n';
}

/** ASCII STL: three separate corners per facet, as STL always stores them. */
export function tetraStl() {
  const lines = ['solid tetra'];
  for (const t of TETRA.triangles) {
    lines.push('  facet normal 0 0 0', '    outer loop');
    for (const i of t) lines.push(`      vertex ${TETRA.positions[i].join(' ')}`);
    lines.push('    endloop', '  endfacet');
  }
  lines.push('endsolid tetra');
  return lines.join('\n') + '\n';
}

export function tetraPly() {
  return [
    'ply', 'format ascii 1.0', 'comment tetrahedron',
    'element vertex 4', 'property float x', 'property float y', 'property float z',
    'property uchar red', 'property uchar green', 'property uchar blue',
    'element face 4', 'property list uchar int vertex_indices', 'end_header',
    ...TETRA.positions.map((p, i) => `${p.join(' ')} ${FACE_COLOURS[i].map((c) => c * 255).join(' ')}`),
    ...TETRA.triangles.map((t) => `3 ${t.join(' ')}`),
  ].join('\n') + '\n';
}

export function tetraCoff() {
  return [
    'COFF', '4 4 6',
    ...TETRA.positions.map((p, i) => `${p.join(' ')} ${FACE_COLOURS[i].map((c) => c * 255).join(' ')} 255`),
    ...TETRA.triangles.map((t) => `3 ${t.join(' ')}`),
  ].join('\n') + '\n';
}

/**
 * A torus as glTF exporters write it: an (n+1) × (m+1) grid of vertices whose last row and column
 * repeat the first (a UV seam), with normals and 32-bit indices. Returns { positions, normals,
 * indices } as plain arrays.
 */
export function torus(n = 48, m = 24, R = 1, r = 0.35) {
  const positions = [], normals = [], indices = [];
  for (let j = 0; j <= m; j++) {
    for (let i = 0; i <= n; i++) {
      const u = (2 * Math.PI * i) / n, v = (2 * Math.PI * j) / m;
      const c = [Math.cos(u) * Math.cos(v), Math.sin(u) * Math.cos(v), Math.sin(v)];
      positions.push(Math.cos(u) * (R + r * Math.cos(v)), Math.sin(u) * (R + r * Math.cos(v)), r * Math.sin(v));
      normals.push(...c);
    }
  }
  const at = (i, j) => j * (n + 1) + i;
  for (let j = 0; j < m; j++) {
    for (let i = 0; i < n; i++) indices.push(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1));
  }
  return { positions, normals, indices };
}

/**
 * A GLB scene of several meshes, each in its own node (with a translation, to check the scene
 * survives export): meshes = [{ positions, normals?, indices, scalars? }], plain arrays; scalars
 * maps custom attribute names (`_NAME`) to one number per vertex.
 */
export function sceneGlb(meshes) {
  const parts = [];
  const bufferViews = [];
  const accessors = [];
  let offset = 0;
  const add = (array, componentType, type, count, extra = {}) => {
    const bytes = Buffer.from(array.buffer);
    bufferViews.push({ buffer: 0, byteOffset: offset, byteLength: bytes.length });
    parts.push(bytes);
    offset += bytes.length;
    accessors.push({ bufferView: bufferViews.length - 1, componentType, count, type, ...extra });
    return accessors.length - 1;
  };
  const gltfMeshes = meshes.map((mesh) => {
    const p = new Float32Array(mesh.positions);
    const min = [0, 1, 2].map((k) => Math.min(...p.filter((_, i) => i % 3 === k)));
    const max = [0, 1, 2].map((k) => Math.max(...p.filter((_, i) => i % 3 === k)));
    const attributes = { POSITION: add(p, 5126, 'VEC3', p.length / 3, { min, max }) };
    if (mesh.normals) attributes.NORMAL = add(new Float32Array(mesh.normals), 5126, 'VEC3', p.length / 3);
    for (const [name, values] of Object.entries(mesh.scalars ?? {})) attributes[name] = add(new Float32Array(values), 5126, 'SCALAR', values.length);
    const indices = add(new Uint32Array(mesh.indices), 5125, 'SCALAR', mesh.indices.length);
    return { primitives: [{ attributes, indices }] };
  });
  const json = {
    asset: { version: '2.0', generator: 'geoshift e2e fixtures' },
    scene: 0,
    scenes: [{ nodes: meshes.map((_, i) => i) }],
    nodes: meshes.map((_, i) => ({ mesh: i, name: `part-${i}`, translation: [3 * i, 0, 0] })),
    meshes: gltfMeshes,
    accessors,
    bufferViews,
    buffers: [{ byteLength: offset }],
  };
  return glb(json, Buffer.concat(parts));
}

const COMPONENT_ARRAYS = { 5120: Int8Array, 5121: Uint8Array, 5122: Int16Array, 5123: Uint16Array, 5125: Uint32Array, 5126: Float32Array };
const TYPE_SIZES = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };

/** Reads a GLB: { json, accessor(index) -> typed array (count × components) }. */
export function parseGlb(buffer) {
  let json, bin;
  for (let at = 12; at < buffer.length;) {
    const length = buffer.readUInt32LE(at);
    const type = buffer.readUInt32LE(at + 4);
    const chunk = buffer.subarray(at + 8, at + 8 + length);
    if (type === 0x4e4f534a) json = JSON.parse(chunk.toString());
    else if (type === 0x004e4942) bin = chunk;
    at += 8 + length;
  }
  const accessor = (index) => {
    const a = json.accessors[index];
    const view = json.bufferViews[a.bufferView];
    const Typed = COMPONENT_ARRAYS[a.componentType];
    const size = TYPE_SIZES[a.type];
    const stride = view.byteStride ?? size * Typed.BYTES_PER_ELEMENT;
    const start = (view.byteOffset ?? 0) + (a.byteOffset ?? 0);
    const out = new Typed(a.count * size);
    for (let i = 0; i < a.count; i++) {
      const bytes = Uint8Array.from(bin.subarray(start + i * stride, start + i * stride + size * Typed.BYTES_PER_ELEMENT));
      out.set(new Typed(bytes.buffer), i * size);
    }
    return out;
  };
  return { json, accessor };
}

/**
 * A terrain as `geoshift terrain` writes it, Y-up: an n × n grid of hills with the attributes
 * _HEIGHT_ABOVE_GROUND (a quantity) and _CLASS (a category), counter-clockwise seen from above.
 */
export function terrain(n = 24) {
  const positions = [], indices = [], hag = [], cls = [];
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const x = i / (n - 1) * 10, z = j / (n - 1) * 10;
      positions.push(x, 0.6 * Math.sin(x) * Math.cos(z), z);
      hag.push(i > n / 2 ? 2 + Math.cos(i + j) : 0);
      cls.push(i > n / 2 ? 5 : 2);
    }
  }
  const at = (i, j) => j * n + i;
  // Seen from +Y (looking down -Y), x right and z down the screen: (i,j) -> (i,j+1) -> (i+1,j) is
  // counter-clockwise.
  for (let j = 0; j + 1 < n; j++) {
    for (let i = 0; i + 1 < n; i++) indices.push(at(i, j), at(i, j + 1), at(i + 1, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
  }
  return sceneGlb([{ positions, indices, scalars: { _HEIGHT_ABOVE_GROUND: hag, _CLASS: cls } }]);
}

/** A square pyramid standing on its base in the z = 0 plane, apex up along +Z, as OFF text. */
export function pyramidZUpOff() {
  return 'OFF\n5 6 0\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n0 0 2.5\n' +
    // Base seen from below (outward normal -Z), then the four sides.
    '3 0 2 1\n3 0 3 2\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n';
}
