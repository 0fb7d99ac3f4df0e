// Hashes what the CLI writes for every filter preset (and the other filters) on a few meshes, so
// that a change meant to leave results alone can be checked bit for bit: record the hashes with
// the old build, rebuild, and compare.
//
//   node scripts/output-hashes.mjs [--cli PATH] [--out FILE] [--compare FILE]
//
// --cli: the geoshift binary (default build/native-release/cli/geoshift). --out: write the
// "job sha256" lines to FILE. --compare: exit 1 naming every job whose hash differs from FILE's.
// Inputs are made by the same binary (procedural terrain, noise, curvature colors) from the sample
// dragon, so two builds that made different inputs differ already at the input jobs.
import { execFileSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = resolve(fileURLToPath(import.meta.url), '../..');
const args = process.argv.slice(2);
const option = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : undefined;
};
const cli = resolve(option('--cli') ?? join(root, 'build/native-release/cli/geoshift'));
const dir = mkdtempSync(join(tmpdir(), 'geoshift-hashes-'));
const at = (name) => join(dir, name);
const dragon = join(root, 'web/public/samples/ChineseDragon-10kv.off');

// Each job: a name, the CLI arguments, the file it writes. Earlier jobs make later jobs' inputs.
const jobs = [
  ['input: procedural terrain', ['terrain', '--procedural', '129', '--seed', '7', '-o', at('terrain.glb')], 'terrain.glb'],
  ['input: noisy dragon', ['noise', dragon, '-o', at('noisy.obj'), '--amount', '0.3', '--seed', '3'], 'noisy.obj'],
  ['input: colored dragon', ['curvature', dragon, '-o', at('colored.glb'), '--kind', 'mean'], 'colored.glb'],
  ['preset color', ['filter', at('colored.glb'), '-o', at('color.glb'), '--preset', 'color'], 'color.glb'],
  ['preset color, segments', ['filter', at('colored.glb'), '-o', at('seg.glb'), '--preset', 'color', '--hr', '0.2', '--segments'], 'seg.glb'],
  ['preset color, sampled, double weights', ['filter', at('colored.glb'), '-o', at('color-s.glb'), '--preset', 'color', '--range-update', 'sampled', '--double-weights'], 'color-s.glb'],
  ['preset color, exact charts', ['filter', at('colored.glb'), '-o', at('color-x.glb'), '--preset', 'color', '--exact-charts', '--kmax', '5'], 'color-x.glb'],
  ['preset curvature-ms', ['filter', dragon, '-o', at('cms.glb'), '--preset', 'curvature-ms'], 'cms.glb'],
  ['preset curvature-bms', ['filter', dragon, '-o', at('cbms.glb'), '--preset', 'curvature-bms'], 'cbms.glb'],
  ['preset terrain-ms', ['filter', at('terrain.glb'), '-o', at('tms.glb'), '--preset', 'terrain-ms', '--levels', '2'], 'tms.glb'],
  ['preset terrain-bms', ['filter', at('terrain.glb'), '-o', at('tbms.glb'), '--preset', 'terrain-bms', '--levels', '2'], 'tbms.glb'],
  ['terrain signal, direct', ['filter', at('terrain.glb'), '-o', at('tdirect.glb'), '--signal', 'terrain', '--mode', 'bms', '--passes', '2'], 'tdirect.glb'],
  ['normal signal', ['filter', at('noisy.obj'), '-o', at('normal.glb'), '--signal', 'normal', '--kmax', '10'], 'normal.glb'],
  ['two channels, threads 1', ['filter', at('terrain.glb'), '-o', at('two.glb'), '--signal', '_VEGETATION_HEIGHT,_CLASS', '--threads', '1', '--levels', '3'], 'two.glb'],
  ['filter geometry', ['filter', at('terrain.glb'), '-o', at('geo.glb'), '--preset', 'terrain-ms', '--levels', '2', '--filter-geometry', '--alpha', '0.5'], 'geo.glb'],
  ['denoise meanshift', ['denoise', at('noisy.obj'), '-o', at('dn.obj'), '--passes', '1'], 'dn.obj'],
  ['denoise bilateral', ['denoise', at('noisy.obj'), '-o', at('dnb.obj'), '--method', 'bilateral'], 'dnb.obj'],
  ['denoise paper', ['denoise', at('noisy.obj'), '-o', at('dnp.obj'), '--preset', 'paper', '--passes', '1', '--kmax', '10'], 'dnp.obj'],
  ['denoise hybrid', ['denoise', at('noisy.obj'), '-o', at('dnh.obj'), '--passes', '1', '--levels', '1', '--alpha', '0.5'], 'dnh.obj'],
  ['denoise taubin', ['denoise', at('noisy.obj'), '-o', at('dnt.obj'), '--method', 'taubin', '--taubin-iterations', '4'], 'dnt.obj'],
  ['smooth', ['smooth', at('noisy.obj'), '-o', at('smooth.obj'), '--iterations', '5', '--weights', 'cotangent'], 'smooth.obj'],
  ['geodesic', ['geodesic', dragon, '-o', at('geo-dist.glb'), '--source', '5'], 'geo-dist.glb'],
  ['wavelet', ['wavelet', at('terrain.glb'), '-o', at('wav.glb'), '--levels', '3', '--alpha', '0'], 'wav.glb'],
];

const lines = [];
try {
  for (const [name, argv, file] of jobs) {
    execFileSync(cli, argv, { stdio: ['ignore', 'ignore', 'pipe'] });
    const hash = createHash('sha256').update(readFileSync(at(file))).digest('hex');
    lines.push(`${name}\t${hash}`);
    console.log(`${hash.slice(0, 16)}  ${name}`);
  }
} finally {
  rmSync(dir, { recursive: true, force: true });
}

const out = option('--out');
if (out) writeFileSync(out, lines.join('\n') + '\n');
const compare = option('--compare');
if (compare) {
  const expected = new Map(readFileSync(compare, 'utf8').trim().split('\n').map((l) => l.split('\t')));
  const differing = lines.map((l) => l.split('\t')).filter(([name, hash]) => expected.get(name) !== hash);
  if (differing.length) {
    console.error(`differ from ${compare}: ${differing.map(([name]) => name).join('; ')}`);
    process.exit(1);
  }
  console.log(`all ${lines.length} outputs identical to ${compare}`);
}
