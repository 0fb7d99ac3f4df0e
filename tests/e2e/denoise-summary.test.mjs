// Unit tests of web/src/denoise-summary.ts (the app's "Chosen" row), run in the browser through the
// Vite dev server, which compiles the TypeScript on request: the code the app runs.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { useApp } from './harness.mjs';

const app = useApp();

/** chosenSummary of `stats` in the page. */
function chosen(stats) {
  return app.page.evaluate(async (s) => {
    const { chosenSummary } = await import('/src/denoise-summary.ts');
    return chosenSummary(s);
  }, stats);
}

// What the wasm op returns for a default denoise (wasm/ops_denoise.cpp), without a tie.
const PASSES = {
  preset: 'default', noiseLevel: 0.25, noiseEstimated: 'yes', presmoothingSteps: 15, passes: 2, taubinOnly: 'no',
  rangeBandwidth: 0.35, passesRun: 40, tieProbes: 0, tieByNormals: 'no', impulseGarrote: 'no',
};

test('the start, the passes and the range bandwidth are named, in the singular where one', async () => {
  assert.equal(await chosen(PASSES), '15 Taubin steps + 2 passes at Keep edges 0.35');
  assert.equal(await chosen({ ...PASSES, presmoothingSteps: 1, passes: 1 }), '1 Taubin step + 1 pass at Keep edges 0.35');
  assert.equal(await chosen({ ...PASSES, passes: 0 }), '15 Taubin steps + 0 passes at Keep edges 0.35');
});

test('a Taubin-only result has no passes and no range bandwidth', async () => {
  assert.equal(await chosen({ ...PASSES, presmoothingSteps: 27, passes: 0, taubinOnly: 'yes', rangeBandwidth: 0 }),
    '27 Taubin steps alone (no pass)');
});

test('the candidate of the other family blended in is named with its share of the weight', async () => {
  assert.equal(await chosen({ ...PASSES, blendWeight: 0.314, blendSteps: 12, blendPasses: 0, blendTaubinOnly: 'yes' }),
    '15 Taubin steps + 2 passes at Keep edges 0.35, blended with 12 Taubin steps alone (31% of the weight)');
  assert.equal(await chosen({ ...PASSES, presmoothingSteps: 40, passes: 0, taubinOnly: 'yes', rangeBandwidth: 0,
    blendWeight: 0.25, blendSteps: 15, blendPasses: 1, blendTaubinOnly: 'no', tieProbes: 1 }),
    '40 Taubin steps alone (no pass), blended with 15 Taubin steps + 1 pass (25% of the weight);' +
    ' a close call between two starts, settled by 1 more probe');
  // No weight, no blend named.
  assert.equal(await chosen({ ...PASSES, blendWeight: 0, blendSteps: 0, blendPasses: 0, blendTaubinOnly: 'no' }),
    '15 Taubin steps + 2 passes at Keep edges 0.35');
});

test('the candidate of the other start blended in after it is named with its share too', async () => {
  assert.equal(await chosen({ ...PASSES, blendWeight: 0.314, blendSteps: 12, blendPasses: 0, blendTaubinOnly: 'yes',
    startBlendWeight: 0.2, startBlendSteps: 3, startBlendPasses: 4 }),
    '15 Taubin steps + 2 passes at Keep edges 0.35, blended with 12 Taubin steps alone (31% of the weight),' +
    ' then with 3 Taubin steps + 4 passes (20% of the weight)');
  // Only the other start's.
  assert.equal(await chosen({ ...PASSES, blendWeight: 0, startBlendWeight: 0.5, startBlendSteps: 3, startBlendPasses: 1 }),
    '15 Taubin steps + 2 passes at Keep edges 0.35, blended with 3 Taubin steps + 1 pass (50% of the weight)');
  assert.equal(await chosen({ ...PASSES, startBlendWeight: 0, startBlendSteps: 0, startBlendPasses: 0 }),
    '15 Taubin steps + 2 passes at Keep edges 0.35');
});

test('a tie says how many more probes settled it, and when the normals did', async () => {
  assert.equal(await chosen({ ...PASSES, tieProbes: 1 }),
    '15 Taubin steps + 2 passes at Keep edges 0.35; a close call between two starts, settled by 1 more probe');
  assert.equal(await chosen({ ...PASSES, tieProbes: 4, tieByNormals: 'yes' }),
    '15 Taubin steps + 2 passes at Keep edges 0.35; a close call between two starts, settled by 4 more probes' +
    ' and then by the smoother normals');
  // The normals decide only after probes; a stat without probes says nothing of a tie.
  assert.equal(await chosen({ ...PASSES, tieProbes: 0, tieByNormals: 'yes' }), '15 Taubin steps + 2 passes at Keep edges 0.35');
});

test('a light start is named after the tie, with whether its winner was turned down', async () => {
  assert.equal(await chosen({ ...PASSES, presmoothingSteps: 1, passes: 3, lightStart: 'raced' }),
    '1 Taubin step + 3 passes at Keep edges 0.35; a light start raced (little smoothing looked best)');
  assert.equal(await chosen({ ...PASSES, presmoothingSteps: 3, passes: 3, tieProbes: 1, lightStart: 'turned down',
    impulseGarrote: 'yes' }),
    '3 Taubin steps + 3 passes at Keep edges 0.35; a close call between two starts, settled by 1 more probe;' +
    ' a light start raced, turned down (its normals turned too much); impulsive noise: only the outliers moved');
  // 'no', or a stat the op did not send, says nothing of it.
  assert.equal(await chosen({ ...PASSES, lightStart: 'no' }), '15 Taubin steps + 2 passes at Keep edges 0.35');
});

