// The color legend of scalar-field mode: the field's name, the color ramp and its value range.

import { colorAt, cssGradient, type ScalarRange } from './colormap';

const LABELS: Record<string, string> = {
  _curvature: 'Curvature',
  _geodesic: 'Geodesic distance',
  _segment: 'Segments',
};

export function scalarLabel(name: string): string {
  return LABELS[name] ?? name.replace(/^_/, '').replace(/_/g, ' ');
}

// ASPRS LAS classes (LAS 1.4 specification, table 17), as LiDAR terrains carry them.
const LAS_CLASSES: Record<number, string> = {
  0: 'never classified', 1: 'unclassified', 2: 'ground', 3: 'low vegetation', 4: 'medium vegetation',
  5: 'high vegetation', 6: 'building', 7: 'low point', 9: 'water', 17: 'bridge deck',
};

/**
 * A legend end: three significant digits, and zero for what is round-off next to the range's
 * span (a field from 3e-7 to 40 starts at 0).
 */
export function formatEnd(v: number, span: number): string {
  if (v === 0 || Math.abs(v) < 1e-4 * Math.abs(span)) return '0';
  return Math.abs(v) >= 1e5 || Math.abs(v) < 1e-3 ? v.toExponential(2) : String(Number(v.toPrecision(3)));
}

/** What a label means: a LAS class name for class fields, else its number. */
function labelName(field: string, label: number): string {
  const name = /class/i.test(field) ? LAS_CLASSES[label] : undefined;
  return name ? `${label} ${name}` : String(label);
}

/** What the legend shows, for drawing it into a snapshot. */
export interface LegendContent {
  title: string;
  low: string;
  high: string;
  /** sRGB colors of the ramp from left to right, [0, 1] each. */
  ramp: Array<[number, number, number]>;
}

export class Legend {
  private content: LegendContent | null = null;

  constructor(private readonly element: HTMLElement) {
    element.hidden = true;
  }

  show(name: string, range: ScalarRange): void {
    this.element.hidden = false;
    this.element.replaceChildren();
    const labels = range.labels ?? [];
    const title = document.createElement('div');
    title.className = 'legend-title';
    title.textContent = range.kind === 'categorical' ? `${scalarLabel(name)} (${labels.length} ${labels.length === 1 ? 'label' : 'labels'})` : scalarLabel(name);
    const ramp = document.createElement('div');
    ramp.className = 'legend-ramp';
    ramp.style.background = cssGradient(range);
    const ends = document.createElement('div');
    ends.className = 'legend-ends';
    const low = document.createElement('span');
    const high = document.createElement('span');
    if (range.kind !== 'categorical') {
      low.textContent = formatEnd(range.min, range.max - range.min);
      high.textContent = formatEnd(range.max, range.max - range.min);
    } else if (labels.length <= 12) {
      // Few labels: each band is named under it (classes by their LAS name).
      ends.classList.add('legend-labels');
      ends.style.gridTemplateColumns = `repeat(${labels.length}, 1fr)`;
      ends.replaceChildren(...labels.map((label) => {
        const span = document.createElement('span');
        span.textContent = labelName(name, label);
        return span;
      }));
    }
    if (!ends.classList.contains('legend-labels')) ends.append(low, high);
    this.element.append(title, ramp, ends);
    this.element.dataset.scalar = name;
    this.element.dataset.min = String(range.min);
    this.element.dataset.max = String(range.max);
    this.element.dataset.kind = range.kind;
    this.content = {
      title: title.textContent ?? '',
      low: range.kind === 'categorical' ? labelName(name, range.min) : low.textContent ?? '',
      high: range.kind === 'categorical' ? labelName(name, range.max) : high.textContent ?? '',
      ramp: Array.from({ length: 11 }, (_, i) =>
        range.kind === 'categorical'
          ? colorAt(range, labels.length ? labels[Math.min(labels.length - 1, Math.floor((i * labels.length) / 11))]! : i)
          : colorAt(range, range.min + ((range.max - range.min) * i) / 10),
      ),
    };
  }

  hide(): void {
    this.element.hidden = true;
    this.content = null;
  }

  /** The legend on screen, or null when hidden. */
  shown(): LegendContent | null {
    return this.element.hidden ? null : this.content;
  }
}
