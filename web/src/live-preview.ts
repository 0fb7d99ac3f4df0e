// Live preview: while a parameter slider is dragged, the preset's op runs on
// a coarse wavelet level of each mesh (the module's `preview`, at most PREVIEW_SIZES vertices,
// analysed once per mesh and level and kept in the worker) and the result is shown at once; when
// the slider is released the full-resolution run starts and its
// result replaces the preview. Only the newest change matters: a preview still running when
// another change comes is stopped (threaded build) or its result dropped, and the newest runs next.
// The Result section says which one is on screen (the `result-kind` element).

import type { FilterControls } from './filter-controls';
import { applyOutput, baseGeometry, dropPreview, meshArrays, type MeshState } from './model';
import type { ParameterPanel } from './panel';
import type { Preset } from './presets';
import { HEIGHT, heightOf } from './runner';
import type { ScalarView } from './scalar-view';
import type { Viewer } from './viewer';
import type { ViewModeControl } from './view-mode-control';
import type { WorkerClient } from './worker/client';
import type { RunOutput } from './worker/protocol';

/**
 * Sizes of the coarse level, largest first. A preview starts at the first; one slower than
 * TARGET_MS moves its preset to a smaller level (the mean shift with a wide neighbourhood costs
 * ~80 µs a vertex on 2 cores, Taubin ~0.5 µs: bench/wasm/preview.mjs).
 */
export const PREVIEW_SIZES = [25_000, 12_000, 6_000, 3_000];
const TARGET_MS = 200;

/** Ops whose parameters mean the same on a coarser mesh (not a vertex index, as geodesic's source). */
const PREVIEWABLE = new Set(['filter', 'denoise', 'smooth', 'curvature']);

export type ResultKind = 'none' | 'preview' | 'full';

export interface PreviewEvent {
  kind: 'preview' | 'full';
  /** performance.now() when it was put on screen. */
  at: number;
  /** Vertices the op ran on (the coarse level for a preview). */
  vertices: number;
  ms: number;
}

export interface LivePreviewParts {
  client: WorkerClient;
  filters: FilterControls;
  panel: ParameterPanel;
  viewer: Viewer;
  scalars: ScalarView;
  viewMode: ViewModeControl;
  /** Says "preview" or "full result" (data-kind: none | preview | full). */
  kind: HTMLElement;
  /** The "Live preview" checkbox. */
  enabled: HTMLInputElement;
}

interface Wanted {
  preset: Preset;
  params: Record<string, unknown>;
  ticket: number;
}

export class LivePreview {
  private ticket = 0;
  private wanted: Wanted | null = null;
  private running: Promise<void> | null = null;
  /** Worker mesh ids of the preview sessions, with the attributes they were loaded from. */
  private readonly loaded = new Map<string, unknown[]>();
  private loadedStates: MeshState[] = [];
  /** What is on screen when no preview is: the last full result, or nothing. */
  private settled: { kind: ResultKind; text: string } = { kind: 'none', text: '' };
  /** Per preset: the index in PREVIEW_SIZES its previews use. */
  private readonly sizeIndex = new Map<string, number>();
  /** For the tests: every preview and full result put on screen. */
  readonly events: PreviewEvent[] = [];

  constructor(private readonly parts: LivePreviewParts) {
    parts.panel.listen((change) => {
      if (change === 'slide') this.request();
      else if (change === 'release') this.commit();
      // A value typed and entered, a choice picked: a change like a drag and its release (issue 30:
      // a typed value showed nothing until Run). The keystrokes before it are values nobody asked
      // to see.
      else if (change === 'commit') this.settle();
      else if (change === 'preset') this.drop();
    });
    parts.filters.previewGuard = (reason) => {
      this.drop();
      if (reason === 'model') this.sizeIndex.clear();
      // After a revert or with a new file, no result is on screen any more.
      if (reason !== 'export') this.settled = { kind: 'none', text: '' };
      this.setKind(this.settled.kind, this.settled.text);
    };
    parts.filters.onFinished = (report) => {
      if (!report) return;
      this.settled = { kind: 'full', text: `full result (${report.vertices.toLocaleString('en-US')} vertices)` };
      this.setKind(this.settled.kind, this.settled.text);
      this.events.push({ kind: 'full', at: performance.now(), vertices: report.vertices, ms: report.wallMs });
    };
    parts.enabled.addEventListener('change', () => {
      if (!parts.enabled.checked) this.drop();
    });
    this.setKind('none', '');
  }

