// A Node program written as a user of the package would write it, compiled against the packed
// declarations: reads an OFF file with the core's readers, denoises it with progress, checks the
// errors a user meets, filters the colors of another file, and prints what it got as JSON
// (tests/package/package.test.mjs).
import { readFileSync } from 'node:fs';
import { createGeoshift, GeoshiftError, type GeoshiftErrorKind, type MeshResult } from 'geoshift';

const [input, colored, threads] = process.argv.slice(2);
if (!input || !colored) throw new Error('usage: node denoise.js FILE.off COLORED.off [threads]');

async function kindOf(promise: Promise<unknown>): Promise<{ kind: GeoshiftErrorKind | 'none'; message: string }> {
  try {
    await promise;
    return { kind: 'none', message: '' };
  } catch (error) {
    if (!(error instanceof GeoshiftError)) throw error;
    return { kind: error.kind, message: error.message };
  }
}

const gs = await createGeoshift({ threads: threads === undefined ? 'auto' : Number(threads) });
try {
  const file = await gs.read(readFileSync(input), 'input.off');
  const mesh = file.parts[0]?.mesh;
  if (!mesh) throw new Error('the file has no mesh');
  const stages = new Set<string>();
  const result: MeshResult = await gs.denoise(mesh, { onProgress: (_fraction, stage) => stages.add(stage) });
  const taubin = await gs.denoise(mesh, { method: 'taubin', iterations: 4 });
  const wavelet = await gs.wavelet(mesh, { levels: 2, alpha: [0, 0.5] });

  // Cancel a long run after its first progress report; the next job still works.
  const controller = new AbortController();
  const cancelled = kindOf(gs.smooth(mesh, { iterations: 1000000, signal: controller.signal, onProgress: () => controller.abort() }));
  const cancel = await cancelled;
  const after = await gs.curvature(mesh);

  // Vertex colors (RGBA from the reader), filtered by the mean shift: RGB back.
  const sphere = (await gs.read(readFileSync(colored), 'colored.off')).parts[0]!.mesh!;
  const colors = await gs.filter(sphere, { field: 'color', hr: 0.15 });

  const badIndex = await kindOf(gs.denoise({ positions: mesh.positions, indices: new Uint32Array([0, 1, 100000]) }));
  const badOption = await kindOf(gs.smooth(mesh, JSON.parse('{ "iteratons": 3 }')));
  console.log(JSON.stringify({
    info: gs.info,
    positions: Array.from(result.positions),
    taubin: Array.from(taubin.positions),
    wavelet: Array.from(wavelet.positions),
    colors: Array.from(colors.colors ?? []),
    stages: [...stages],
    stats: result.stats,
    inputUnchanged: mesh.positions.every((v, i) => v === file.parts[0]!.mesh!.positions[i]),
    cancel,
    afterCancel: Object.keys(after.attributes),
    badIndex,
    badOption,
  }));
} finally {
  gs.terminate();
}
