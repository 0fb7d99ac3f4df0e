// Builds the gallery's meshes (web/public/gallery/) from the public data sets they come from, small
// enough to ship: positions quantized to 16 bits (KHR_mesh_quantization), colors to 8 bits, the
// large terrain simplified with meshoptimizer, every buffer compressed (EXT_meshopt_compression).
// Vertex order is kept, so a noisy mesh and its clean original still match vertex for vertex.
//
//   node scripts/build-gallery.mjs DATA_DIR [GEOSHIFT_CLI]
//
// DATA_DIR holds the sources named in web/public/gallery/LICENSE.md (gcn_denoiser, pdal_testdata,
// cgal_debian_libcgal_demo); GEOSHIFT_CLI (default build/native-release/cli/geoshift) turns the
// LiDAR point sets into terrain meshes. Only data under licenses that allow shipping is used.
import { execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Document, NodeIO } from '@gltf-transform/core';
import { EXTMeshoptCompression, KHRMeshQuantization } from '@gltf-transform/extensions';
import { MeshoptDecoder, MeshoptEncoder, MeshoptSimplifier } from 'meshoptimizer';

const [dataDir, cli = fileURLToPath(new URL('../build/native-release/cli/geoshift', import.meta.url))] = process.argv.slice(2);
if (!dataDir) {
  console.error('usage: node scripts/build-gallery.mjs DATA_DIR [GEOSHIFT_CLI]');
  process.exit(2);
}
const outDir = fileURLToPath(new URL('../web/public/gallery/', import.meta.url));
mkdirSync(outDir, { recursive: true });

await Promise.all([MeshoptEncoder.ready, MeshoptDecoder.ready, MeshoptSimplifier.ready]);
const io = new NodeIO()
  .registerExtensions([EXTMeshoptCompression, KHRMeshQuantization])
  .registerDependencies({ 'meshopt.encoder': MeshoptEncoder, 'meshopt.decoder': MeshoptDecoder });

/** Positions and triangles of an OBJ (v and f lines; polygons fanned). */
function readObj(path) {
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
  return { positions: Float32Array.from(positions), indices: Uint32Array.from(indices) };
}

/** The box the quantization grid spans: centre and half of its largest side (uniform scale). */
function boxOf(...arrays) {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (const p of arrays) {
    for (let i = 0; i < p.length; i++) {
      min[i % 3] = Math.min(min[i % 3], p[i]);
      max[i % 3] = Math.max(max[i % 3], p[i]);
    }
  }
  const centre = min.map((v, k) => (v + max[k]) / 2);
  const half = Math.max(...min.map((v, k) => max[k] - v)) / 2 || 1;
  return { centre, half };
}

function quantize(positions, { centre, half }) {
  const q = new Int16Array(positions.length);
  for (let i = 0; i < positions.length; i++) q[i] = Math.round(((positions[i] - centre[i % 3]) / half) * 32767);
  return q;
}

/**
 * One mesh in one node. `matrix` (column-major 4×4) places the mesh's own coordinates, before the
 * quantization's translation and scale; `scalars` are one-number attributes written as `_NAME`.
 */
async function writeMesh(name, { positions, indices, colors, scalars = {}, box = boxOf(positions), matrix }) {
  const doc = new Document();
  doc.createExtension(KHRMeshQuantization).setRequired(true);
  doc.createExtension(EXTMeshoptCompression).setRequired(true).setEncoderOptions({ method: EXTMeshoptCompression.EncoderMethod.QUANTIZE });
  const buffer = doc.createBuffer();
  const prim = doc.createPrimitive();
  prim.setAttribute('POSITION', doc.createAccessor().setType('VEC3').setArray(quantize(positions, box)).setNormalized(true).setBuffer(buffer));
  const vertexCount = positions.length / 3;
  prim.setIndices(doc.createAccessor().setType('SCALAR').setArray(vertexCount < 65536 ? Uint16Array.from(indices) : Uint32Array.from(indices)).setBuffer(buffer));
  if (colors) {
    const c8 = Uint8Array.from(colors, (v) => Math.round(Math.min(1, Math.max(0, v)) * 255));
    prim.setAttribute('COLOR_0', doc.createAccessor().setType('VEC3').setArray(c8).setNormalized(true).setBuffer(buffer));
  }
  for (const [key, values] of Object.entries(scalars)) prim.setAttribute(key, doc.createAccessor().setType('SCALAR').setArray(Float32Array.from(values)).setBuffer(buffer));
  const mesh = doc.createMesh(name).addPrimitive(prim);
  // The dequantization (translation + uniform scale) comes after the file's own placement.
  const s = box.half;
  const dequantize = [s, 0, 0, 0, 0, s, 0, 0, 0, 0, s, 0, box.centre[0], box.centre[1], box.centre[2], 1];
  const node = doc.createNode(name).setMesh(mesh).setMatrix(matrix ? multiply(matrix, dequantize) : dequantize);
  doc.createScene().addChild(node);
  doc.getRoot().getAsset().generator = 'geoshift scripts/build-gallery.mjs';
  const path = join(outDir, `${name}.glb`);
  await io.write(path, doc);
  console.log(`${name}.glb: ${vertexCount} vertices, ${indices.length / 3} triangles, ${(statSync(path).size / 1024).toFixed(0)} KiB`);
}

function multiply(a, b) {
  const out = new Array(16).fill(0);
  for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) for (let k = 0; k < 4; k++) out[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
  return out;
}

/**
 * The first `dim` components of every element of an accessor, as floats (normalized integers
 * decoded): the vertex layout of the attribute whatever its type (VEC3 or VEC4, float or not).
 */
