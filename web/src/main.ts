// Wiring only: find the page's elements, create the parts, connect them, open the sample.

import './style.css';
import { App } from './app';
import { installDropZone } from './dropzone';
import { StatusLine } from './status';
import { ViewModeControl } from './view-mode-control';
import { Viewer } from './viewer';

const SAMPLE = { url: `${import.meta.env.BASE_URL}samples/ChineseDragon-10kv.off`, name: 'ChineseDragon-10kv.off' };

function element<T extends HTMLElement>(testId: string, type: new () => T): T {
  const found = document.querySelector(`[data-testid="${testId}"]`);
  if (!(found instanceof type)) throw new Error(`index.html lacks the ${testId} element`);
  return found;
}

function start(): Promise<void> {
  const status = new StatusLine(element('status', HTMLElement));
  let viewer: Viewer;
  try {
    viewer = new Viewer(element('viewport', HTMLElement));
  } catch (error) {
    console.error(error);
    status.error('This browser cannot show 3D graphics (WebGL is unavailable or disabled).');
    window.__geoshift = { ready: Promise.resolve(), stats: () => null, settled: () => Promise.resolve() };
    return window.__geoshift.ready;
  }
  const viewMode = new ViewModeControl(element('view-mode', HTMLSelectElement), viewer);
  const app = new App(viewer, status, viewMode);

  const input = element('file-input', HTMLInputElement);
  input.addEventListener('change', () => {
    const file = input.files?.[0];
    // Cleared so that choosing the same file again (after editing it elsewhere) fires 'change'.
    input.value = '';
    if (file) void app.openFile(file);
  });
  installDropZone(document.body, element('drop-overlay', HTMLElement), (file) => void app.openFile(file));
  element('reset-view', HTMLButtonElement).addEventListener('click', () => viewer.fitToView());

  const ready = app.openUrl(SAMPLE.url, SAMPLE.name).then(() => app.settled());
  window.__geoshift = { ready, stats: () => app.stats(), settled: () => app.settled() };
  return ready;
}

void start();
