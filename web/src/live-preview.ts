// Live preview: while a parameter slider is dragged, the preset's op runs on
// a coarse wavelet level of each mesh (the module's `preview`, at most PREVIEW_SIZES vertices,
// analysed once per mesh and level and kept in the worker) and the result is shown at once; when
// the slider is released the full-resolution run starts and its
// result replaces the preview. Only the newest change matters: a preview still running when
// another change comes is finished and shown, and the newest value runs next; a release, another
// preset or another file stops it (threaded build) or drops its result.
// The Result section says which one is on screen (the `result-kind` element).

import type { FilterControls } from './filter-controls';
import { applyOutput, baseGeometry, dropPreview, meshArrays, type MeshState } from './model';
import type { ParameterPanel } from './panel';
import { costPerVertex } from './preview-cost';
import type { Preset } from './presets';
import { HEIGHT, heightOf } from './runner';
import type { ScalarView } from './scalar-view';
import type { Viewer } from './viewer';
import type { ViewModeControl } from './view-mode-control';
import type { RunOutput, WorkerClient } from './worker/client';

/**
 * Sizes of the coarse level, largest first. A preset's first preview takes the largest that its
 * cost guess (costPerVertex) fits in the budget and that holds at most MAX_SHARE of the mesh; one
 * slower than TARGET_MS moves its preset to a smaller level (adapt).
 */
export const PREVIEW_SIZES = [25_000, 12_000, 6_000, 3_000, 1_500, 750];
const TARGET_MS = 200;
/** Share of TARGET_MS the op itself may take; the rest brings the result back and draws it. */
const OP_SHARE = 0.6;
/**
 * A preview's level holds at most this share of the mesh. The first preview used to run on the
 * whole mesh (a level of 25,000 vertices for a 13,971-vertex mesh), a full run in disguise that
 * showed nothing for seconds (issue 30).
 */
const MAX_SHARE = 1 / 3;
/**
 * Meshes up to this size get their coarse level analysed when they are opened, so that the first
 * drag only runs the op (the analysis costs ~15 µs a vertex, bench/wasm/preview.mjs).
 */
const WARM_UP_VERTICES = 200_000;

/** Ops whose parameters mean the same on a coarser mesh (not a vertex index, as geodesic's source). */
const PREVIEWABLE = new Set(['filter', 'denoise', 'smooth', 'curvature']);

export type ResultKind = 'none' | 'computing' | 'preview' | 'full';

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
  /** this.generation when asked: a commit, a drop or a new file makes the preview worthless. */
  generation: number;
}

