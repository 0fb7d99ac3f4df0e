// Scalar fields as colors: a sequential map (viridis-like) for values of one sign, a diverging
// blue-white-red map centred on zero for values of both signs, and distinct hues for labels
// (segments, LiDAR classes). Ranges are clamped at the 2nd and 98th percentiles so that a few spikes
// do not wash out the rest; magnitudes (absolute curvature, distances, heights above ground) start
// at zero, so that a field that is never negative is never drawn as if it were.

export type MapKind = 'sequential' | 'diverging' | 'categorical';

export interface ScalarRange {
  kind: MapKind;
  min: number;
  max: number;
  /** The labels present, ascending (categorical only). */
  labels?: number[];
}

const VIRIDIS: Array<[number, number, number]> = [
  [0.267, 0.005, 0.329], [0.283, 0.141, 0.458], [0.254, 0.265, 0.53], [0.207, 0.372, 0.553],
  [0.164, 0.471, 0.558], [0.128, 0.567, 0.551], [0.135, 0.659, 0.518], [0.267, 0.749, 0.441],
  [0.478, 0.821, 0.318], [0.741, 0.873, 0.15], [0.993, 0.906, 0.144],
];
/** Color shown for "no value" (a geodesic distance beyond the radius). */
export const MISSING: [number, number, number] = [0.35, 0.35, 0.38];

function lerpStops(stops: Array<[number, number, number]>, t: number): [number, number, number] {
  const x = Math.min(1, Math.max(0, t)) * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(x));
  const f = x - i;
  const a = stops[i]!;
  const b = stops[i + 1]!;
  return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
}

const DIVERGING: Array<[number, number, number]> = [[0.23, 0.3, 0.75], [0.87, 0.87, 0.87], [0.71, 0.02, 0.15]];

/** Negative values of a distance field mean "not reached". */
export function isMissing(name: string, value: number): boolean {
  return !Number.isFinite(value) || (name === '_geodesic' && value < 0);
}

/** Labels, not quantities: segments found by a run, LiDAR classes. */
export function isCategorical(name: string): boolean {
  return name === '_segment' || /class/i.test(name);
}

/** Fields that are never negative by definition (a negative height above ground is a few cm of noise). */
function isMagnitude(name: string): boolean {
  return name === '_geodesic' || /height_above_ground|vegetation_height/i.test(name);
}

export function rangeOf(name: string, fields: Float32Array[]): ScalarRange {
  if (isCategorical(name)) {
    const seen = new Set<number>();
    for (const f of fields) for (const v of f) if (Number.isFinite(v) && seen.size <= 4096) seen.add(Math.round(v));
    const labels = [...seen].sort((a, b) => a - b);
    return { kind: 'categorical', min: labels[0] ?? 0, max: labels.at(-1) ?? 0, labels };
  }
  const values: number[] = [];
  for (const f of fields) for (const v of f) if (!isMissing(name, v)) values.push(v);
  if (values.length === 0) return { kind: 'sequential', min: 0, max: 1 };
  values.sort((a, b) => a - b);
  const at = (q: number) => values[Math.min(values.length - 1, Math.floor(q * (values.length - 1)))]!;
  let min = at(0.02);
  let max = at(0.98);
  // A curvature with no negative value (absolute, RMS) is a magnitude too; mean and Gaussian are not.
  const magnitude = isMagnitude(name) || (name === '_curvature' && values[0]! >= -1e-6 * Math.abs(values.at(-1)!));
  if (magnitude) min = 0;
  else if (min < 0 && max > 0) {
    const m = Math.max(-min, max);
    return { kind: 'diverging', min: -m, max: m };
  }
  if (max <= min) max = min + 1;
  return { kind: 'sequential', min, max };
}

export function colorAt(range: ScalarRange, value: number): [number, number, number] {
  if (range.kind === 'categorical') return labelColor(value);
  const t = (value - range.min) / (range.max - range.min);
  return lerpStops(range.kind === 'diverging' ? DIVERGING : VIRIDIS, t);
}

// The maps are defined in sRGB (as printed and as in the legend's CSS); three shades vertex colors
// in linear space.
const toLinear = (c: number) => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4);

/** Linear RGB per vertex for a scalar field. */
export function colorize(name: string, field: Float32Array, range: ScalarRange): Float32Array {
  const out = new Float32Array(field.length * 3);
  for (let i = 0; i < field.length; i++) {
    const v = field[i]!;
    const c = isMissing(name, v) ? MISSING : colorAt(range, v);
    out[3 * i] = toLinear(c[0]);
    out[3 * i + 1] = toLinear(c[1]);
    out[3 * i + 2] = toLinear(c[2]);
  }
  return out;
}

/** Golden-angle hues: neighbouring labels get clearly different colors. */
export function labelColor(label: number): [number, number, number] {
  const hue = (((Math.round(label) * 0.618034) % 1) + 1) % 1;
  return hsl(hue, 0.65, 0.55);
}

/** CSS gradient of the map, for the legend: one band per label when there are few. */
export function cssGradient(range: ScalarRange): string {
  const labels = range.labels ?? [];
  if (range.kind === 'categorical' && labels.length > 0 && labels.length <= 12) {
    const bands = labels.map((label, i) => {
      const [r, g, b] = labelColor(label);
      const color = `rgb(${Math.round(r * 255)} ${Math.round(g * 255)} ${Math.round(b * 255)})`;
      return `${color} ${((100 * i) / labels.length).toFixed(2)}% ${((100 * (i + 1)) / labels.length).toFixed(2)}%`;
    });
    return `linear-gradient(to right, ${bands.join(', ')})`;
  }
  const stops: string[] = [];
  for (let i = 0; i <= 10; i++) {
    const [r, g, b] = range.kind === 'categorical' ? hsl((i * 0.618034) % 1, 0.65, 0.55) : colorAt(range, range.min + ((range.max - range.min) * i) / 10);
    stops.push(`rgb(${Math.round(r * 255)} ${Math.round(g * 255)} ${Math.round(b * 255)}) ${i * 10}%`);
  }
  return `linear-gradient(to right, ${stops.join(', ')})`;
}

function hsl(h: number, s: number, l: number): [number, number, number] {
  const f = (n: number) => {
    const k = (n + h * 12) % 12;
    return l - s * Math.min(l, 1 - l) * Math.max(-1, Math.min(k - 3, 9 - k, 1));
  };
  return [f(0), f(8), f(4)];
}
