// Mistakes the package's types must turn into compile errors (tests/package/package.test.mjs
// compiles this file and expects exactly these errors, by line).
import { createGeoshift } from 'geoshift';
import { denoiseGeometry } from 'geoshift/three';
import { BufferGeometry } from 'three';

const gs = await createGeoshift();
const mesh = { positions: new Float32Array(9) };
await gs.denoise(mesh, { methd: 'taubin' }); // @error TS2561 an option name with a typo ("did you mean")
await gs.smooth(mesh, { iterations: 'ten' }); // @error TS2322 a number option given a string
await gs.geodesic(mesh, { sauce: 3 }); // @error TS2353 an unknown option
await gs.curvature(mesh, { kind: 'gaussian' }); // @error TS2322 not one of the choices
await gs.filter(mesh, { field: 'color', hr: 0.2, passes: 2, segmnts: true }); // @error TS2561 a typo among good options
await gs.denoise({ positions: [0, 0, 0] }); // @error TS2740 positions must be a Float32Array
await denoiseGeometry(gs, new BufferGeometry(), { strenght: 2 }); // @error TS2561 the three helpers' options too
await gs.run('denoise', mesh); // @error TS2339 no untyped run(op, ...) on the package's API