export class LivePreview {
  /** Counts changes: the newest value is the one to preview next. */
  private ticket = 0;
  /** Counts what makes previews in flight worthless (a commit, a drop, a new file). */
  private generation = 0;
  private wanted: Wanted | null = null;
  private running: Promise<void> | null = null;
  /** The analysis of the coarse level made ahead of the first drag (warmUp), while it runs. */
  private warming: Promise<void> | null = null;
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
      else if (change === 'preset') {
        this.drop();
        this.warmUp();
      }
    });
    parts.filters.previewGuard = (reason) => {
      this.drop();
      if (reason === 'model') {
        this.sizeIndex.clear();
        // After setModel has the new meshes in place.
        setTimeout(() => this.warmUp(), 0);
      }
      // After a revert or with a new file, no result is on screen any more.
      if (reason !== 'export') this.settled = { kind: 'none', text: '' };
      this.setKind(this.settled.kind, this.settled.text);
    };
    // A run waits for the worker: an analysis ahead of time gives way to it (threaded build).
    parts.filters.beforeRun = () => {
      if (this.warming) parts.client.stopPreview();
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
    while (this.running || this.warming) await (this.running ?? this.warming);
  }

  /**
   * Analyses the coarse level the current preset's previews will use, while nothing else runs, so
   * that the first drag only runs the op on it (the analysis is kept with the worker's preview
   * session, wasm/preview.cpp). Meshes above WARM_UP_VERTICES wait for the first drag.
   */
  private warmUp(): void {
    const preset = this.parts.panel.preset();
    const states = this.parts.filters.meshStates();
    if (this.warming || this.running || !this.active(preset) || this.parts.filters.isBusy()) return;
    if (vertexCount(states) > WARM_UP_VERTICES) return;
    const params = this.parts.panel.params();
    const size = this.levelSize(preset, params);
    // Every level from the largest a preview may use down to this preset's, one analysis of the
    // previous level's coarse mesh each, so that adapt() can move either way at no cost.
    const cap = MAX_SHARE * vertexCount(states);
    const sizes = PREVIEW_SIZES.filter((s) => s >= size && s <= cap);
    if (sizes.length === 0) sizes.push(size);
    this.warming = (async () => {
      for (const state of states) {
        for (const s of sizes) {
          if (states !== this.parts.filters.meshStates() || this.parts.filters.isBusy()) return;
          await this.ensureLoaded(state, params);
          // Taubin with no step: the analysis and the way back, nothing else.
          await this.parts.client.preview(previewId(state), 'smooth', { iterations: 0 }, s);
        }
      }
      // The preset's own op once, not shown: the browser compiles a WebAssembly function fully
      // only after its first calls (the first preview of the denoiser took 250 ms, the next ones
      // 100), and its time picks the level before the first drag (adapt).
      const started = performance.now();
      const outputs: RunOutput[] = [];
      for (const state of states) {
        if (states !== this.parts.filters.meshStates() || this.parts.filters.isBusy()) return;
        outputs.push(await this.parts.client.preview(previewId(state), preset.op, params, this.levelSize(preset, params)));
      }
      this.adapt(preset.id, outputs, performance.now() - started);
    })()
      .catch(() => undefined)
      .finally(() => {
        this.warming = null;
        // A drag that came meanwhile waited for the analysis.
        if (this.wanted && !this.running) this.start();
      });
  }

  /** The coarse level's size for a preset: measured by its last preview, else guessed. */
  private levelSize(preset: Preset, params: Record<string, unknown>): number {
    let index = this.sizeIndex.get(preset.id);
    if (index === undefined) {
      const budget = (OP_SHARE * TARGET_MS * 1000) / costPerVertex(preset.op, params);
      const cap = MAX_SHARE * vertexCount(this.parts.filters.meshStates());
      index = PREVIEW_SIZES.findIndex((size) => size <= budget && size <= cap);
      if (index < 0) index = PREVIEW_SIZES.length - 1;
      this.sizeIndex.set(preset.id, index);
    }
    return PREVIEW_SIZES[index]!;
  }

  private active(preset: Preset): boolean {
    return this.parts.enabled.checked && PREVIEWABLE.has(preset.op) && this.parts.panel.isAvailable(preset) && this.parts.filters.meshStates().length > 0;
  }

  /** A parameter is moving: preview it (the newest change wins). */
  private request(): void {
    const preset = this.parts.panel.preset();
    if (!this.active(preset)) return;
    this.wanted = { preset, params: this.parts.panel.params(), ticket: ++this.ticket, generation: this.generation };
    // Said where the person looks (the view's status) until the first preview of this change shows.
    if (this.parts.kind.dataset.kind !== 'preview') this.setKind('computing', 'computing preview…');
    // A preview in flight finishes and the newest value runs next: stopping it at every step of a
    // drag (a step every ~16 ms, a preview ~100 ms) showed nothing until the pointer paused.
    if (this.warming || this.running) return;
    this.start();
  }

  private start(): void {
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
    this.generation++;
    if (this.running) this.parts.client.stopPreview();
    // After the preview in flight (the worker runs one request at a time anyway).
    void this.idle().then(() => this.parts.filters.run(preset, this.parts.panel.params()));
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
          outputs.push(await this.parts.client.preview(previewId(state), job.preset.op, job.params, this.levelSize(job.preset, job.params)));
          if (job.generation !== this.generation) break;
        }
        // A newer value waiting does not make this one worthless: it is newer than what is on
        // screen, and the newer one runs next.
        if (job.generation !== this.generation || states !== this.parts.filters.meshStates() || this.parts.filters.isBusy()) continue;
        const ms = performance.now() - started;
        this.adapt(job.preset.id, outputs, ms);
        this.show(job, states, outputs, ms);
      } catch (error) {
        // A stopped preview is superseded by a newer one; a failing one says why where a run would.
        if (job.generation === this.generation && !(error instanceof Error && /cancel/i.test(error.message))) {
          this.setKind('none', `preview failed: ${error instanceof Error ? error.message : String(error)}`);
        } else if (job.generation === this.generation && this.parts.kind.dataset.kind === 'computing') {
          this.setKind(this.settled.kind, this.settled.text);
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
    this.events.push({ kind: "preview", at: performance.now(), vertices: coarse, ms });
  }

  /**
   * Picks the preset's coarse level for the next previews from how long this one took. The op's
   * share grows with the coarse vertex count; the rest (bringing the result back to every vertex,
   * drawing it) does not. A level too slow for TARGET_MS gives way to the largest one that fits; a
   * level that leaves room moves up one, at most MAX_SHARE of the mesh, when the next one would still
   * fit with a fifth to spare (the warm-up analysed the levels in between, so this is quick; only a
   * mesh above WARM_UP_VERTICES analyses on the way).
   */
  private adapt(presetId: string, outputs: RunOutput[], ms: number): void {
    const sum = (key: string) => outputs.reduce((t, o) => t + Number(o.stats[key] ?? 0), 0);
    const opMs = sum('coarseOpMs');
    const vertices = Math.max(sum('previewVertices'), 1);
    const fixedMs = Math.max(ms - sum('analysisMs') - opMs, 0);
    const perVertex = opMs / vertices;
    const budget = Math.max(TARGET_MS - fixedMs, TARGET_MS / 2);
    const index = this.sizeIndex.get(presetId) ?? PREVIEW_SIZES.length - 1;
    if (PREVIEW_SIZES[index]! * perVertex > budget) {
      const fits = PREVIEW_SIZES.findIndex((size) => size * perVertex <= budget);
      this.sizeIndex.set(presetId, fits < 0 ? PREVIEW_SIZES.length - 1 : Math.max(fits, index));
      return;
    }
    const larger = PREVIEW_SIZES[index - 1];
    const cap = MAX_SHARE * vertexCount(this.parts.filters.meshStates());
    if (larger !== undefined && larger <= cap && larger * perVertex <= 0.8 * budget) this.sizeIndex.set(presetId, index - 1);
  }

  private hasPreview(): boolean {
    return this.parts.filters.meshStates().some((s) => s.previewBase !== null);
  }

  /** Takes the preview off screen (another preset, revert, export, a new file). */
  drop(): void {
    this.wanted = null;
    this.ticket++;
    this.generation++;
    if (this.parts.kind.dataset.kind === 'computing') this.setKind(this.settled.kind, this.settled.text);
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

function vertexCount(states: MeshState[]): number {
  return states.reduce((t, s) => t + baseGeometry(s).getAttribute('position').count, 0);
}

function previewId(state: MeshState): string {
  return `preview:${state.id}`;
}
