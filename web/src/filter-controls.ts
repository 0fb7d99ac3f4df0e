// The filter side of the page: Run / Cancel / Add noise / Revert / Export, the progress bar, the
// before/after comparison and the metrics of the last run. It owns the MeshStates of the model on
// screen; the loader side (app.ts) hands every new model over through setModel.

import type { Mesh } from 'three';
import type { LoadedModel } from './loaders';
import { chosenSummary } from './denoise-summary';
import { exportGlb, download, exportName } from './export';
import { meshStates, revert, scalarNames, type MeshState } from './model';
import type { ParameterPanel } from './panel';
import { NOISE, paramsOf, type Preset } from './presets';
import type { ProgressBar } from './progress-bar';
import { describeRunFailure, runOnMeshes, type ProgressEvent, type RunReport } from './runner';
import type { ScalarView } from './scalar-view';
import type { StatusLine } from './status';
import type { Viewer } from './viewer';
import type { ViewModeControl } from './view-mode-control';
import { GeoshiftError, type WorkerClient } from './worker/client';

export interface FilterElements {
  run: HTMLButtonElement;
  cancel: HTMLButtonElement;
  addNoise: HTMLButtonElement;
  noiseAmount: HTMLInputElement;
  revert: HTMLButtonElement;
  export: HTMLButtonElement;
  beforeToggle: HTMLInputElement;
  split: HTMLInputElement;
  splitLine: HTMLElement;
  metrics: HTMLElement;
}

const count = new Intl.NumberFormat('en-US');

/** What a run left: its report when it succeeded, its message when not, and its progress events. */
export interface RunLog {
  report: RunReport | null;
  error: string | null;
  progressEvents: ProgressEvent[];
}

export class FilterControls {
  private model: LoadedModel | null = null;
  private fileName = '';
  private states: MeshState[] = [];
  private busy = false;
  private cancelRequested = false;
  private noiseSeed = 1;
  /** What the error figure is measured against: the mesh before noise, or a clean original. */
  private referenceName = 'before noise';
  private log: RunLog = { report: null, error: null, progressEvents: [] };
  private current: Promise<void> = Promise.resolve();
  /** Takes a live preview off screen before what must not see it (revert, export, a new file). */
  previewGuard: (reason: 'revert' | 'export' | 'model') => void = () => undefined;
  /** Told when a run finished (null: failed or cancelled). */
  onFinished: (report: RunReport | null) => void = () => undefined;
  /** Told when a run starts (the live preview stops an analysis made ahead of time). */
  beforeRun: () => void = () => undefined;

  constructor(
    private readonly el: FilterElements,
    private readonly client: WorkerClient,
    private readonly panel: ParameterPanel,
    private readonly progress: ProgressBar,
    private readonly viewer: Viewer,
    private readonly viewMode: ViewModeControl,
    private readonly scalars: ScalarView,
    private readonly status: StatusLine,
  ) {
    el.run.addEventListener('click', () => void this.run(this.panel.preset(), this.panel.params()));
    el.addNoise.addEventListener('click', () => {
      const amount = Number(el.noiseAmount.value);
      void this.run(NOISE, paramsOf(NOISE, { amount: Number.isFinite(amount) ? amount : 0.5, seed: this.noiseSeed++ }));
    });
    el.cancel.addEventListener('click', () => {
      this.cancelRequested = true;
      this.client.cancel();
    });
    el.revert.addEventListener('click', () => this.revert());
    el.export.addEventListener('click', () => void this.exportFile());
    el.beforeToggle.addEventListener('change', () => this.updateComparison());
    el.split.addEventListener('input', () => this.updateComparison());
    this.updateButtons();
  }

  setModel(model: LoadedModel, fileName: string): void {
    this.previewGuard('model');
    for (const old of this.states) {
      old.before?.dispose();
      old.original.dispose();
      void this.client.free(old.id).catch(() => undefined);
    }
    this.model = model;
    this.fileName = fileName;
    this.referenceName = 'before noise';
    this.states = meshStates(model.meshes);
    this.el.beforeToggle.checked = false;
    this.el.split.value = '0';
    this.log.report = null;
    this.showMetrics(null);
    // The last file's "Done in 8.54 s" is not news about this one.
    this.progress.idle();
    this.scalars.setStates(this.states);
    this.panel.setScalarChoices(this.scalarChoices());
    this.updateComparison();
    this.updateButtons();
  }

