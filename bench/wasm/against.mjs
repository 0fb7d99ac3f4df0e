// This checkout's denoise benchmark against another commit's, in turns within the same hour: the
// way to compare speed with a bar measured on another day, on machines whose speed drifts by 20%
// within an hour (docs/denoising.md#speed-and-memory, "Against the bar's own build").
//
//   node bench/wasm/against.mjs [COMMIT] [--rounds R] [--vertices N] [--preset default|paper]
//
// COMMIT defaults to 2fe82f8, where the denoise budget of issue 27 was measured (8.56 s native on
// one thread, 6.38 s in Chromium with two). Its sources are exported (git archive) to
// build/against-<sha>/src and its native CLI and threaded web wasm built there once; this
// checkout's builds are used as they are (scripts/bootstrap.sh makes them). Each round runs
// bench/wasm/denoise.mjs (medians of 3 runs) for the two builds one after the other, the order
// alternating from round to round; the table gives every round's figure and the ratio of the
// medians over the rounds.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import { median } from '../../tests/wasm/support.mjs';

const root = path.resolve(import.meta.dirname, '../..');
const argv = process.argv.slice(2);
const option = (name, fallback) => {
  const i = argv.indexOf(name);
  if (i < 0) return fallback;
  const value = argv[i + 1];
  argv.splice(i, 2);
  if (value === undefined) throw new Error(`${name} needs a value`);
  return value;
};
const rounds = Number(option('--rounds', '3'));
const vertices = Number(option('--vertices', '144000'));
const preset = option('--preset', 'default');
if (!(Number.isInteger(rounds) && rounds >= 1)) throw new Error(`--rounds must be a positive integer (got ${rounds})`);
if (!(vertices >= 100)) throw new Error(`--vertices must be at least 100 (got ${vertices})`);
if (argv.length > 1 || (argv[0] ?? '').startsWith('-')) throw new Error(`unexpected arguments: ${argv.join(' ')}`);
const commit = argv[0] ?? '2fe82f8';

function run(command, args, options = {}) {
  const r = spawnSync(command, args, { encoding: 'utf8', maxBuffer: 1 << 26, ...options });
  if (r.status !== 0) {
    throw new Error(`${command} ${args.join(' ')} failed (exit ${r.status}):\n${(r.stderr || r.stdout || '').slice(-2000)}`);
  }
  return r.stdout;
}

const sha = run('git', ['rev-parse', '--short', `${commit}^{commit}`], { cwd: root }).trim();
const there = path.join(root, 'build', `against-${sha}`, 'src');
const builds = {
  [sha]: {
    cli: path.join(there, 'build/native-release/cli/geoshift'),
    wasm: path.join(there, 'build/wasm-release/wasm'),
  },
  here: {
    cli: path.join(root, 'build/native-release/cli/geoshift'),
    wasm: path.join(root, 'build/wasm-release/wasm'),
  },
};
if (!fs.existsSync(builds.here.cli) || !fs.existsSync(path.join(builds.here.wasm, 'geoshift_web_mt.wasm'))) {
  throw new Error(`this checkout's builds are missing (${builds.here.cli}, ${builds.here.wasm}): run scripts/bootstrap.sh first`);
}

// The other commit's sources and builds, made once.
const jobs = String(os.cpus().length);
if (!fs.existsSync(path.join(there, 'CMakePresets.json'))) {
  console.log(`exporting ${sha} to ${path.relative(root, there)}`);
  fs.mkdirSync(there, { recursive: true });
  const tar = spawnSync('sh', ['-c', `git archive ${sha} | tar -x -C "${there}"`], { cwd: root, encoding: 'utf8' });
  if (tar.status !== 0) {
    fs.rmSync(there, { recursive: true, force: true });
    throw new Error(`git archive ${sha} failed: ${tar.stderr}`);
  }
}
if (!fs.existsSync(builds[sha].cli)) {
  console.log(`building ${sha}'s native CLI`);
  run('cmake', ['--preset', 'native-release'], { cwd: there });
  run('cmake', ['--build', 'build/native-release', '-j', jobs, '--target', 'geoshift'], { cwd: there });
}
if (!fs.existsSync(path.join(builds[sha].wasm, 'geoshift_web_mt.wasm'))) {
  console.log(`building ${sha}'s threaded web wasm`);
  run('emcmake', ['cmake', '--preset', 'wasm-release'], { cwd: there });
  run('cmake', ['--build', 'build/wasm-release', '-j', jobs, '--target', 'geoshift_web_mt'], { cwd: there });
}

// One round of one build: denoise.mjs natively and in Chromium, its figures by row.
function measure(b) {
  const env = { ...process.env, GEOSHIFT_NATIVE_CLI: b.cli, GEOSHIFT_WASM_DIR: b.wasm };
  const out = {};
  for (const only of ['native', 'chromium']) {
    const text = run(process.execPath, [path.join(root, 'bench/wasm/denoise.mjs'), '--vertices', String(vertices),
      '--repetitions', '3', '--preset', preset, '--only', only], { cwd: root, env });
    for (const line of text.split('\n')) {
      const time = /^(native CLI, [^ ].*?|Chromium wasm, threads \(\d+\))\s+(\d+)\s/.exec(line);
      if (time) out[time[1]] = Number(time[2]) / 1000;
      const scan = /^scan peak memory.*?(\d+) bytes per vertex/.exec(line);
      if (scan) out['native peak, scan (bytes a vertex)'] = Number(scan[1]);
    }
  }
  return out;
}

console.log(`${preset} preset, ${vertices} vertices; ${rounds} rounds of medians of 3; ${os.cpus().length} cores`);
const figures = { [sha]: [], here: [] };
for (let r = 0; r < rounds; ++r) {
  const order = r % 2 === 0 ? [sha, 'here'] : ['here', sha];
  for (const name of order) {
    figures[name].push(measure(builds[name]));
    console.log(`round ${r + 1}, ${name === 'here' ? 'this checkout' : sha}: ${JSON.stringify(figures[name].at(-1))}`);
  }
}

const rows = [...new Set([...figures[sha], ...figures.here].flatMap((f) => Object.keys(f)))];
const cell = (name, row) => figures[name].map((f) => f[row]).filter((v) => v !== undefined);
const show = (values, row) => values.map((v) => (row.includes('bytes') ? String(v) : `${v.toFixed(2)} s`)).join(', ');
console.log(`\n| | ${sha} | this checkout | this / ${sha} (medians) |\n|---|---|---|---|`);
for (const row of rows) {
  const a = cell(sha, row), b = cell('here', row);
  const ratio = a.length && b.length ? (median(b) / median(a)).toFixed(2) : '-';
  console.log(`| ${row} | ${show(a, row)} | ${show(b, row)} | ${ratio} |`);
}
