// The status line in the header: what is on screen, what is loading or running, or what went wrong.
// data-state lets tests and styles tell them apart without parsing the text.

import type { MeshCounts } from './loaders';
import { counted } from './words';

export class StatusLine {
  constructor(private readonly element: HTMLElement) {}

  loading(fileName: string): void {
    this.set('loading', `Loading ${fileName}…`);
  }

  /** `repairs`: what the filters' reading of the file repairs (core-check.ts repairsOf), if anything. */
  shown(fileName: string, counts: MeshCounts, repairs: { summary: string[]; full: string[] } = { summary: [], full: [] }): void {
    const text = `${fileName}: ${counted(counts.vertices, 'vertex', 'vertices')}, ${counted(counts.triangles, 'triangle')}`;
    const repaired = (lines: string[]) => (lines.length ? `; repaired for the filters: ${lines.join('; ')}` : '');
    this.set('ok', text + repaired(repairs.summary), text + repaired(repairs.full));
  }

  /** A filter is running on the model on screen. */
  working(text: string): void {
    this.set('working', text);
  }

  /** A filter finished (or the mesh was reverted). */
  done(text: string): void {
    this.set('ok', text);
  }

  /** An error keeps the previous mesh on screen, so the message says which file failed. */
  error(message: string): void {
    this.set('error', message);
  }

  private set(state: 'loading' | 'working' | 'ok' | 'error', text: string, title = text): void {
    this.element.dataset.state = state;
    this.element.textContent = text;
    this.element.title = title;
  }
}
