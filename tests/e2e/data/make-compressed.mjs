// Writes torus-draco.glb and torus-meshopt.glb: the procedural torus of tests/e2e/fixtures.mjs
// compressed with glTF-Transform. Not part of the test run (the packages are not dependencies of
// the project); to regenerate, in an empty folder:
//   npm install @gltf-transform/core @gltf-transform/extensions @gltf-transform/functions draco3dgltf meshoptimizer
//   node /path/to/tests/e2e/data/make-compressed.mjs /path/to/tests/e2e/data
import { Document, NodeIO } from '@gltf-transform/core';
import { ALL_EXTENSIONS } from '@gltf-transform/extensions';
import { draco, meshopt } from '@gltf-transform/functions';
import draco3d from 'draco3dgltf';
import { MeshoptEncoder, MeshoptDecoder } from 'meshoptimizer';
import fs from 'node:fs';
import { torus } from '../fixtures.mjs';

const out = process.argv[2];
function doc() {
  const t = torus(48, 24);
  const d = new Document();
  const buffer = d.createBuffer();
  const prim = d.createPrimitive()
    .setAttribute('POSITION', d.createAccessor().setType('VEC3').setArray(new Float32Array(t.positions)).setBuffer(buffer))
    .setAttribute('NORMAL', d.createAccessor().setType('VEC3').setArray(new Float32Array(t.normals)).setBuffer(buffer))
    .setIndices(d.createAccessor().setType('SCALAR').setArray(new Uint32Array(t.indices)).setBuffer(buffer));
  const mesh = d.createMesh('torus').addPrimitive(prim);
  d.createScene().addChild(d.createNode('torus').setMesh(mesh));
  return d;
}
const io = new NodeIO().registerExtensions(ALL_EXTENSIONS).registerDependencies({
  'draco3d.encoder': await draco3d.createEncoderModule(),
  'draco3d.decoder': await draco3d.createDecoderModule(),
  'meshopt.encoder': MeshoptEncoder,
  'meshopt.decoder': MeshoptDecoder,
});
await MeshoptEncoder.ready;
const a = doc();
await a.transform(draco({ method: 'edgebreaker' }));
fs.writeFileSync(`${out}/torus-draco.glb`, await io.writeBinary(a));
const b = doc();
await b.transform(meshopt({ encoder: MeshoptEncoder, level: 'medium' }));
fs.writeFileSync(`${out}/torus-meshopt.glb`, await io.writeBinary(b));
