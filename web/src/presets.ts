// The presets of the side panel: which op each runs and every parameter it sends, with the unit
// and a plain-words explanation shown as a tooltip. Spatial parameters are multiples of the mesh's
// average edge length (AEL). The values of the filter presets are the core's (filterPresets(),
// docs/algorithms.md#presets), read from the module when it starts (applyCorePresets).

import type { CorePreset } from 'geoshift';

export interface NumberParam {
  key: string;
  kind: 'number';
  label: string;
  unit: string;
  value: number;
  min: number;
  max: number;
  step: number;
  tooltip: string;
}

export interface ChoiceParam {
  key: string;
  kind: 'choice';
  label: string;
  value: string;
  /** Shown label -> value sent. */
  options: Record<string, string>;
  tooltip: string;
}

export interface FlagParam {
  key: string;
  kind: 'flag';
  label: string;
  value: boolean;
  tooltip: string;
}

export type Param = (NumberParam | ChoiceParam | FlagParam) & {
  /** Folded away under "Expert settings" in the panel. */
  expert?: boolean;
};

export interface Preset {
  id: string;
  name: string;
  /** Op of the wasm module (ops_NAME.cpp). */
  op: string;
  /** One sentence shown under the preset select. */
  summary: string;
  params: Param[];
  /** Sent unchanged, not shown (e.g. the method of the denoise op). */
  fixed?: Record<string, unknown>;
  /** The output's colors replace the mesh's vertex colors (a color filter). */
  replacesColors?: boolean;
  /** The scalar the result is best looked at in (view mode "scalar field"). */
  showsScalar?: string;
  /** The scalar signal the op reads, chosen from the mesh's scalar attributes (Terrain). */
  needsScalar?: boolean;
  /** The core's filter preset whose values its parameters take (applyCorePresets). */
  core?: string;
}

const AEL = '× AEL';
/** The value of a parameter that the module gives (applyCorePresets). */
const CORE = Number.NaN;

/** A parameter shown in the preset's folded "Expert settings". */
const expert = <P extends Param>(p: P): P => ({ ...p, expert: true });

const num = (key: string, label: string, unit: string, value: number, min: number, max: number, step: number, tooltip: string): NumberParam => ({
  key, kind: 'number', label, unit, value, min, max, step, tooltip,
});

// Parameters shared by the mean shift presets, in the words of a user first and the paper second.
const radius = (v: number) => num('radius', 'Neighbourhood radius r', AEL, v, 0.5, 30, 0.5, 'How far around each point the filter looks. Larger is smoother and slower.');
const hs = (v: number) => num('hs', 'Spatial bandwidth h_s', AEL, v, 0.25, 20, 0.25, 'How quickly the influence of a neighbour fades with its distance along the surface.');
const kmax = (v: number) => num('kmax', 'Max iterations k_max', '', v, 1, 500, 1, 'Upper limit on mean shift steps per point; points usually settle sooner.');
const eps = (v: number) => num('eps', 'Convergence ε', AEL, v, 0.01, 2, 0.01, 'A point stops moving once a step is shorter than this.');
const passes = (v: number) => num('passes', 'Passes', '', v, 1, 50, 1, 'How many times the filter is applied in a row (blurring mean shift uses several).');
// The mode and the value update of the filter presets come from the module ('' until then).
const mode = (): ChoiceParam => ({
  key: 'mode', kind: 'choice', label: 'Algorithm', value: '',
  options: { 'Mean shift (MS)': 'ms', 'Blurring mean shift (BMS)': 'bms' },
  tooltip: 'Mean shift keeps the input fixed while points climb to the nearest mode; blurring mean shift updates the signal after every pass (smoother, faster to flatten).',
});
const rangeUpdate = (): ChoiceParam => ({
  key: 'rangeUpdate', kind: 'choice', label: 'Value update', value: '',
  // Short labels: the select is as wide as the panel's value column; the tooltip explains them.
  options: { Joint: 'joint', 'Sampled (paper)': 'sampled' },
  tooltip: 'How a point\'s value follows it. Joint: it takes its own mean shift step (moves with the point; smooths evenly sampled signals better). Sampled: it is read from the surface where the point is (the paper).',
});
// The denoiser's treatment of outliers (docs/denoising.md#impulsive-noise); the module gives the default.
const impulse = (): ChoiceParam => ({
  key: 'impulse', kind: 'choice', label: 'Outliers', value: '',
  options: { Auto: 'auto', 'Always fix': 'on', 'Never fix': 'off' },
  tooltip: 'Spikes where a few scan points landed far off. Auto fixes them when the result shows few points moved far, keeping the other points where they were; Always fixes them in any case; Never smooths every point alike.',
});
const segments: FlagParam = {
  key: 'segments', kind: 'flag', label: 'Also find segments', value: false,
  tooltip: 'Label vertices that end at the same mode with one number, and show the labels as segments.',
};
/**
 * The mean shift presets' settings a first try does not need, folded under "Expert settings" so
 * that the Result section stays in view at 1280 × 800 (issue 30).
 */
