// Scalar-field display: the field select in the bar, the color map written into each mesh's
// SCALAR_COLOR attribute (current and "before" geometry alike, over one shared range, so the
// comparison shows the change), and the legend.

import { BufferAttribute, type BufferGeometry } from 'three';
import { colorize, rangeOf } from './colormap';
import { Legend, scalarLabel } from './legend';
import { SCALAR_COLOR } from './materials';
import { scalarNames, type MeshState } from './model';

export class ScalarView {
  private states: MeshState[] = [];
  private active = false;

  constructor(
    private readonly select: HTMLSelectElement,
    private readonly legend: Legend,
    private readonly onChange: () => void,
  ) {
    select.addEventListener('change', () => this.refresh());
  }

  /** The scalar fields the meshes carry (file attributes and results). */
  names(): string[] {
    const names = new Set<string>();
    for (const s of this.states) for (const n of scalarNames(s.mesh.geometry)) names.add(n);
    return [...names].sort();
  }

  setStates(states: MeshState[]): void {
    this.states = states;
    this.refresh();
  }

  /** Shown in the legend and colored only while the view mode is 'scalar'. */
  setActive(active: boolean): void {
    this.active = active;
    this.refresh();
  }

  /** Picks a field (e.g. the one a run produced) and recolors. */
  choose(name: string): void {
    this.refresh(name);
  }

  refresh(prefer?: string): void {
    const names = this.names();
    const current = prefer && names.includes(prefer) ? prefer : names.includes(this.select.value) ? this.select.value : (names[0] ?? '');
    this.select.replaceChildren(
      ...(names.length ? names : ['']).map((n) => {
        const o = document.createElement('option');
        o.value = n;
        o.textContent = n ? scalarLabel(n) : 'none yet';
        return o;
      }),
    );
    this.select.value = current;
    this.select.disabled = names.length === 0;
    const geometries: BufferGeometry[] = [];
    for (const s of this.states) {
      geometries.push(s.mesh.geometry);
      if (s.before) geometries.push(s.before);
    }
    if (!current) {
      for (const g of geometries) g.deleteAttribute(SCALAR_COLOR);
      this.legend.hide();
      this.onChange();
      return;
    }
    const fields = geometries.map((g) => g.getAttribute(current)).filter((a) => a !== undefined).map((a) => a.array as Float32Array);
    const range = rangeOf(current, fields);
    for (const g of geometries) {
      const a = g.getAttribute(current);
      if (a) g.setAttribute(SCALAR_COLOR, new BufferAttribute(colorize(current, Float32Array.from(a.array as ArrayLike<number>), range), 3));
      else g.deleteAttribute(SCALAR_COLOR);
    }
    if (this.active) this.legend.show(current, range);
    else this.legend.hide();
    this.onChange();
  }
}