  /**
   * Gives the clean original of the noisy meshes on screen (same vertices, same order): every run
   * then reports its error against it, as after Add noise. `name` completes "Error vs. …".
   */
  setReference(positions: Float32Array[], name: string): void {
    if (positions.length !== this.states.length) throw new Error(`the clean original has ${positions.length} meshes, the file ${this.states.length}`);
    this.states.forEach((state, i) => {
      const p = positions[i]!;
      const n = state.mesh.geometry.getAttribute('position').count;
      if (p.length !== 3 * n) throw new Error(`the clean original of mesh ${i + 1} has ${p.length / 3} vertices, the mesh ${n}`);
      state.reference = p;
      state.preNoise = p;
    });
    this.referenceName = name;
  }

  /** Resolves when no run is in progress. */
  idle(): Promise<void> {
    return this.current;
  }

  /** What the last run left (read by the test hooks, test-hooks.ts). */
  get runLog(): Readonly<RunLog> {
    return this.log;
  }

  /** The meshes of the file on screen, with their states (the live preview works on them). */
  meshStates(): MeshState[] {
    return this.states;
  }

  isBusy(): boolean {
    return this.busy;
  }

  meshes(): Mesh[] {
    return this.states.map((s) => s.mesh);
  }

  async exportBytes(): Promise<ArrayBuffer> {
    if (!this.model) throw new Error('no model is open');
    this.previewGuard('export');
    return exportGlb(this.model.root, this.model.meshes);
  }

  run(preset: Preset, params: Record<string, unknown>): Promise<void> {
    if (this.busy || this.states.length === 0) return this.current;
    this.beforeRun();
    this.busy = true;
    this.cancelRequested = false;
    this.log = { report: null, error: null, progressEvents: [] };
    const log = this.log;
    this.updateButtons();
    this.progress.start(preset.name);
    this.status.working(`${preset.name}: running on ${this.fileName}…`);
    const states = this.states;
    const task = async () => {
      try {
        const report = await runOnMeshes(this.client, states, preset, params, (event) => {
          log.progressEvents.push(event);
          this.progress.update(event.fraction, event.stage, event.stageFraction);
        }, () => this.cancelRequested);
        if (states !== this.states) return; // another file was opened meanwhile
        log.report = report;
        this.afterRun(preset, report, params);
        this.onFinished(report);
      } catch (error) {
        this.onFinished(null);
        log.error = describeRunFailure(error);
        this.progress.idle(log.error);
        // A cancel the person asked for is news, not a failure: no red, no warning sign.
        if (error instanceof GeoshiftError && error.kind === 'cancelled') this.status.done(`${preset.name}: ${log.error}`);
        else this.status.error(`${preset.name}: ${log.error}`);
      } finally {
        this.busy = false;
        this.updateButtons();
      }
    };
    this.current = task();
    return this.current;
  }

  private afterRun(preset: Preset, report: RunReport, params: Record<string, unknown>): void {
    const wantsSegments = params.segments === true;
    const seconds = (report.wallMs / 1000).toFixed(report.wallMs < 10_000 ? 2 : 1);
    this.progress.idle(`Done in ${seconds} s`);
    this.status.done(`${preset.name} done on ${this.fileName} in ${seconds} s`);
    this.showMetrics(report);
    this.viewMode.modelChanged(this.states.some((s) => s.mesh.geometry.getAttribute('color') !== undefined));
    this.panel.setScalarChoices(this.scalarChoices());
    const preferred = wantsSegments ? '_segment' : preset.showsScalar;
    const shown = preferred && report.scalars.includes(preferred) ? preferred : report.scalars[0];
    this.scalars.setStates(this.states);
    if (shown && preset.op !== 'noise') {
      this.scalars.choose(shown);
      this.viewMode.show('scalar');
    }
    // The distance field's zero: where its source vertex is (issue 30: it was unmarked).
    const source = preset.op === 'geodesic' ? this.states.find((s) => Number(params.source) < s.mesh.geometry.getAttribute('position').count) : undefined;
    this.viewer.setMarker(source ? { mesh: source.mesh, vertex: Number(params.source) } : null);
    this.viewer.geometryChanged();
    this.updateComparison();
  }

