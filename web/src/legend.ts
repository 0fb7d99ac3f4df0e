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

const format = (v: number) => (Math.abs(v) >= 1000 || (Math.abs(v) < 0.01 && v !== 0) ? v.toExponential(2) : v.toPrecision(3));

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
    const title = document.createElement('div');
    title.className = 'legend-title';
    title.textContent = range.kind === 'categorical' ? `${scalarLabel(name)} (${range.max + 1} labels)` : scalarLabel(name);
    const ramp = document.createElement('div');
    ramp.className = 'legend-ramp';
    ramp.style.background = cssGradient(range);
    const ends = document.createElement('div');
    ends.className = 'legend-ends';
    const low = document.createElement('span');
    const high = document.createElement('span');
    if (range.kind !== 'categorical') {
      low.textContent = format(range.min);
      high.textContent = format(range.max);
    }
    ends.append(low, high);
    this.element.append(title, ramp, ends);
    this.element.dataset.scalar = name;
    this.content = {
      title: title.textContent ?? '',
      low: low.textContent ?? '',
      high: high.textContent ?? '',
      ramp: Array.from({ length: 11 }, (_, i) =>
        range.kind === 'categorical' ? colorAt(range, i) : colorAt(range, range.min + ((range.max - range.min) * i) / 10),
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
