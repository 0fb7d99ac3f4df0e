// Opening files: load, show, report. A failed load leaves the previous model on screen; when two
// loads overlap (a second file dropped while the first still parses), only the last one is shown.
// The user's own files are read by the core first (core-check.ts), so a damaged file gets the CLI's
// message; the files the app ships (the sample, the gallery) are not, so that the first view does
// not wait for the WebAssembly module.

import { checkWithCore, CoreReadError, repairsOf, type CoreReader } from './core-check';
import { describeLoadFailure, loadModel, LoadError, type LoadedModel, type MeshCounts } from './loaders';
import type { StatusLine } from './status';
import type { Viewer } from './viewer';
import type { ViewModeControl } from './view-mode-control';

export interface ShownStats extends MeshCounts {
  file: string;
}

export class App {
  private shown: ShownStats | null = null;
  private latest = 0;
  private pending: Promise<void> = Promise.resolve();

  constructor(
    private readonly viewer: Viewer,
    private readonly status: StatusLine,
    private readonly viewMode: ViewModeControl,
    /** Told about every model put on screen (the filter panel takes it from there). */
    private readonly onShown: (model: LoadedModel, fileName: string) => void = () => undefined,
    /** The core's readers in the worker; without it, three's loaders and the app's checks decide. */
    private readonly core: CoreReader | null = null,
  ) {}

  /** Stats of the model on screen, or null before the first successful load. */
  stats(): ShownStats | null {
    return this.shown ? { ...this.shown } : null;
  }

  openFile(file: File): Promise<void> {
    return this.open(file.name, () => file.arrayBuffer(), true);
  }

  /** Fetches a file that ships with the app (the startup sample). */
  openUrl(url: string, fileName: string): Promise<void> {
    return this.open(fileName, async () => {
      let response: Response;
      try {
        response = await fetch(url);
      } catch (e) {
        throw new LoadError(`it could not be downloaded (${e instanceof Error ? e.message : String(e)})`);
      }
      if (!response.ok) throw new LoadError(`the server answered ${response.status} ${response.statusText}`);
      return response.arrayBuffer();
    });
  }

  /** Resolves when no load is in progress and the last change has been drawn. */
  async settled(): Promise<void> {
    let seen: Promise<void>;
    do {
      seen = this.pending;
      await seen;
    } while (seen !== this.pending);
    await this.viewer.nextFrame();
  }

  private open(fileName: string, read: () => Promise<ArrayBuffer>, checkWithTheCore = false): Promise<void> {
    const ticket = ++this.latest;
    this.status.loading(fileName);
    const run = async (): Promise<void> => {
      try {
        const data = await read();
        const info = checkWithTheCore && this.core ? await checkWithCore(this.core, fileName, data) : null;
        if (ticket !== this.latest) return;
        const model = await loadModel(fileName, data);
        if (ticket !== this.latest) return;
        this.viewMode.modelChanged(model.hasVertexColors);
        this.viewer.setModel(model);
        this.onShown(model, fileName);
        this.shown = { file: fileName, ...model.counts };
        this.status.shown(fileName, model.counts, repairsOf(info));
      } catch (error) {
        if (ticket !== this.latest) return;
        console.error(`geoshift: could not read ${fileName}`, error);
        const still = this.shown ? ` Still showing ${this.shown.file}.` : '';
        // The core's message names the file itself, as the CLI prints it.
        const what = error instanceof CoreReadError ? error.message : `${fileName}: ${describeLoadFailure(error)}`;
        this.status.error(`Could not read ${what}.${still}`);
      }
    };
    const done = run();
    this.pending = this.pending.then(() => done);
    return done;
  }
}