function rowsOf(accessor, dim) {
  const out = new Float32Array(accessor.getCount() * dim);
  const element = [];
  for (let v = 0; v < accessor.getCount(); v++) {
    accessor.getElement(v, element);
    if (element.length < dim) throw new Error(`an attribute has ${element.length} components, ${dim} are needed`);
    for (let k = 0; k < dim; k++) out[v * dim + k] = element[k];
  }
  return out;
}

/** A terrain from `geoshift terrain`, optionally simplified to about `targetVertices`. */
async function terrainFromCli(input, extraArgs, targetVertices) {
  const tmp = mkdtempSync(join(tmpdir(), 'geoshift-gallery-'));
  const glb = join(tmp, 'terrain.glb');
  execFileSync(cli, ['terrain', input, '-o', glb, ...extraArgs], { stdio: ['ignore', 'ignore', 'inherit'] });
  const doc = await io.read(glb);
  const node = doc.getRoot().listNodes().find((n) => n.getMesh());
  const prim = node.getMesh().listPrimitives()[0];
  let positions = rowsOf(prim.getAttribute('POSITION'), 3);
  let indices = Uint32Array.from(prim.getIndices().getArray());
  // The CLI writes COLOR_0 as RGBA: taking its flat array as RGB rows shifted every color onto
  // another vertex (issue 30). Rows of the first three components keep them on their own vertex.
  let colors = prim.getAttribute('COLOR_0') && rowsOf(prim.getAttribute('COLOR_0'), 3);
  const scalars = {};
  for (const key of prim.listSemantics()) if (key.startsWith('_')) scalars[key] = rowsOf(prim.getAttribute(key), 1);
  const vertexCount = positions.length / 3;
  if (targetVertices && vertexCount > targetVertices) {
    // About two triangles per vertex on a terrain; the simplifier keeps a subset of the vertices,
    // so attribute values (classes included) stay values that were measured.
    const [simplified] = MeshoptSimplifier.simplify(indices, positions, 3, Math.floor((2 * targetVertices * 3) / 3) * 3, 0.01, ['LockBorder']);
    const used = new Int32Array(vertexCount).fill(-1);
    let next = 0;
    for (const v of simplified) if (used[v] < 0) used[v] = next++;
    const gather = (array, dim) => {
      const out = new Float32Array(next * dim);
      for (let v = 0; v < vertexCount; v++) if (used[v] >= 0) for (let k = 0; k < dim; k++) out[used[v] * dim + k] = array[v * dim + k];
      return out;
    };
    positions = gather(positions, 3);
    if (colors) colors = gather(colors, 3);
    for (const key of Object.keys(scalars)) scalars[key] = gather(scalars[key], 1);
    indices = simplified.map((v) => used[v]);
  }
  return { positions, indices, colors, scalars, matrix: node.getMatrix() };
}

/**
 * Orders triangles for the vertex cache and vertices by first use, which is what makes meshopt's
 * codecs compress well; unused vertices are dropped. `order` from an earlier call applies the same
 * permutation to another mesh with the same faces (the clean mesh of a noisy one).
 */
function reorder(mesh, order = null) {
  let indices, remap, unique;
  if (order) ({ indices, remap, unique } = order);
  else {
    indices = Uint32Array.from(mesh.indices);
    [remap, unique] = MeshoptEncoder.reorderMesh(indices, true, true);
  }
  const move = (array, dim) => {
    if (!array) return array;
    const out = new Float32Array(unique * dim);
    for (let v = 0; v < remap.length; v++) if (remap[v] !== 0xffffffff) for (let k = 0; k < dim; k++) out[remap[v] * dim + k] = array[v * dim + k];
    return out;
  };
  const scalars = Object.fromEntries(Object.entries(mesh.scalars ?? {}).map(([k, v]) => [k, move(v, 1)]));
  return { ...mesh, positions: move(mesh.positions, 3), colors: move(mesh.colors, 3), scalars, indices, order: { indices, remap, unique } };
}

const gcn = join(dataDir, 'gcn_denoiser/models');

// Noisy scan with its clean original (Fertility, Gaussian noise): one grid for both, so that
// their difference is the noise and nothing else.
const noisy = readObj(join(gcn, 'fertility_gaus_n3.obj'));
const clean = readObj(join(gcn, 'fertility.obj'));
if (noisy.positions.length !== clean.positions.length || noisy.indices.some((v, i) => v !== clean.indices[i])) {
  throw new Error('fertility: the noisy and the clean mesh do not share their vertices and faces');
}
const pairBox = boxOf(noisy.positions, clean.positions);
const noisyOrdered = reorder(noisy);
await writeMesh('fertility-noisy', { ...noisyOrdered, box: pairBox });
await writeMesh('fertility-clean', { ...reorder(clean, noisyOrdered.order), box: pairBox });

// CAD part (Fandisk, clean).
await writeMesh('fandisk', reorder(readObj(join(gcn, 'fandisk.obj'))));

// Colored mesh: CGAL's b9 urban LiDAR scene (ground is label 0 there).
await writeMesh('b9-colors', reorder(await terrainFromCli(join(dataDir, 'cgal_debian_libcgal_demo/data/points_3/b9_training.ply'), ['--ground-class', '0'])));

// Terrain with height above ground and classes: PDAL's Autzen sample, simplified.
await writeMesh('autzen-terrain', reorder(await terrainFromCli(join(dataDir, 'pdal_testdata/las/autzen_trim.las'), [], 30000)));
