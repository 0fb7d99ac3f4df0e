// The view mode <select>: shaded, vertex colors, scalar field, wireframe.

import { isViewMode, type ViewMode } from './materials';
import type { Viewer } from './viewer';

export class ViewModeControl {
  private readonly colorsOption: HTMLOptionElement | null;

  constructor(
    private readonly select: HTMLSelectElement,
    private readonly viewer: Viewer,
    /** Told about every mode change (the scalar legend shows only in scalar mode). */
    private readonly onMode: (mode: ViewMode) => void = () => undefined,
  ) {
    this.colorsOption = select.querySelector<HTMLOptionElement>('option[value="colors"]');
    select.addEventListener('change', () => this.apply());
    this.apply();
  }

  /**
   * Follows what a new model offers: a model with vertex colors is shown in color (the colors are
   * usually why it was opened), and 'colors' is unavailable for one without. Wireframe stays.
   */
  modelChanged(hasVertexColors: boolean): void {
    if (this.colorsOption) this.colorsOption.disabled = !hasVertexColors;
    const mode = this.mode();
    if (hasVertexColors && mode === 'shaded') this.set('colors');
    else if (!hasVertexColors && mode === 'colors') this.set('shaded');
  }

  /** Switches to a mode (after a run that produced a scalar field, to show it). */
  show(mode: ViewMode): void {
    this.set(mode);
  }

  private mode(): ViewMode {
    return isViewMode(this.select.value) ? this.select.value : 'shaded';
  }

  private set(mode: ViewMode): void {
    this.select.value = mode;
    this.apply();
  }

  private apply(): void {
    const mode = this.mode();
    this.viewer.setViewMode(mode);
    this.onMode(mode);
  }
}
