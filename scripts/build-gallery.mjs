// Builds the gallery's meshes (web/public/gallery/) from the public data sets they come from, small
// enough to ship: positions quantized to 16 bits (KHR_mesh_quantization) unless a filter's
// parameters are in the file's own units, colors to 8 bits, the large terrain simplified with
// meshoptimizer, every buffer compressed (EXT_meshopt_compression). A noisy mesh and its clean
// original get the same vertex order, so they still match vertex for vertex.
//
//   node scripts/build-gallery.mjs DATA_DIR [GEOSHIFT_CLI]
//
// DATA_DIR holds the sources named in scripts/gallery-sources.mjs (gcn_denoiser, pdal_testdata);
// GEOSHIFT_CLI (default build/native-release/cli/geoshift) makes the noisy CAD part and turns the
// LiDAR points into a terrain mesh, as the core does for any user. Only data under licenses that
// allow shipping is used (web/public/gallery/LICENSE.md). tests/e2e/gallery-files.test.mjs checks
// the files against what the core makes from the same sources.
import { mkdirSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { Document, NodeIO } from '@gltf-transform/core';
import { EXTMeshoptCompression, KHRMeshQuantization } from '@gltf-transform/extensions';
import { MeshoptDecoder, MeshoptEncoder, MeshoptSimplifier } from 'meshoptimizer';
import { coreMesh, GALLERY_SOURCES } from './gallery-sources.mjs';

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
 * Unquantized, the positions stay floats and the buffers uncompressed (meshopt's float filters
 * would round them).
 */
async function writeMesh(name, { positions, indices, colors, scalars = {}, box = boxOf(positions), matrix, quantized = true }) {
  const doc = new Document();
  if (quantized) {
    doc.createExtension(KHRMeshQuantization).setRequired(true);
    doc.createExtension(EXTMeshoptCompression).setRequired(true).setEncoderOptions({ method: EXTMeshoptCompression.EncoderMethod.QUANTIZE });
  }
  const buffer = doc.createBuffer();
  const prim = doc.createPrimitive();
  const position = doc.createAccessor().setType('VEC3').setBuffer(buffer);
  prim.setAttribute('POSITION', quantized ? position.setArray(quantize(positions, box)).setNormalized(true) : position.setArray(Float32Array.from(positions)));
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
  const dequantize = quantized ? [s, 0, 0, 0, 0, s, 0, 0, 0, 0, s, 0, box.centre[0], box.centre[1], box.centre[2], 1] : null;
  const placement = matrix && dequantize ? multiply(matrix, dequantize) : (matrix ?? dequantize);
  const node = doc.createNode(name).setMesh(mesh);
  if (placement) node.setMatrix(placement);
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

/**
 * Keeps about `target` vertices of a terrain (two triangles per vertex): the simplifier keeps a
 * subset of the vertices, so attribute values (classes included) stay values that were measured.
 */
function simplified(mesh, target) {
  const vertexCount = mesh.positions.length / 3;
  if (vertexCount <= target) return mesh;
  const [kept] = MeshoptSimplifier.simplify(mesh.indices, mesh.positions, 3, Math.floor((2 * target * 3) / 3) * 3, 0.01, ['LockBorder']);
  const used = new Int32Array(vertexCount).fill(-1);
  let next = 0;
  for (const v of kept) if (used[v] < 0) used[v] = next++;
  const gather = (array, dim) => {
    if (!array) return array;
    const out = new Float32Array(next * dim);
    for (let v = 0; v < vertexCount; v++) if (used[v] >= 0) for (let k = 0; k < dim; k++) out[used[v] * dim + k] = array[v * dim + k];
    return out;
  };
  const scalars = Object.fromEntries(Object.entries(mesh.scalars).map(([k, v]) => [k, gather(v, 1)]));
  return { ...mesh, positions: gather(mesh.positions, 3), colors: gather(mesh.colors, 3), scalars, indices: kept.map((v) => used[v]) };
}

const meshes = new Map();
for (const entry of GALLERY_SOURCES) {
  const mesh = await coreMesh(entry, dataDir, cli, io);
  meshes.set(entry.file, entry.simplify ? simplified(mesh, entry.simplify) : mesh);
}
for (const entry of GALLERY_SOURCES) {
  const mesh = meshes.get(entry.file);
  const name = entry.file.replace(/\.glb$/, '');
  const quantized = entry.quantize !== false;
  const paired = GALLERY_SOURCES.find((e) => e.pairedWith === entry.file);
  if (entry.pairedWith || paired) {
    // A noisy mesh and its clean original: one grid and one vertex order for both, so that their
    // difference is the noise and nothing else.
    const noisy = meshes.get(entry.pairedWith ? entry.file : paired.file);
    const clean = meshes.get(entry.pairedWith ?? entry.file);
    if (noisy.positions.length !== clean.positions.length || noisy.indices.some((v, i) => v !== clean.indices[i])) {
      throw new Error(`${entry.file}: the noisy and the clean mesh do not share their vertices and faces`);
    }
    const order = reorder(noisy).order;
    await writeMesh(name, { ...reorder(mesh, order), box: boxOf(noisy.positions, clean.positions), quantized });
  } else {
    await writeMesh(name, { ...reorder(mesh), quantized });
  }
}
