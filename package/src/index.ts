/**
 * geoshift: filters for signals on triangle meshes (denoising, mean shift of colors, normals,
 * curvature and terrain attributes, wavelets), running as WebAssembly in a worker.
 *
 * ```ts
 * import { createGeoshift } from 'geoshift';
 * const gs = await createGeoshift();
 * const { positions } = await gs.denoise({ positions, indices }, { onProgress: (f) => bar.value = f });
 * gs.terminate();
 * ```
 * @packageDocumentation
 */

import { create, type Geoshift } from './geoshift.js';
import { browser } from './platform-browser.js';
import type { CreateOptions } from './types.js';

export * from './api.js';

/**
 * Starts a worker with the geoshift module: the threaded build when the page is cross-origin
 * isolated (and in Node), else the single-threaded one (`info` says which). Rejects with a
 * GeoshiftError of kind 'internal' when the module cannot start (a missing or blocked .wasm file).
 */
export function createGeoshift(options?: CreateOptions): Promise<Geoshift> {
  return create(browser, options);
}
