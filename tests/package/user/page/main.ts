// A page written as a user of the package would write it, bundled by Vite from the installed
// tarball: denoises a three.js BufferGeometry in the package's worker, with progress, cancel and a
// bad input (tests/package/package.test.mjs drives it in Chromium through window.userTest).
import { createGeoshift, GeoshiftError, type Geoshift, type GeoshiftInfo } from 'geoshift';
import { denoiseGeometry, smoothGeometry } from 'geoshift/three';
import { BufferAttribute, BufferGeometry, InterleavedBuffer, InterleavedBufferAttribute } from 'three';

interface Outcome {
  kind: string;
  message: string;
}

async function outcome(promise: Promise<unknown>): Promise<Outcome> {
  try {
    await promise;
    return { kind: 'none', message: '' };
  } catch (error) {
    return error instanceof GeoshiftError ? { kind: error.kind, message: error.message } : { kind: 'not a GeoshiftError', message: String(error) };
  }
}

/** Positions interleaved with uvs (as glTF files often hold them), and an index: a layout three produces. */
function geometryOf(positions: number[], indices: number[]): BufferGeometry {
  const count = positions.length / 3;
  const interleaved = new Float32Array(5 * count);
  for (let v = 0; v < count; v++) {
    interleaved.set(positions.slice(3 * v, 3 * v + 3), 5 * v);
    interleaved.set([v / count, 1 - v / count], 5 * v + 3);
  }
  const buffer = new InterleavedBuffer(interleaved, 5);
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new InterleavedBufferAttribute(buffer, 3, 0));
  geometry.setAttribute('uv', new InterleavedBufferAttribute(buffer, 2, 3));
  geometry.setIndex(new BufferAttribute(new Uint16Array(indices), 1));
  geometry.addGroup(0, indices.length, 0);
  return geometry;
}

const userTest = {
  gs: null as Geoshift | null,

  async start(threads: 'auto' | number): Promise<GeoshiftInfo> {
    this.gs = await createGeoshift({ threads });
    return this.gs.info;
  },

  /** A second worker whose module files come from elsewhere (as from a CDN): /cdn/ on this server. */
  async elsewhere(positions: number[], indices: number[]) {
    const asked: string[] = [];
    const gs = await createGeoshift({ threads: 1, locateFile: (file) => (asked.push(file), new URL(`/cdn/${file}`, location.href)) });
    try {
      const { attributes } = await gs.curvature({ positions: new Float32Array(positions), indices: new Uint32Array(indices) });
      return { asked, curvature: Object.keys(attributes) };
    } finally {
      gs.terminate();
    }
  },

  async denoise(positions: number[], indices: number[]) {
    const gs = this.gs!;
    const geometry = geometryOf(positions, indices);
    const progress: Array<[number, string]> = [];
    const denoised = await denoiseGeometry(gs, geometry, { onProgress: (fraction, stage) => progress.push([fraction, stage]) });
    const position = denoised.getAttribute('position');
    const out: number[] = [];
    for (let v = 0; v < position.count; v++) out.push(position.getX(v), position.getY(v), position.getZ(v));
    const before = geometry.getAttribute('position');
    return {
      positions: out,
      progress,
      normals: denoised.getAttribute('normal')?.count ?? 0,
      uvKept: denoised.getAttribute('uv')?.getY(1) === geometry.getAttribute('uv').getY(1),
      groupsKept: denoised.groups.length === 1,
      inputUnchanged: Array.from({ length: before.count * 3 }, (_, i) => [before.getX, before.getY, before.getZ][i % 3]!.call(before, Math.floor(i / 3))).every((x, i) => x === positions[i]),
    };
  },

  /** A long smoothing, aborted at its first progress report; then a short job on the same worker. */
  async cancel(positions: number[], indices: number[]) {
    const gs = this.gs!;
    const controller = new AbortController();
    const started = performance.now();
    const cancelled = await outcome(smoothGeometry(gs, geometryOf(positions, indices), { iterations: 1_000_000, signal: controller.signal, onProgress: () => controller.abort() }));
    const ms = performance.now() - started;
    const after = await outcome(smoothGeometry(gs, geometryOf(positions, indices), { iterations: 2 }));
    return { cancelled, after, ms };
  },

  async badInput(positions: number[]) {
    const gs = this.gs!;
    const badIndex = await outcome(gs.denoise({ positions: new Float32Array(positions), indices: new Uint32Array([0, 1, 7_000_000]) }));
    const badValue = await outcome(gs.smooth({ positions: new Float32Array(positions.slice(0, 9)) }, { iterations: -3 }));
    const notAnArray = await outcome(gs.denoise({ positions: positions as unknown as Float32Array }));
    return { badIndex, badValue, notAnArray };
  },
};

declare global {
  interface Window {
    userTest: typeof userTest;
  }
}
window.userTest = userTest;
document.getElementById('state')!.textContent = 'ready';
