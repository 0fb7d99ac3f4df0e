// Wiring only: find the page's elements, create the parts, connect them, open the first mesh.
// start() names the steps; each step is a function below.

import './style.css';
import { App } from './app';
import { installDropZone } from './dropzone';
import { Gallery } from './gallery';
import { decodeState, HashSync } from './hash-state';
import { installShortcuts } from './keyboard';
import { LivePreview } from './live-preview';
import { installSheet } from './sheet';
import { saveBlob } from './export';
import { snapshotName, snapshotPng } from './snapshot';
import { axisVector, UpAxisControl } from './up-axis';
import { FilterControls } from './filter-controls';
import { Legend } from './legend';
import { ParameterPanel } from './panel';
import { ProgressBar } from './progress-bar';
import { ScalarView } from './scalar-view';
import { StatusLine } from './status';
import { installFailedTestHooks, installTestHooks } from './test-hooks';
import { ViewModeControl } from './view-mode-control';
import { Viewer } from './viewer';
import { WorkerClient, type WorkerInfo } from './worker/client';

/** The preset the start page opens with (a link's preset wins). */
const START_PRESET = 'curvature';

const SAMPLE = { url: `${import.meta.env.BASE_URL}samples/ChineseDragon-10kv.off`, name: 'ChineseDragon-10kv.off' };

function element<T extends HTMLElement>(testId: string, type: new () => T): T {
  const found = document.querySelector(`[data-testid="${testId}"]`);
  if (!(found instanceof type)) throw new Error(`index.html lacks the ${testId} element`);
  return found;
}

/** ?build=single|threaded forces a wasm build (comparisons, tests); default: what the page allows. */
function requestedBuild(): 'auto' | 'single' | 'threaded' {
  const build = new URLSearchParams(location.search).get('build');
  return build === 'single' || build === 'threaded' ? build : 'auto';
}

/**
 * ?heap=MB: the most the single-threaded build's WebAssembly heap may grow to (at least 64), as on a
 * device with less memory; default: wasm32's 4 GB.
 */
function requestedHeapMB(): number | undefined {
  const heap = Number(new URLSearchParams(location.search).get('heap'));
  return Number.isFinite(heap) && heap > 0 ? heap : undefined;
}

/** The page's parts, created once and connected by the steps below. */
interface Parts {
  status: StatusLine;
  viewer: Viewer;
  legend: Legend;
  scalars: ScalarView;
  viewMode: ViewModeControl;
  client: WorkerClient;
  panel: ParameterPanel;
  filters: FilterControls;
  live: LivePreview;
  upAxis: UpAxisControl;
  app: App;
  snapshot: () => Promise<Blob>;
}

/** How the page opens meshes: the startup sample, a gallery case, a file of the person's own. */
interface Demo {
  gallery: Gallery;
  hashSync: HashSync;
  openSample: () => Promise<void>;
  openOwn: (file: File) => void;
}

/** The 3D view, or null (after saying so) when the browser has no WebGL. */
function createViewer(status: StatusLine): Viewer | null {
  try {
    return new Viewer(element('viewport', HTMLElement));
  } catch (error) {
    console.error(error);
    status.error('This browser cannot show 3D graphics (WebGL is unavailable or disabled).');
    return null;
  }
}

function createParts(status: StatusLine, viewer: Viewer): Parts {
  const legend = new Legend(element('legend', HTMLElement));
  const scalars = new ScalarView(element('scalar-select', HTMLSelectElement), legend, () => viewer.geometryChanged());
  const viewMode = new ViewModeControl(element('view-mode', HTMLSelectElement), viewer, (mode) => scalars.setActive(mode === 'scalar'));

  const client = new WorkerClient(requestedBuild(), requestedHeapMB());
  const panel = new ParameterPanel(
    element('preset-select', HTMLSelectElement),
    element('preset-summary', HTMLElement),
    element('params', HTMLElement),
    () => filters.refresh(),
  );
  const filters = new FilterControls(
    {
      run: element('run-button', HTMLButtonElement),
      cancel: element('cancel-button', HTMLButtonElement),
      addNoise: element('add-noise-button', HTMLButtonElement),
      noiseAmount: element('noise-amount', HTMLInputElement),
      revert: element('revert-button', HTMLButtonElement),
      export: element('export-button', HTMLButtonElement),
      beforeToggle: element('before-toggle', HTMLInputElement),
      split: element('split-slider', HTMLInputElement),
      splitLine: element('split-line', HTMLElement),
      metrics: element('metrics', HTMLElement),
    },
    client,
    panel,
    new ProgressBar(element('progress', HTMLElement)),
    viewer,
    viewMode,
    scalars,
    status,
  );
  const live = new LivePreview({
    client,
    filters,
    panel,
    viewer,
    scalars,
    viewMode,
    kind: element('result-kind', HTMLElement),
    enabled: element('live-preview', HTMLInputElement),
  });
  const upAxis = new UpAxisControl(element('up-axis-select', HTMLSelectElement), (axis, front) => viewer.setUp(axisVector(axis), front));
  const app = new App(
    viewer,
    status,
    viewMode,
    (model, fileName) => {
      upAxis.modelChanged(model.meshes, fileName);
      filters.setModel(model, fileName);
    },
    client,
  );
  const snapshot = () =>
    snapshotPng(viewer, {
      viewport: element('viewport', HTMLElement),
      legend: { element: element('legend', HTMLElement), content: legend.shown() },
      splitLine: element('split-line', HTMLElement),
    });
  return { status, viewer, legend, scalars, viewMode, client, panel, filters, live, upAxis, app, snapshot };
}