const expertFilterParams = (): Param[] => [mode(), radius(CORE), kmax(CORE), eps(CORE), passes(CORE), rangeUpdate(), levels(CORE), alpha(CORE)].map(expert);
const levels = (v: number) => num('levels', 'Wavelet levels L', '', v, 0, 12, 1, 'Filter a coarser version of the mesh L times simplified, then add the detail back. Faster on big meshes.');
const alpha = (v: number) => num('alpha', 'Detail gain α', '', v, 0, 2, 0.05, 'How much of the removed fine detail is added back (0 = none, 1 = all of it).');

export const PRESETS: Preset[] = [
  {
    id: 'denoise', name: 'Denoise', op: 'denoise', core: 'denoise',
    summary: 'Removes scanner noise from the surface while keeping sharp edges and corners. Auto measures the noise on the mesh and picks how much to smooth.',
    fixed: { method: 'meanshift' },
    params: [
      num('strength', 'Strength', '× the noise', CORE, 0.25, 4, 0.05, 'How hard to smooth, relative to the noise measured on the mesh (or given below). Above 1 smooths more, below 1 keeps more fine detail.'),
      num('hr', 'Keep edges (0 = Auto)', 'normal tolerance', CORE, 0, 1, 0.01, 'How different two surface directions may be and still be averaged. Smaller keeps more edges and corners sharp; larger smooths organic shapes more evenly. 0 lets the risk estimate choose between 0.35 and 0.5.'),
      num('noise', 'Noise level (0 = Auto)', AEL, CORE, 0, 3, 0.01, 'How far the scan points scatter around the true surface. 0 measures it on the mesh; the result panel shows the value found.'),
      expert(num('passes', 'Passes (0 = Auto)', '', CORE, 0, 60, 1, 'Rounds of normal filtering and vertex update. 0 lets the risk estimate choose.')),
      expert(num('radius', 'Neighbourhood radius r', AEL, CORE, 0.5, 10, 0.05, 'How far around each face the normals are averaged.')),
      expert(num('hs', 'Spatial bandwidth h_s', AEL, CORE, 0.1, 5, 0.05, 'How quickly the influence of a neighbouring face fades with its distance.')),
      expert(num('vertexIterations', 'Vertex update steps', '', CORE, 1, 200, 1, 'Steps that move the vertices to fit the filtered normals after each pass.')),
      expert(impulse()),
      expert(num('lightStart', 'Light start (0 = off)', 'Taubin steps', CORE, 0, 10, 1, 'On thin parts (blades, fins, sheets) a result with very little smoothing often looks best: it is tried too, and kept only if its surface is not much rougher than the others. 0 never tries it.')),
      expert(levels(CORE)), expert(alpha(CORE)),
    ],
  },
  {
    id: 'smooth-colors', name: 'Smooth colors', op: 'filter', replacesColors: true, core: 'color',
    summary: 'Evens out blotchy vertex colors while keeping borders between differently colored regions.',
    fixed: { signal: 'color' },
    params: [
      hs(CORE),
      num('hr', 'Color tolerance h_r', 'linear RGB', CORE, 0.01, 0.5, 0.01, 'How different two colors may be and still be blended. Smaller keeps more borders.'),
      segments, ...expertFilterParams(),
    ],
  },
  {
    id: 'filter-curvature', name: 'Filter curvature', op: 'filter', showsScalar: '_curvature', core: 'curvature-ms',
    summary: 'Smooths the absolute curvature of the surface, e.g. to find ridges and valleys robustly.',
    fixed: { signal: 'curvature' },
    params: [
      hs(CORE),
      num('hr', 'Curvature tolerance h_r', '1 / length', CORE, 0.01, 2, 0.01, 'How different two curvature values may be and still be averaged. Smaller keeps creases apart from the faces around them.'),
      segments, ...expertFilterParams(),
    ],
  },
  {
    // The filtered attribute comes back under its own name, the first scalar of the result.
    id: 'terrain', name: 'Terrain', op: 'filter', needsScalar: true, core: 'terrain-bms',
    summary: 'Smooths a per-vertex attribute of a terrain (height, vegetation height, class) along the ground.',
    params: [
      hs(CORE),
      num('hr', 'Value tolerance h_r', 'attribute units', CORE, 0.1, 30, 0.1, 'How different two attribute values may be and still be averaged (for a height above ground: metres).'),
      segments, ...expertFilterParams(),
    ],
  },
  {
    id: 'taubin', name: 'Smooth shape (Taubin)', op: 'smooth',
    summary: 'Classic Taubin λ|μ smoothing of the positions: fast, but rounds off sharp edges too.',
    params: [
      num('iterations', 'Iterations', '', 10, 0, 100000, 1, 'Number of shrink-and-inflate step pairs. More is smoother.'),
      num('lambda', 'Shrink step λ', '', 0.5, 0.01, 1, 0.01, 'Size of the smoothing step.'),
      num('mu', 'Inflate step μ', '', -0.53, -1, -0.01, 0.01, 'Size of the step that undoes shrinking; must be below −λ.'),
      {
        key: 'weights', kind: 'choice', label: 'Neighbour weights', value: 'uniform',
        options: { Uniform: 'uniform', 'Inverse edge length': 'fujiwara', Cotangent: 'cotangent' },
        tooltip: 'How neighbours are weighted: all alike, closer ones more, or by the surface geometry.',
      },
    ],
  },
  {
    id: 'curvature', name: 'Curvature', op: 'curvature', showsScalar: '_curvature',
    summary: 'Computes the discrete curvature of the surface and shows it as a color map.',
    params: [{
      key: 'kind', kind: 'choice', label: 'Kind', value: 'abs',
      options: { 'Absolute |k1|+|k2|': 'abs', 'Mean H': 'mean', 'Gaussian K': 'gauss', RMS: 'rms' },
      tooltip: 'Which curvature to compute: absolute is large on any bend, mean has a sign (bulge or dent), Gaussian tells domes from saddles.',
    }],
  },
  {
    id: 'geodesic', name: 'Geodesic distance', op: 'geodesic', showsScalar: '_geodesic',
    summary: 'Distance along the surface from one vertex (Alt+click the mesh to pick it).',
    params: [
      num('source', 'From vertex', 'index', 0, 0, 1e9, 1, 'The vertex distances are measured from; Alt+click on the mesh to pick one.'),
      num('radius', 'Up to', AEL, 1000, 1, 1e6, 1, 'Vertices farther than this are left out (shown grey).'),
    ],
  },
];

