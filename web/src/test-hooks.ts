// The one way the end-to-end tests (tests/e2e) look into the app: window.__geoshift
// (GeoshiftTestHooks, globals.d.ts). Nothing else in the app exists for the tests.

import type { App } from './app';
import type { FilterControls } from './filter-controls';
import type { ParameterPanel } from './panel';
import type { WorkerInfo } from './worker/client';

export interface TestHookParts {
  ready: Promise<void>;
  app: App;
  filters: FilterControls;
  panel: ParameterPanel;
  workerReady: Promise<WorkerInfo>;
}

export function installTestHooks({ ready, app, filters, panel, workerReady }: TestHookParts): void {
  window.__geoshift = {
    ready,
    stats: () => app.stats(),
    settled: async () => {
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
    exportGlb: async () => {
      // Base64: a GLB as a JSON array of numbers would be several times larger to pass to a test.
      const bytes = new Uint8Array(await filters.exportBytes());
      let binary = '';
      for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
      return btoa(binary);
    },
  };
}

/** When the page cannot show 3D graphics: the tests still learn that it started. */
export function installFailedTestHooks(): Promise<void> {
  window.__geoshift = { ready: Promise.resolve(), stats: () => null, settled: () => Promise.resolve() } as unknown as Window['__geoshift'];
  return window.__geoshift.ready;
}