/** Starts the worker; the presets' values and the available ops arrive with it. */
function connectWorker({ client, panel, filters, status }: Parts): Promise<WorkerInfo> {
  const workerReady = client.ready().then(
    (info) => {
      panel.setCorePresets(info.presets);
      panel.setAvailableOps(info.ops);
      filters.refresh();
      return info;
    },
    (error: unknown) => {
      status.error(`The filters cannot run in this browser: ${error instanceof Error ? error.message : String(error)}. Viewing still works.`);
      throw error;
    },
  );
  workerReady.catch(() => undefined);
  return workerReady;
}

/** The gallery, the URL state, and the three ways a mesh gets on screen. */
function createDemo({ app, panel, filters, upAxis, status, viewMode, scalars }: Parts): Demo {
  let sampleShown = false;
  const gallery: Gallery = new Gallery(element('gallery', HTMLElement), element('gallery-hint', HTMLElement), {
    app,
    panel,
    filters,
    viewMode,
    scalars,
    base: `${import.meta.env.BASE_URL}gallery/`,
    onOpened: () => hashSync.write(true),
    onError: (message) => status.error(message),
  });
  const openSample = async () => {
    gallery.leave(true);
    await app.openUrl(SAMPLE.url, SAMPLE.name);
    sampleShown = app.stats()?.file === SAMPLE.name;
  };
  const hashSync = new HashSync({
    panel,
    up: upAxis,
    caseId: () => gallery.current(),
    ownFile: () => gallery.current() === null && !sampleShown,
    openCase: (id) => (id === null ? openSample() : gallery.open(id)),
    onIgnored: (message) => status.error(message),
  });
  element('up-axis-select', HTMLSelectElement).addEventListener('change', () => hashSync.write(true));
  const openOwn = (file: File) => {
    gallery.leave();
    sampleShown = false;
    void app.openFile(file).then(() => hashSync.write(true));
  };
  return { gallery, hashSync, openSample, openOwn };
}

/** Buttons, the file picker, drop, keyboard and pointer shortcuts. */
function installControls({ app, viewer, panel, status, snapshot }: Parts, demo: Demo): void {
  const input = element('file-input', HTMLInputElement);
  input.addEventListener('change', () => {
    const file = input.files?.[0];
    // Cleared so that choosing the same file again (after editing it elsewhere) fires 'change'.
    input.value = '';
    if (file) demo.openOwn(file);
  });
  installDropZone(document.body, element('drop-overlay', HTMLElement), (file) => demo.openOwn(file));
  element('reset-view', HTMLButtonElement).addEventListener('click', () => viewer.fitToView());
  element('snapshot-button', HTMLButtonElement).addEventListener('click', () => {
    snapshot().then(
      (png) => saveBlob(png, snapshotName(app.stats()?.file ?? 'geoshift')),
      (error: unknown) => status.error(`Could not take a snapshot: ${error instanceof Error ? error.message : String(error)}`),
    );
  });
  installShortcuts(element('run-button', HTMLButtonElement), element('cancel-button', HTMLButtonElement));
  installSheet(element('panel-toggle', HTMLButtonElement));
  // Alt+click picks the source vertex of the geodesic distance.
  viewer.canvas.addEventListener('click', (event) => {
    if (!event.altKey || panel.preset().op !== 'geodesic') return;
    const hit = viewer.pick(event.clientX, event.clientY);
    if (hit) panel.set('source', hit.vertex);
  });
}

/**
 * The first mesh: a link to a gallery case opens the case (with the link's settings); any other
 * page starts with the sample. Resolves when it is on screen.
 */
function openFirstMesh({ app, panel }: Parts, demo: Demo, workerReady: Promise<WorkerInfo>): Promise<void> {
  const linked = decodeState(location.hash);
  // The sample is a clean mesh: its curvature shows at once what the app does; Denoise would
  // change nothing visible (issue 30).
  if (!linked.preset && !linked.caseId) panel.restore(START_PRESET, {});
  return (linked.caseId ? Promise.resolve() : demo.openSample())
    // The presets' availability is known once the worker is up; a link may name any preset.
    .then(() => workerReady.catch(() => undefined))
    .then(() => demo.hashSync.restore(location.hash))
    .then(() => (app.stats() ? undefined : demo.openSample()))
    .then(() => demo.hashSync.replace())
    .then(() => app.settled());
}

function start(): Promise<void> {
  const status = new StatusLine(element('status', HTMLElement));
  const viewer = createViewer(status);
  if (!viewer) return installFailedTestHooks();
  const parts = createParts(status, viewer);
  const workerReady = connectWorker(parts);
  const demo = createDemo(parts);
  installControls(parts, demo);
  const ready = openFirstMesh(parts, demo, workerReady);
  const { app, filters, panel, upAxis, live, snapshot } = parts;
  installTestHooks({
    ready,
    app,
    filters,
    panel,
    workerReady,
    viewer,
    upAxis,
    live,
    snapshot: async () => new Uint8Array(await (await snapshot()).arrayBuffer()),
  });
  return ready;
}

void start();
