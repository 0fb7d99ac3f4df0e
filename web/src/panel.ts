// The side panel's parameter part: the preset select and a lil-gui folder with every parameter of
// the chosen preset, each with its unit and a plain-words tooltip. Values are kept per preset, so
// switching back and forth keeps what the user typed.

import GUI from 'lil-gui';
import type { CorePreset } from 'geoshift';
import { PRESETS, applyCorePresets, hasValues, paramsOf, presetById, type Param, type Preset } from './presets';
import { scalarLabel } from './legend';
import { HEIGHT } from './runner';
import { orderSignals } from './signal-order';

/**
 * A change in the panel: another preset; a slider being dragged ('slide') and let go ('release');
 * a number being typed ('input') and settled, or a choice picked ('commit').
 */
export type PanelChange = 'preset' | 'slide' | 'release' | 'input' | 'commit';

export class ParameterPanel {
  private gui: GUI | null = null;
  private readonly listeners: Array<(change: PanelChange) => void> = [];
  /** A lil-gui slider is held (pointer down on it until its change finishes). */
  private sliding = false;
  private readonly values = new Map<string, Record<string, unknown>>();
  private available: Set<string> | null = null;
  /** Extra choices for presets that read a named scalar (Terrain): the mesh's scalar attributes. */
  private scalarChoices: string[] = [];

  constructor(
    private readonly select: HTMLSelectElement,
    private readonly summary: HTMLElement,
    private readonly container: HTMLElement,
    private readonly onChange: () => void = () => undefined,
  ) {
    for (const preset of PRESETS) {
      const option = document.createElement('option');
      option.value = preset.id;
      option.textContent = preset.name;
      option.title = preset.summary;
      select.append(option);
    }
    select.addEventListener('change', () => {
      this.build();
      this.onChange();
      this.notify('preset');
    });
    const grab = (event: Event) => {
      this.sliding = event.target instanceof Element && event.target.closest('.lil-slider') !== null;
    };
    container.addEventListener('pointerdown', grab, { capture: true });
    container.addEventListener('touchstart', grab, { capture: true, passive: true });
    this.build();
  }

  preset(): Preset {
    return presetById(this.select.value) ?? PRESETS[0]!;
  }

  /** The parameter object for the op, with the user's values. */
  params(): Record<string, unknown> {
    const preset = this.preset();
    const values = this.valuesOf(preset);
    const params = paramsOf(preset, values);
    if (preset.needsScalar) params.signal = values.signal;
    return params;
  }

  /** Marks presets whose op this build of the module lacks; selects the first usable one if needed. */
  setAvailableOps(ops: string[]): void {
    this.available = new Set(ops);
    for (const option of this.select.options) {
      const preset = presetById(option.value);
      const ok = !preset || this.available.has(preset.op);
      option.disabled = !ok;
      option.textContent = `${preset?.name ?? option.value}${ok ? '' : ' (not in this build yet)'}`;
    }
    if (this.select.selectedOptions[0]?.disabled) {
      const first = [...this.select.options].find((o) => !o.disabled);
      if (first) this.select.value = first.value;
    }
    this.build();
  }

  isAvailable(preset: Preset): boolean {
    return hasValues(preset) && (!this.available || this.available.has(preset.op));
  }

  /** Takes the filter presets' values from the module (they are the core's: one table for all). */
  setCorePresets(core: CorePreset[]): void {
    applyCorePresets(core);
    for (const preset of PRESETS) if (preset.core) this.values.delete(preset.id);
    this.build();
  }

  setScalarChoices(names: string[]): void {
    this.scalarChoices = names;
    if (this.preset().needsScalar) this.build();
  }

  /** Sets one parameter of the current preset (Alt+click picks the geodesic source). */
  set(key: string, value: unknown): void {
    this.valuesOf(this.preset())[key] = value;
    this.gui?.controllersRecursive().forEach((c) => c.updateDisplay());
    this.notify('commit');
  }

