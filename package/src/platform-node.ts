// Node: the worker is a worker_threads thread running node-worker.js. It keeps the process alive
// while it starts and while a call is pending (client.ts says when), so a script that forgets
// terminate() still exits.

import os from 'node:os';
import { Worker } from 'node:worker_threads';

import type { Platform } from './geoshift.js';

export const node: Platform = {
  sharedMemory: () => true,
  cores: () => os.availableParallelism(),
  noThreads: '',
  spawn(events) {
    const worker = new Worker(new URL('./node-worker.js', import.meta.url));
    let ended = false;
    worker.on('message', (data: unknown) => events.message(data));
    worker.on('error', (error: Error) => events.error(error.message));
    worker.on('exit', (code: number) => {
      if (!ended) events.error(`the worker thread exited (code ${code})`);
    });
    return {
      postMessage: (message, transfer = []) => worker.postMessage(message, transfer as never),
      terminate: () => {
        ended = true;
        void worker.terminate();
      },
      busy: (busy) => (busy ? worker.ref() : worker.unref()),
    };
  },
};
