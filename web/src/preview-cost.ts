// What an op costs per vertex of a live preview's coarse level, before a preview has measured it
// (live-preview.ts picks the first level from it).

// From bench/wasm/preview.mjs (threaded build, 2 cores shared with other work; op time on a
// 2,500-vertex level): the Terrain preset's filter (r = 15 AEL, k_max 5) 95 µs a vertex, Filter
// curvature (r = 9, k_max 50, two levels inside) 65, Denoise 82, Taubin (10 steps) under 1.
const FILTER_US_PER_AREA = 0.9;
const DENOISE_US = 100;
const SMOOTH_US_PER_ITERATION = 0.05;
const OTHER_US = 1;

/**
 * What an op costs per vertex of the coarse level (µs, threaded build on 2 cores), before a preview
 * has measured it: the mean shift grows with the neighbourhood's area (r² in AEL) and the passes.
 * A high guess only costs detail in the first preview (adapt() moves up after it); a low one makes
 * the first drag wait. Figures: bench/wasm/preview.mjs, docs/performance.md#live-preview.
 */
export function costPerVertex(op: string, params: Record<string, unknown>): number {
  const number = (key: string, fallback: number) => (typeof params[key] === 'number' && Number.isFinite(params[key]) ? (params[key] as number) : fallback);
  switch (op) {
    case 'filter': {
      const hs = number('hs', 3);
      const radius = number('radius', 0) > 0 ? number('radius', 0) : 3 * hs;
      const passes = params.mode === 'bms' ? Math.max(1, number('passes', 10)) : 1;
      return FILTER_US_PER_AREA * radius * radius * passes;
    }
    case 'denoise':
      return DENOISE_US;
    case 'smooth':
      return SMOOTH_US_PER_ITERATION * Math.max(1, number('iterations', 10));
    default:
      return OTHER_US;
  }
}
