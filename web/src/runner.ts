// Runs an op on every mesh of the open file, one after another, through the worker. Results are
// applied only when every mesh succeeded, so a failure or a cancel leaves the model as it was.

import { BufferAttribute } from 'three';
import { applyOutput, baseGeometry, dropPreview, meshArrays, rmsError, snapshot, type MeshState } from './model';
import type { Preset } from './presets';
import { GeoshiftError, type RunOutput, type WorkerClient } from './worker/client';

export interface RunReport {
  op: string;
  preset: string;
  /** Wall time on the page, load and copies included (ms). */
  wallMs: number;
  /** Time inside the module, summed over meshes (ms). */
  computeMs: number;
  vertices: number;
  meshes: number;
  /** Iterations, mean shift steps per vertex or passes the op reports, when it does. */
  iterations: { kind: 'iterations' | 'meanIterations' | 'passes'; value: number } | null;
  /** Per-vertex RMS distance to the positions before noise was added, and that of the input. */
  error: { rms: number; inputRms: number; diagonal: number } | null;
  scalars: string[];
  stats: RunOutput['stats'][];
}

export interface ProgressEvent {
  /** Overall, over all meshes. */
  fraction: number;
  stage: string;
  /** The stage's own fraction, or null for a step that cannot tell (sending the mesh). */
  stageFraction: number | null;
  /** performance.now() when the page received it. */
  at: number;
}

/** The signal a terrain filter falls back to when the file has no attribute of its own. */
export const HEIGHT = '_height';

/** Each vertex's coordinate along the axis in which the mesh is thinnest (a terrain's "up"). */
export function heightOf(positions: Float32Array): Float32Array {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i++) {
    min[i % 3] = Math.min(min[i % 3]!, positions[i]!);
    max[i % 3] = Math.max(max[i % 3]!, positions[i]!);
  }
  const extent = [0, 1, 2].map((k) => max[k]! - min[k]!);
  const up = extent.indexOf(Math.min(...extent));
  return Float32Array.from({ length: positions.length / 3 }, (_, v) => positions[3 * v + up]!);
}

function iterationsOf(stats: RunOutput['stats'][]): RunReport['iterations'] {
  for (const kind of ['iterations', 'meanIterations', 'passes'] as const) {
    const values = stats.map((s) => s[kind]).filter((v): v is number => typeof v === 'number');
    if (values.length) return { kind, value: Math.max(...values) };
  }
  return null;
}

export async function runOnMeshes(
  client: WorkerClient,
  states: MeshState[],
  preset: Preset,
  params: Record<string, unknown>,
  onProgress: (event: ProgressEvent) => void,
  /** Checked between the steps: a cancel may come while a mesh is still being sent. */
  cancelled: () => boolean = () => false,
): Promise<RunReport> {
  const started = performance.now();
  const outputs: RunOutput[] = [];
  const inputs: Float32Array[] = [];
  /** Per mesh, the raw field a filter of a computed signal started from (for "before"). */
  const raws: Array<Record<string, Float32Array>> = [];
  for (const [i, state] of states.entries()) {
    const prefix = states.length > 1 ? `mesh ${i + 1}/${states.length}: ` : '';
    onProgress({ fraction: i / states.length, stage: `${prefix}preparing the mesh`, stageFraction: null, at: performance.now() });
    const stopIfCancelled = () => {
      if (cancelled()) throw new GeoshiftError('cancelled', 'cancelled');
    };
    stopIfCancelled();
    // A live preview may be on screen meanwhile; the run works on the mesh's own geometry.
    const arrays = meshArrays(baseGeometry(state));
    if (params.signal === HEIGHT && !arrays.scalars[HEIGHT]) arrays.scalars[HEIGHT] = heightOf(arrays.positions);
    inputs.push(arrays.positions);
    await client.load(state.id, arrays);
    stopIfCancelled();
    outputs.push(
      await client.run(state.id, preset.op, params, (fraction, stage) =>
        onProgress({ fraction: (i + fraction) / states.length, stage: `${prefix}${stage}`, stageFraction: fraction, at: performance.now() }),
      ),
    );
    raws.push(await rawField(client, state.id, preset, params));
  }
  // Every mesh succeeded: apply all at once.
  let errorSum = 0;
  let inputErrorSum = 0;
  let errorCount = 0;
  let diagonal = 0;
  for (const [i, state] of states.entries()) {
    const output = outputs[i]!;
    dropPreview(state);
    snapshot(state);
    // "Before" shows the field the filter started from, so that the split view compares two fields.
    for (const [name, values] of Object.entries(raws[i]!)) state.before?.setAttribute(name.toLowerCase(), new BufferAttribute(values, 1));
    if (preset.op === 'noise' && output.positions && !state.preNoise) state.preNoise = inputs[i]!;
    applyOutput(state, output, preset.replacesColors === true);
    if (preset.op !== 'noise' && state.preNoise && output.positions && state.preNoise.length === output.positions.length) {
      const after = rmsError(output.positions, state.preNoise);
      const before = rmsError(inputs[i]!, state.preNoise);
      const n = output.positions.length / 3;
      errorSum += after.rms ** 2 * n;
      inputErrorSum += before.rms ** 2 * n;
      errorCount += n;
      diagonal = Math.max(diagonal, after.diagonal);
    }
  }
  const stats = outputs.map((o) => o.stats);
  return {
    op: preset.op,
    preset: preset.name,
    wallMs: performance.now() - started,
    computeMs: stats.reduce((t, s) => t + s.timeMs, 0),
    vertices: stats.reduce((t, s) => t + s.vertices, 0),
    meshes: states.length,
    iterations: iterationsOf(stats),
    error: errorCount ? { rms: Math.sqrt(errorSum / errorCount), inputRms: Math.sqrt(inputErrorSum / errorCount), diagonal } : null,
    scalars: [...new Set(outputs.flatMap((o) => Object.keys(o.scalars).map((n) => n.toLowerCase())))],
    stats,
  };
}

/**
 * A filter of a signal the op computes from the shape (the absolute curvature) leaves no field in
 * the mesh before it: the raw field is computed here by the `curvature` op on the same mesh (the
 * filter left the worker's copy unmoved), the same values the filter started from
 * (filter_request.cpp). Other runs: nothing.
 */
async function rawField(client: WorkerClient, meshId: string, preset: Preset, params: Record<string, unknown>): Promise<Record<string, Float32Array>> {
  if (preset.op !== 'filter' || params.signal !== 'curvature' || params.filterGeometry === true) return {};
  const raw = await client.run(meshId, 'curvature', { kind: 'abs' }, () => undefined);
  return raw.scalars;
}

/** Plain words for a failed run. */
export function describeRunFailure(error: unknown): string {
  if (error instanceof GeoshiftError) {
    switch (error.kind) {
      case 'cancelled':
        return 'Cancelled; the mesh is unchanged.';
      case 'out-of-memory':
        return 'Out of memory: the mesh is too large for the browser. Try a smaller mesh, or the command-line tool.';
      case 'input':
        return `The filter could not run: ${error.message}. The mesh is unchanged.`;
      case 'internal':
        // An internal error's text (a C++ or JS exception) means nothing to users: it goes to the
        // console, the page says what failed.
        console.error('geoshift: internal error in a filter run', error);
        return 'Something went wrong inside the filter (an internal error; details in the browser console). The mesh is unchanged; reloading the page may help.';
    }
  }
  console.error('geoshift: a filter run failed', error);
  return 'Something went wrong while running the filter (details in the browser console). The mesh is unchanged.';
}
