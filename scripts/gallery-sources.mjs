// Where each gallery file (web/public/gallery) comes from, and how the core makes its mesh from the
// source: scripts/build-gallery.mjs builds the files from it, tests/e2e/gallery-files.test.mjs
// checks that the files still hold, vertex for vertex, what the core makes.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

/**
 * file: the gallery file; source: under the shared data folder; how: 'obj' (read as it is),
 * 'noise' (the CLI's `noise` on it with `args`) or 'terrain' (the CLI's `terrain` with `args`);
 * simplify: most vertices kept (the simplifier keeps a subset of the vertices, their values as
 * measured); quantize: positions as 16-bit integers (false: floats, where a filter's parameters are
 * in the file's own units, as curvature's h_r in 1 / length).
 */
export const GALLERY_SOURCES = [
  { file: 'fertility-noisy.glb', source: 'gcn_denoiser/models/fertility_gaus_n3.obj', how: 'obj', pairedWith: 'fertility-clean.glb' },
  { file: 'fertility-clean.glb', source: 'gcn_denoiser/models/fertility.obj', how: 'obj' },
  // A CAD part with scanner-like noise: its raw curvature is speckled, the filtered one is not.
  { file: 'fandisk-noisy.glb', source: 'gcn_denoiser/models/fandisk.obj', how: 'noise', args: ['--amount', '0.1', '--dist', 'gaussian', '--seed', '3'], quantize: false },
  // Autzen's LiDAR points with their aerial-photo RGB, height above ground and class.
  { file: 'autzen-terrain.glb', source: 'pdal_testdata/las/autzen_trim.las', how: 'terrain', args: [], simplify: 40000 },
];

/**
 * The mesh the core makes from a source, as flat arrays: { positions, matrix (null: the positions
 * are the source's own), indices, colors?, scalars: { _NAME: Float32Array } }. `cli` is the
 * geoshift binary, `io` a gltf-transform NodeIO.
 */
export async function coreMesh(entry, dataDir, cli, io) {
  const input = join(dataDir, entry.source);
  if (entry.how === 'obj') return readObj(input);
  const tmp = mkdtempSync(join(tmpdir(), 'geoshift-gallery-'));
  try {
    if (entry.how === 'noise') {
      const out = join(tmp, 'noisy.obj');
      execFileSync(cli, ['noise', input, '-o', out, ...entry.args], { stdio: ['ignore', 'ignore', 'inherit'] });
      return readObj(out);
    }
    const glb = join(tmp, 'terrain.glb');
    execFileSync(cli, ['terrain', input, '-o', glb, ...entry.args], { stdio: ['ignore', 'ignore', 'inherit'] });
    return await readGlbMesh(io, glb);
  } finally {
    rmSync(tmp, { recursive: true, force: true });
  }
}

/** Positions and triangles of an OBJ (v and f lines; polygons fanned). */
export function readObj(path) {
  const positions = [];
  const indices = [];
  for (const line of readFileSync(path, 'utf8').split('\n')) {
    const t = line.trim().split(/\s+/);
    if (t[0] === 'v') positions.push(+t[1], +t[2], +t[3]);
    else if (t[0] === 'f') {
      const v = t.slice(1).map((s) => parseInt(s.split('/')[0], 10) - 1);
      for (let k = 1; k + 1 < v.length; k++) indices.push(v[0], v[k], v[k + 1]);
    }
  }
  return { positions: Float32Array.from(positions), matrix: null, indices: Uint32Array.from(indices), scalars: {} };
}

/**
 * The first `dim` components of every element of an accessor, as floats (normalized integers
 * decoded): the vertex layout of the attribute whatever its type (VEC3 or VEC4, float or not).
 */
export function rowsOf(accessor, dim) {
  const out = new Float32Array(accessor.getCount() * dim);
  const element = [];
  for (let v = 0; v < accessor.getCount(); v++) {
    accessor.getElement(v, element);
    if (element.length < dim) throw new Error(`an attribute has ${element.length} components, ${dim} are needed`);
    for (let k = 0; k < dim; k++) out[v * dim + k] = element[k];
  }
  return out;
}

/**
 * The one mesh of a glTF file: positions in the mesh's own coordinates and `matrix`, its node's
 * placement (column-major 4 × 4; the CLI's terrain moves its origin there), indices, COLOR_0 as RGB
 * rows (the CLI writes RGBA) and the `_` scalars.
 */
export async function readGlbMesh(io, path) {
  const doc = await io.read(path);
  const node = doc.getRoot().listNodes().find((n) => n.getMesh());
  const prim = node.getMesh().listPrimitives()[0];
  const scalars = {};
  for (const key of prim.listSemantics()) if (key.startsWith('_')) scalars[key] = rowsOf(prim.getAttribute(key), 1);
  return {
    positions: rowsOf(prim.getAttribute('POSITION'), 3),
    matrix: node.getWorldMatrix(),
    indices: Uint32Array.from(prim.getIndices().getArray()),
    colors: prim.getAttribute('COLOR_0') ? rowsOf(prim.getAttribute('COLOR_0'), 3) : undefined,
    scalars,
  };
}

/** Positions placed by a column-major 4 × 4 matrix (null: as they are), in double precision. */
export function placed(positions, matrix) {
  const out = Float64Array.from(positions);
  if (!matrix) return out;
  for (let i = 0; i < out.length; i += 3) {
    const [x, y, z] = [out[i], out[i + 1], out[i + 2]];
    for (let r = 0; r < 3; r++) out[i + r] = matrix[r] * x + matrix[4 + r] * y + matrix[8 + r] * z + matrix[12 + r];
  }
  return out;
}
