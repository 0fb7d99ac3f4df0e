// The one way the end-to-end tests (tests/e2e) look into the app: window.__geoshift
// (GeoshiftTestHooks, globals.d.ts). Nothing else in the app exists for the tests.

import type { App } from './app';
import type { FilterControls } from './filter-controls';
import type { LivePreview } from './live-preview';
import type { ParameterPanel } from './panel';
import type { UpAxisControl } from './up-axis';
import type { Viewer } from './viewer';
import type { WorkerInfo } from './worker/client';

export interface TestHookParts {
  ready: Promise<void>;
  app: App;
  filters: FilterControls;
  panel: ParameterPanel;
  workerReady: Promise<WorkerInfo>;
  viewer: Viewer;
  upAxis: UpAxisControl;
  live: LivePreview;
  /** The PNG bytes the Snapshot button saves. */
  snapshot: () => Promise<Uint8Array>;
}

function base64(bytes: Uint8Array): string {
  // Base64: bytes as a JSON array of numbers would be several times larger to pass to a test.
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary);
}

export function installTestHooks({ ready, app, filters, panel, workerReady, viewer, upAxis, live, snapshot }: TestHookParts): void {
  window.__geoshift = {
    ready,
    stats: () => app.stats(),
    settled: async () => {
      await live.idle();
      await filters.idle();
      await app.settled();
    },
    workerReady: () => workerReady,
    setParam: (key: string, value: unknown) => panel.set(key, value),
    idle: () => filters.idle(),
    lastRun: () => filters.runLog.report,
    lastError: () => filters.runLog.error,
    progressEvents: () => filters.runLog.progressEvents.slice(),
    positions: () => filters.meshes().map((mesh) => Array.from(mesh.geometry.getAttribute('position').array as ArrayLike<number>)),
    scalar: (name: string) =>
      filters.meshes().map((mesh) => {
        const a = mesh.geometry.getAttribute(name);
        return a ? Array.from(a.array as ArrayLike<number>) : null;
      }),
    exportGlb: async () => base64(new Uint8Array(await filters.exportBytes())),
    colors: () =>
      filters.meshes().map((mesh) => {
        const a = mesh.geometry.getAttribute('color');
        if (!a) return null;
        // Denormalized RGB rows, as the filters read them (8-bit colors of a glTF included).
        const rgb: number[] = [];
        for (let i = 0; i < a.count; i++) rgb.push(a.getComponent(i, 0), a.getComponent(i, 1), a.getComponent(i, 2));
        return rgb;
      }),
    indices: () => filters.meshes().map((mesh) => (mesh.geometry.index ? Array.from(mesh.geometry.index.array as ArrayLike<number>) : null)),
    camera: () => viewer.cameraState(),
    marker: () => viewer.markerPosition(),
    upAxis: () => upAxis.axis(),
    params: () => ({ preset: panel.preset().id, params: panel.params() }),
    previewEvents: () => live.events.slice(),
    snapshot: async () => base64(await snapshot()),
  };
}

/** When the page cannot show 3D graphics: the tests still learn that it started. */
export function installFailedTestHooks(): Promise<void> {
  window.__geoshift = { ready: Promise.resolve(), stats: () => null, settled: () => Promise.resolve() } as unknown as Window['__geoshift'];
  return window.__geoshift.ready;
}