  /** Resolves when no preview is being computed. */
  async idle(): Promise<void> {
    while (this.running) await this.running;
  }

  private active(preset: Preset): boolean {
    return this.parts.enabled.checked && PREVIEWABLE.has(preset.op) && this.parts.panel.isAvailable(preset) && this.parts.filters.meshStates().length > 0;
  }

  /** A parameter is moving: preview it (the newest change wins). */
  private request(): void {
    const preset = this.parts.panel.preset();
    if (!this.active(preset)) return;
    this.wanted = { preset, params: this.parts.panel.params(), ticket: ++this.ticket };
    if (this.running) {
      this.parts.client.stopPreview();
      return;
    }
    this.running = this.work().finally(() => {
      this.running = null;
    });
  }

  /** A value set in one step: its preview first, then the full run. */
  private settle(): void {
    this.request();
    const ticket = this.ticket;
    void (this.running ?? Promise.resolve()).then(() => {
      if (ticket === this.ticket) this.commit();
    });
  }

  /** A parameter settled: the full run (it replaces the preview when it is done). */
  private commit(): void {
    const preset = this.parts.panel.preset();
    if (!this.active(preset) && !(this.parts.enabled.checked && this.hasPreview())) return;
    this.wanted = null;
    this.ticket++;
    if (this.running) this.parts.client.stopPreview();
    // After the preview in flight (the worker runs one request at a time anyway).
    void (this.running ?? Promise.resolve()).then(() => this.parts.filters.run(preset, this.parts.panel.params()));
  }

  private async work(): Promise<void> {
    while (this.wanted) {
      const job = this.wanted;
      this.wanted = null;
      // A full run owns the worker and the meshes; a preview after it would show stale settings.
      if (this.parts.filters.isBusy()) return;
      const states = this.parts.filters.meshStates();
      try {
        const started = performance.now();
        const outputs: RunOutput[] = [];
        for (const state of states) {
          await this.ensureLoaded(state, job.params);
          outputs.push(await this.parts.client.preview(previewId(state), job.preset.op, job.params, PREVIEW_SIZES[this.sizeIndex.get(job.preset.id) ?? 0]!));
          if (job.ticket !== this.ticket) break;
        }
        if (job.ticket !== this.ticket || states !== this.parts.filters.meshStates() || this.parts.filters.isBusy()) continue;
        const ms = performance.now() - started;
        this.adapt(job.preset.id, outputs, ms);
        this.show(job, states, outputs, ms);
      } catch (error) {
        // A stopped preview is superseded by a newer one; a failing one says why where a run would.
        if (job.ticket === this.ticket && !(error instanceof Error && /cancel/i.test(error.message))) {
          this.setKind('none', `preview failed: ${error instanceof Error ? error.message : String(error)}`);
        }
      }
    }
  }

  /** Loads the mesh's own geometry into its preview session when it changed since the last load. */
  private async ensureLoaded(state: MeshState, params: Record<string, unknown>): Promise<void> {
    if (this.loadedStates !== this.parts.filters.meshStates()) {
      for (const id of this.loaded.keys()) void this.parts.client.free(id).catch(() => undefined);
      this.loaded.clear();
      this.loadedStates = this.parts.filters.meshStates();
    }
    const geometry = baseGeometry(state);
    const signature = Object.values(geometry.attributes);
    const needsHeight = params.signal === HEIGHT;
    const known = this.loaded.get(previewId(state));
    if (known && known.length === signature.length + 1 && known.every((a, i) => a === [...signature, needsHeight][i])) return;
    const arrays = meshArrays(geometry);
    if (needsHeight && !arrays.scalars[HEIGHT]) arrays.scalars[HEIGHT] = heightOf(arrays.positions);
    await this.parts.client.load(previewId(state), arrays);
    this.loaded.set(previewId(state), [...signature, needsHeight]);
  }