  private revert(): void {
    if (this.busy) return;
    this.previewGuard('revert');
    this.viewer.setMarker(null);
    for (const state of this.states) revert(state);
    this.scalars.setStates(this.states);
    this.viewer.geometryChanged();
    this.log.report = null;
    this.showMetrics(null);
    this.updateComparison();
    this.updateButtons();
    this.status.done(`${this.fileName}: back to the mesh as it was opened`);
  }

  private async exportFile(): Promise<void> {
    if (!this.model) return;
    try {
      download(await this.exportBytes(), exportName(this.fileName));
    } catch (error) {
      this.status.error(`Could not export: ${error instanceof Error ? error.message : String(error)}`);
    }
  }

  private scalarChoices(): string[] {
    const names = new Set<string>();
    for (const s of this.states) for (const n of scalarNames(s.mesh.geometry)) names.add(n);
    return [...names];
  }

  private updateComparison(): void {
    const before = new Map();
    for (const s of this.states) if (s.before) before.set(s.mesh, s.before);
    const split = Number(this.el.split.value) / 100;
    const splitting = before.size > 0 && split > 0;
    this.viewer.setComparison({ before, showBefore: this.el.beforeToggle.checked, split: splitting ? split : null });
    this.el.splitLine.hidden = !splitting;
    this.el.splitLine.style.left = `${split * 100}%`;
    this.el.beforeToggle.disabled = before.size === 0;
    this.el.split.disabled = before.size === 0;
  }

  private updateButtons(): void {
    const has = this.states.length > 0;
    const preset = this.panel.preset();
    this.el.run.disabled = this.busy || !has || !this.panel.isAvailable(preset);
    this.el.addNoise.disabled = this.busy || !has;
    this.el.cancel.disabled = !this.busy;
    this.el.revert.disabled = this.busy || !this.states.some((s) => s.before !== null);
    this.el.export.disabled = this.busy || !has;
    document.body.dataset.busy = String(this.busy);
  }

  /** Re-evaluates the Run button after the preset or the worker's op list changed. */
  refresh(): void {
    this.updateButtons();
  }

  private showMetrics(report: RunReport | null): void {
    const rows: Array<[string, string]> = [];
    if (!report) rows.push(['No run yet', '']);
    else {
      rows.push(['Filter', report.preset]);
      rows.push(['Time', `${(report.wallMs / 1000).toFixed(2)} s (${(report.computeMs / 1000).toFixed(2)} s computing)`]);
      rows.push(['Vertices', `${count.format(report.vertices)}${report.meshes > 1 ? ` in ${report.meshes} meshes` : ''}`]);
      if (report.iterations !== null) rows.push(iterationsRow(report.iterations));
      const estimate = report.stats.find((st) => typeof st.noiseLevel === 'number');
      if (estimate) {
        const level = (estimate.noiseLevel as number).toPrecision(2);
        rows.push(['Noise level', `${level} × AEL${estimate.noiseEstimated === 'yes' ? ' (measured on the mesh)' : ''}`]);
        const chosen = chosenSummary(estimate);
        if (chosen) rows.push(['Chosen', chosen]);
      }
      if (report.error) {
        const pct = (v: number) => `${((100 * v) / Math.max(report.error!.diagonal, 1e-30)).toFixed(3)}%`;
        rows.push([`Error vs. ${this.referenceName}`, `${report.error.rms.toPrecision(3)} RMS (${pct(report.error.rms)} of the size)`]);
        rows.push(['Noisy input had', `${report.error.inputRms.toPrecision(3)} RMS (${pct(report.error.inputRms)})`]);
      }
    }
    this.el.metrics.replaceChildren(
      ...rows.flatMap(([k, v]) => {
        const dt = document.createElement('dt');
        dt.textContent = k;
        const dd = document.createElement('dd');
        dd.textContent = v;
        return [dt, dd];
      }),
    );
  }
}

/** "Iterations 20", "Passes 10", or the mean of a mean shift ("7.8 per vertex", not "7.808"). */
function iterationsRow(iterations: NonNullable<RunReport['iterations']>): [string, string] {
  switch (iterations.kind) {
    case 'meanIterations':
      return ['Mean shift steps', `${iterations.value.toFixed(1)} per vertex on average`];
    case 'passes':
      return ['Passes', count.format(iterations.value)];
    default:
      return ['Iterations', count.format(iterations.value)];
  }
}