  /** Told about every change (the URL and the live preview follow the panel). */
  listen(listener: (change: PanelChange) => void): void {
    this.listeners.push(listener);
  }

  /**
   * Selects a preset and sets its values (a shared link, a gallery case, back/forward) without
   * telling the listeners: the caller restores a state, it does not make a new one. False when the
   * preset is unknown or unavailable in this build.
   */
  restore(presetId: string, values: Record<string, unknown>): boolean {
    const preset = presetById(presetId);
    if (!preset || !this.isAvailable(preset)) return false;
    Object.assign(this.valuesOf(preset), values);
    if (this.select.value !== presetId) {
      this.select.value = presetId;
      this.build();
      this.onChange();
    } else {
      this.gui?.controllersRecursive().forEach((c) => c.updateDisplay());
    }
    return true;
  }

  /** The values of the current preset as the panel shows them (signal included). */
  currentValues(): Record<string, unknown> {
    return { ...this.valuesOf(this.preset()) };
  }

  private notify(change: PanelChange): void {
    for (const listener of this.listeners) listener(change);
  }

  /** Heights first, categories last (signal-order.ts); the first is the default. */
  private signalChoices(): string[] {
    return orderSignals(this.scalarChoices, HEIGHT);
  }

  private valuesOf(preset: Preset): Record<string, unknown> {
    let values = this.values.get(preset.id);
    if (!values) {
      values = Object.fromEntries(preset.params.map((p) => [p.key, p.value]));
      this.values.set(preset.id, values);
    }
    if (preset.needsScalar && !this.signalChoices().includes(values.signal as string)) values.signal = this.signalChoices()[0];
    return values;
  }

  private build(): void {
    this.gui?.destroy();
    const preset = this.preset();
    this.summary.textContent = this.isAvailable(preset)
      ? preset.summary
      : !hasValues(preset)
        ? `${preset.summary} Its settings arrive with the filters, which are starting.`
        : `${preset.summary} This build of the WebAssembly module does not include the "${preset.op}" operation yet.`;
    if (!hasValues(preset)) {
      this.gui = null;
      return;
    }
    const values = this.valuesOf(preset);
    const gui = new GUI({ container: this.container, title: `${preset.name} parameters`, width: 300 });
    if (preset.needsScalar) {
      // Shown in words, as the legend and the Field select name them ("height above ground").
      const choices = Object.fromEntries(this.signalChoices().map((n) => [n === HEIGHT ? 'height (along the thinnest axis)' : scalarLabel(n), n]));
      const c = gui.add(values, 'signal', choices).name('Attribute to filter');
      c.domElement.title = 'The per-vertex value to smooth: one from the file, or the height of each vertex along the mesh\'s thinnest axis.';
      c.domElement.dataset.param = 'signal';
    }
    for (const param of preset.params.filter((p) => !p.expert)) addController(gui, values, param);
    const expertParams = preset.params.filter((p) => p.expert);
    if (expertParams.length) {
      const folder = gui.addFolder('Expert settings');
      for (const param of expertParams) addController(folder, values, param);
      folder.close();
    }
    // Changes in the folder reach the GUI's handlers too (lil-gui passes them up).
    gui.onChange(() => this.notify(this.sliding ? 'slide' : 'input'));
    gui.onFinishChange(() => {
      const released = this.sliding;
      this.sliding = false;
      this.notify(released ? 'release' : 'commit');
    });
    this.gui = gui;
  }
}

function addController(gui: GUI, values: Record<string, unknown>, param: Param): void {
  let controller;
  switch (param.kind) {
    case 'number':
      controller = gui.add(values, param.key, param.min, param.max, param.step).name(param.unit ? `${param.label} (${param.unit})` : param.label);
      break;
    case 'choice':
      controller = gui.add(values, param.key, param.options).name(param.label);
      break;
    case 'flag':
      controller = gui.add(values, param.key).name(param.label);
      break;
  }
  controller.domElement.title = param.tooltip;
  controller.domElement.dataset.param = param.key;
}