  private show(job: Wanted, states: MeshState[], outputs: RunOutput[], ms: number): void {
    const { viewer, scalars, viewMode } = this.parts;
    states.forEach((state, i) => {
      const output = outputs[i]!;
      const base = baseGeometry(state);
      if (state.previewBase) state.mesh.geometry.dispose();
      state.previewBase = base;
      state.mesh.geometry = base.clone();
      applyOutput(state, output, job.preset.replacesColors === true);
    });
    viewMode.modelChanged(states.some((s) => s.mesh.geometry.getAttribute('color') !== undefined));
    scalars.setStates(states);
    const names = [...new Set(outputs.flatMap((o) => Object.keys(o.scalars).map((n) => n.toLowerCase())))];
    const preferred = job.params.segments === true ? '_segment' : job.preset.showsScalar;
    const shown = preferred && names.includes(preferred) ? preferred : names[0];
    if (shown) {
      scalars.choose(shown);
      viewMode.show('scalar');
    }
    viewer.geometryChanged();
    const coarse = outputs.reduce((t, o) => t + Number(o.stats.previewVertices ?? o.stats.vertices), 0);
    this.setKind('preview', `preview (coarse level, ${coarse.toLocaleString('en-US')} vertices, ${ms.toFixed(0)} ms)`);
    this.events.push({ kind: 'preview', at: performance.now(), vertices: coarse, ms });
  }

  /**
   * Picks the preset's coarse level for the next previews from how long this one took. The op's
   * share grows with the coarse vertex count; the rest (bringing the result back to every vertex,
   * drawing it) does not. Levels only go down, and only for the file on screen (a smaller level
   * analyses the kept coarse mesh further, which is quick; the first analysis of a large mesh is
   * not: ~15 s for 1M vertices, bench/wasm/preview.mjs).
   */
  private adapt(presetId: string, outputs: RunOutput[], ms: number): void {
    const sum = (key: string) => outputs.reduce((t, o) => t + Number(o.stats[key] ?? 0), 0);
    const opMs = sum('coarseOpMs');
    const vertices = Math.max(sum('previewVertices'), 1);
    const fixedMs = Math.max(ms - sum('analysisMs') - opMs, 0);
    const perVertex = opMs / vertices;
    const budget = Math.max(TARGET_MS - fixedMs, TARGET_MS / 2);
    const index = this.sizeIndex.get(presetId) ?? 0;
    if (PREVIEW_SIZES[index]! * perVertex <= budget) return;
    const fits = PREVIEW_SIZES.findIndex((size) => size * perVertex <= budget);
    this.sizeIndex.set(presetId, fits < 0 ? PREVIEW_SIZES.length - 1 : Math.max(fits, index));
  }

  private hasPreview(): boolean {
    return this.parts.filters.meshStates().some((s) => s.previewBase !== null);
  }

  /** Takes the preview off screen (another preset, revert, export, a new file). */
  drop(): void {
    this.wanted = null;
    this.ticket++;
    if (!this.hasPreview()) return;
    const states = this.parts.filters.meshStates();
    for (const state of states) dropPreview(state);
    this.parts.scalars.setStates(states);
    this.parts.viewer.geometryChanged();
    this.setKind(this.settled.kind, this.settled.text);
  }

  private setKind(kind: ResultKind, text: string): void {
    this.parts.kind.dataset.kind = kind;
    this.parts.kind.textContent = text || (kind === 'none' ? 'Nothing computed yet' : '');
  }
}

function previewId(state: MeshState): string {
  return `preview:${state.id}`;
}