test('the impulse correction is named after the tie', async () => {
  assert.equal(await chosen({ ...PASSES, presmoothingSteps: 3, passes: 1, tieProbes: 2, impulseGarrote: 'yes' }),
    '3 Taubin steps + 1 pass at Keep edges 0.35; a close call between two starts, settled by 2 more probes;' +
    ' impulsive noise: only the outliers moved');
});

test('a level read against the flat faces the noise left is named next to the recipe, before the tie', async () => {
  assert.equal(await chosen({ ...PASSES, planarLevel: 'yes' }),
    '15 Taubin steps + 2 passes at Keep edges 0.35; noise level read against the flat faces the noise left');
  assert.equal(await chosen({ ...PASSES, planarLevel: 'yes', blendWeight: 0.314, blendSteps: 12, blendPasses: 0,
    blendTaubinOnly: 'yes', tieProbes: 1, impulseGarrote: 'yes' }),
    '15 Taubin steps + 2 passes at Keep edges 0.35, blended with 12 Taubin steps alone (31% of the weight);' +
    ' noise level read against the flat faces the noise left; a close call between two starts, settled by 1 more probe;' +
    ' impulsive noise: only the outliers moved');
  // 'no', or a stat the op did not send, says nothing of it.
  assert.equal(await chosen({ ...PASSES, planarLevel: 'no' }), '15 Taubin steps + 2 passes at Keep edges 0.35');
});

test('vertices on untouched planes put back after the impulse correction are counted, in the singular where one', async () => {
  const impulsive = { ...PASSES, impulseGarrote: 'yes' };
  assert.equal(await chosen({ ...impulsive, planarKept: 1 }),
    '15 Taubin steps + 2 passes at Keep edges 0.35; impulsive noise: only the outliers moved;' +
    ' 1 vertex on an untouched plane kept as it was');
  assert.equal(await chosen({ ...impulsive, planarLevel: 'yes', planarKept: 1234, keptPieces: 1, keptVertices: 3 }),
    '15 Taubin steps + 2 passes at Keep edges 0.35; noise level read against the flat faces the noise left;' +
    ' impulsive noise: only the outliers moved; 1,234 vertices on untouched planes kept as they were; 1 small piece left as it was');
  assert.equal(await chosen({ ...impulsive, planarKept: 0 }),
    '15 Taubin steps + 2 passes at Keep edges 0.35; impulsive noise: only the outliers moved');
  assert.equal(await chosen(impulsive), '15 Taubin steps + 2 passes at Keep edges 0.35; impulsive noise: only the outliers moved');
});

test('pieces too small to denoise are counted last, in the singular where one', async () => {
  assert.equal(await chosen({ ...PASSES, keptPieces: 1, keptVertices: 4 }),
    '15 Taubin steps + 2 passes at Keep edges 0.35; 1 small piece left as it was');
  assert.equal(await chosen({ ...PASSES, impulseGarrote: 'yes', keptPieces: 3, keptVertices: 40 }),
    '15 Taubin steps + 2 passes at Keep edges 0.35; impulsive noise: only the outliers moved; 3 small pieces left as they were');
  assert.equal(await chosen({ ...PASSES, keptPieces: 0, keptVertices: 0 }), '15 Taubin steps + 2 passes at Keep edges 0.35');
});

test('a mesh left as it was says so, with no recipe, and still counts its small pieces', async () => {
  const kept = { ...PASSES, presmoothingSteps: 0, passes: 0, rangeBandwidth: 0, keptInput: 'yes' };
  assert.equal(await chosen(kept), 'left as it was: no smoothing is estimated to bring it closer to the noise-free surface');
  assert.equal(await chosen({ ...kept, tieProbes: 2, keptPieces: 2, keptVertices: 8 }),
    'left as it was: no smoothing is estimated to bring it closer to the noise-free surface; 2 small pieces left as they were');
  assert.equal(await chosen({ ...PASSES, keptInput: 'no' }), '15 Taubin steps + 2 passes at Keep edges 0.35');
  // A clean part of flat faces is kept because of the level read against its planes.
  assert.equal(await chosen({ ...kept, planarLevel: 'yes', planarKept: 0 }),
    'left as it was: no smoothing is estimated to bring it closer to the noise-free surface' +
    ' (noise level read against the flat faces the noise left)');
  assert.equal(await chosen({ ...kept, planarLevel: 'no' }),
    'left as it was: no smoothing is estimated to bring it closer to the noise-free surface');
});

test('stats of another filter or of the paper preset have no Chosen row', async () => {
  assert.equal(await chosen({ method: 'taubin', iterations: 20, threads: 1 }), null);
  assert.equal(await chosen({ preset: 'paper', passes: 3, meanIterations: 7.5 }), null);
  assert.equal(await chosen({}), null);
});
