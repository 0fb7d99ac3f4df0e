// The entry Node resolves (package.json "exports", condition "node"): the same API, on worker_threads.

import { create, type Geoshift } from './geoshift.js';
import { node } from './platform-node.js';
import type { CreateOptions } from './types.js';

export * from './api.js';

/** Starts a worker thread with the geoshift module (threaded unless `threads: 1`). */
export function createGeoshift(options?: CreateOptions): Promise<Geoshift> {
  return create(node, options);
}