/** "Add noise" runs this op; the amount is editable next to the button. */
export const NOISE: Preset = {
  id: 'noise', name: 'Add noise', op: 'noise',
  summary: 'Displaces every vertex randomly, to try the denoising filters on.',
  params: [
    num('amount', 'Noise amount', AEL, 0.5, 0, 5, 0.05, 'How far each vertex is moved, in average edge lengths.'),
    num('seed', 'Seed', '', 1, 0, 1e9, 1, 'The same seed gives the same noise.'),
  ],
  fixed: { distribution: 'fixed', direction: 'random' },
};

/**
 * Gives the presets that follow a core preset its values (the module's presets()). Throws when the
 * module lacks one of them or a value for one of their parameters.
 */
export function applyCorePresets(core: CorePreset[], presets: Preset[] = PRESETS): void {
  for (const preset of presets) {
    if (!preset.core) continue;
    const values = core.find((c) => c.name === preset.core) as Record<string, unknown> | undefined;
    if (!values) throw new Error(`the module has no filter preset "${preset.core}"`);
    for (const param of preset.params) {
      if (param.kind === 'flag') continue;
      const value = values[param.key];
      if (typeof value !== typeof param.value) throw new Error(`the module's preset "${preset.core}" gives no ${param.key}`);
      param.value = value as never;
    }
  }
}

/** Whether the preset's values are known (a core preset's arrive with the module). */
export function hasValues(preset: Preset): boolean {
  return preset.params.every((p) => p.kind !== 'number' || !Number.isNaN(p.value)) &&
    preset.params.every((p) => p.kind !== 'choice' || p.value !== '');
}

export function presetById(id: string): Preset | undefined {
  return PRESETS.find((p) => p.id === id);
}

/** The parameter object sent to the op. */
export function paramsOf(preset: Preset, values: Record<string, unknown>): Record<string, unknown> {
  const params: Record<string, unknown> = { ...preset.fixed };
  for (const p of preset.params) params[p.key] = values[p.key] ?? p.value;
  return params;
}
