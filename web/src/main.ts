// Wiring only: find the page's elements, create the parts, connect them, open the sample.

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
import { WorkerClient } from './worker/client';

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

function start(): Promise<void> {
  const status = new StatusLine(element('status', HTMLElement));
  let viewer: Viewer;
  try {
    viewer = new Viewer(element('viewport', HTMLElement));
  } catch (error) {
    console.error(error);
    status.error('This browser cannot show 3D graphics (WebGL is unavailable or disabled).');
    return installFailedTestHooks();
  }
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
  const upAxis = new UpAxisControl(element('up-axis-select', HTMLSelectElement), (axis) => viewer.setUp(axisVector(axis)));
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

  const input = element('file-input', HTMLInputElement);
  input.addEventListener('change', () => {
    const file = input.files?.[0];
    // Cleared so that choosing the same file again (after editing it elsewhere) fires 'change'.
    input.value = '';
    if (file) openOwn(file);
  });
  installDropZone(document.body, element('drop-overlay', HTMLElement), (file) => openOwn(file));
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

  const gallery: Gallery = new Gallery(element('gallery', HTMLElement), element('gallery-hint', HTMLElement), {
    app,
    panel,
    filters,
    base: `${import.meta.env.BASE_URL}gallery/`,
    onOpened: () => hashSync.write(true),
    onError: (message) => status.error(message),
  });
  let sampleShown = false;
  const openSample = async () => {
    gallery.leave();
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

  // A link to a gallery case opens the case (restore below); any other page starts with the sample.
  const linkedCase = decodeState(location.hash).caseId;
  const ready = (linkedCase ? Promise.resolve() : openSample())
    // The presets' availability is known once the worker is up; a link may name any preset.
    .then(() => workerReady.catch(() => undefined))
    .then(() => hashSync.restore(location.hash))
    .then(() => (app.stats() ? undefined : openSample()))
    .then(() => hashSync.replace())
    .then(() => app.settled());
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
