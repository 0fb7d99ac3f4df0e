// What the default denoiser chose on a mesh, in words, from the stats the wasm op returns
// (wasm/ops_denoise.cpp): the app's "Chosen" row. The choice itself is described in
// docs/denoising.md#the-default-pipeline; this only words it, as the CLI's report line does.
import { counted } from './words';

/** The stats of one mesh's run: the op's named numbers and strings. */
export type DenoiseStats = Readonly<Record<string, number | string | undefined>>;

// docs/denoising.md#the-noise-level ("Planes left untouched")
const PLANAR_LEVEL = 'noise level read against the flat faces the noise left';

/**
 * "15 Taubin steps + 2 passes at Keep edges 0.35", "27 Taubin steps alone (no pass)" or that the mesh
 * was left as it was, with the candidates blended in, whether the noise level was read against the
 * flat faces the noise left, what decided a close call between the starts, whether a light start
 * raced (and whether its winner was turned down), whether only outliers were
 * moved, how many vertices that correction moved were put back because they lie on untouched planes,
 * and how many pieces too small to denoise were left as they were; null for stats that are not the
 * default denoiser's (another filter, the paper preset).
 */
export function chosenSummary(stats: DenoiseStats): string | null {
  const steps = stats.presmoothingSteps;
  const passes = stats.passes;
  if (typeof steps !== 'number' || typeof passes !== 'number' || typeof stats.noiseLevel !== 'number') return null;
  // docs/denoising.md#the-input-as-a-candidate
  if (stats.keptInput === 'yes') {
    // A clean part of flat faces is kept because its level, read against its planes, is nearly 0.
    const reading = stats.planarLevel === 'yes' ? ` (${PLANAR_LEVEL})` : '';
    return withKeptPieces(`left as it was: no smoothing is estimated to bring it closer to the noise-free surface${reading}`, stats);
  }
  let text = stats.taubinOnly === 'yes' ? `${recipe(steps, passes, true)} (no pass)` : recipe(steps, passes, false);
  if (stats.taubinOnly !== 'yes' && typeof stats.rangeBandwidth === 'number' && stats.rangeBandwidth > 0)
    text += ` at Keep edges ${stats.rangeBandwidth}`;
  // docs/denoising.md#the-blend-of-least-risk: the other family's best, then the other start's,
  // each mixed in with the weight of least estimated error.
  const other = blendedIn(stats.blendWeight, stats.blendSteps, stats.blendPasses, stats.blendTaubinOnly === 'yes');
  if (other) text += `, blended with ${other}`;
  const start = blendedIn(stats.startBlendWeight, stats.startBlendSteps, stats.startBlendPasses, false);
  if (start) text += `, ${other ? 'then' : 'blended'} with ${start}`;
  // Next to the recipe: the level it was chosen with.
  if (stats.planarLevel === 'yes') text += `; ${PLANAR_LEVEL}`;
  // docs/denoising.md#ties-between-starts: more probes, and where they leave it open, the normals.
  const probes = stats.tieProbes;
  if (typeof probes === 'number' && probes > 0)
    text +=
      `; a close call between two starts, settled by ${counted(probes, 'more probe', 'more probes')}` +
      (stats.tieByNormals === 'yes' ? ' and then by the smoother normals' : '');
  // docs/denoising.md#a-light-start: little smoothing looked best.
  if (stats.lightStart === 'raced') text += '; a light start raced (little smoothing looked best)';
  else if (stats.lightStart === 'turned down') text += '; a light start raced, turned down (its normals turned too much)';
  if (stats.impulseGarrote === 'yes') text += '; impulsive noise: only the outliers moved';
  // docs/denoising.md#impulsive-noise ("Vertices on untouched planes"): moved by the correction, put back.
  const planarKept = stats.planarKept;
  if (typeof planarKept === 'number' && planarKept > 0)
    text +=
      `; ${counted(planarKept, 'vertex on an untouched plane', 'vertices on untouched planes')}` +
      ` kept as ${planarKept === 1 ? 'it was' : 'they were'}`;
  return withKeptPieces(text, stats);
}

/** "12 Taubin steps alone (31% of the weight)": a candidate blended in, or null where none was. */
function blendedIn(weight: unknown, steps: unknown, passes: unknown, taubinOnly: boolean): string | null {
  if (typeof weight !== 'number' || !(weight > 0) || typeof steps !== 'number') return null;
  return `${recipe(steps, Number(passes), taubinOnly)} (${Math.round(weight * 100)}% of the weight)`;
}

/** "27 Taubin steps alone" or "15 Taubin steps + 2 passes": one candidate. */
function recipe(steps: number, passes: number, taubinOnly: boolean): string {
  return taubinOnly
    ? `${counted(steps, 'Taubin step')} alone`
    : `${counted(steps, 'Taubin step')} + ${counted(passes, 'pass', 'passes')}`;
}

function withKeptPieces(text: string, stats: DenoiseStats): string {
  // docs/denoising.md#small-pieces
  const kept = stats.keptPieces;
  if (typeof kept === 'number' && kept > 0)
    text += `; ${counted(kept, 'small piece')} left as ${kept === 1 ? 'it was' : 'they were'}`;
  return text;
}
