// The demo's state in the URL hash, so that a link reproduces it and Back/Forward step through
// earlier settings: `#case=ID&preset=ID&up=+z&KEY=VALUE...` with every parameter the preset
// declares (presets.ts), whatever they are. Settled changes (a slider released, a preset or a case
// picked) add a history entry; values still moving only replace the current one.

import type { ParameterPanel } from './panel';
import { presetById, type Preset } from './presets';

export interface DemoState {
  preset?: string;
  caseId?: string;
  up?: string;
  /** Parameter values as written in the URL (strings), not yet checked against a preset. */
  values: Record<string, string>;
}

const RESERVED = new Set(['preset', 'case', 'up']);

export function encodeState(state: { preset: string; caseId?: string | null; up?: string; values: Record<string, unknown> }): string {
  const q = new URLSearchParams();
  if (state.caseId) q.set('case', state.caseId);
  q.set('preset', state.preset);
  if (state.up && state.up !== 'auto') q.set('up', state.up);
  for (const [key, value] of Object.entries(state.values)) {
    if (RESERVED.has(key) || value === undefined || value === null) continue;
    q.set(key, String(value));
  }
  return `#${q.toString()}`;
}

export function decodeState(hash: string): DemoState {
  const q = new URLSearchParams(hash.replace(/^#/, ''));
  const state: DemoState = { values: {} };
  for (const [key, value] of q) {
    if (key === 'preset') state.preset = value;
    else if (key === 'case') state.caseId = value;
    else if (key === 'up') state.up = value;
    else state.values[key] = value;
  }
  return state;
}

/**
 * The values of `preset` found in `raw`, typed as its parameters declare; anything else (unknown
 * keys, a number that is not one, a choice not offered) is left out and listed in `ignored`.
 */
export function typedValues(preset: Preset, raw: Record<string, string>): { values: Record<string, unknown>; ignored: string[] } {
  const values: Record<string, unknown> = {};
  const ignored: string[] = [];
  for (const [key, text] of Object.entries(raw)) {
    const param = preset.params.find((p) => p.key === key);
    if (!param) {
      if (key === 'signal' && preset.needsScalar) values.signal = text;
      else ignored.push(key);
      continue;
    }
    if (param.kind === 'number') {
      const x = Number(text);
      if (text.trim() !== '' && Number.isFinite(x)) values[key] = x;
      else ignored.push(key);
    } else if (param.kind === 'flag') {
      if (text === 'true' || text === 'false') values[key] = text === 'true';
      else ignored.push(key);
    } else if (Object.values(param.options).includes(text)) values[key] = text;
    else ignored.push(key);
  }
  return { values, ignored };
}

export interface HashSyncParts {
  panel: ParameterPanel;
  /** The up-axis choice ('auto' or an axis) and how to set it. */
  up: { choice(): string; set(choice: string): void };
  /** The gallery case on screen, or null for a file of the person's own or the startup sample. */
  caseId(): string | null;
  /** A file of the person's own is on screen (a link without a case leaves it there). */
  ownFile(): boolean;
  /**
   * Opens a gallery case, or the startup sample for null (Back/Forward across cases); resolves when
   * it is on screen, rejects when there is no such case.
   */
  openCase(id: string | null): Promise<void>;
  /** Told when a link named something this app does not know. */
  onIgnored(message: string): void;
}

export class HashSync {
  private restoring = false;
  /** A value is moving and the current history entry is its own (made at its first step). */
  private moving = false;

  constructor(private readonly parts: HashSyncParts) {
    parts.panel.listen((change) => this.write(change !== 'input' && change !== 'slide'));
    window.addEventListener('popstate', () => {
      this.moving = false;
      void this.restore(location.hash);
    });
  }

  /** The state as the page shows it. */
  current(): string {
    const { panel, up, caseId } = this.parts;
    return encodeState({ preset: panel.preset().id, caseId: caseId(), up: up.choice(), values: panel.currentValues() });
  }

  /**
   * Records the page's state. A change in steps (a slider dragged, a number typed) gets one new
   * history entry at its first step, updated in place until it settles (`settled`); a settled
   * change of its own gets a new entry.
   */
  write(settled: boolean): void {
    if (this.restoring) return;
    const hash = this.current();
    if (hash === location.hash) {
      if (settled) this.moving = false;
      return;
    }
    if (this.moving) history.replaceState(null, '', hash);
    else history.pushState(null, '', hash);
    this.moving = !settled;
  }

  /** Replaces the current entry's state (startup, a file of one's own) without a new entry. */
  replace(): void {
    if (this.restoring) return;
    const hash = this.current();
    if (hash !== location.hash) history.replaceState(null, '', hash);
  }

  /** Applies a hash (at startup, or Back/Forward): the case first, then preset, values, up axis. */
  async restore(hash: string): Promise<void> {
    const state = decodeState(hash);
    this.restoring = true;
    try {
      const wanted = state.caseId ?? null;
      if (wanted !== this.parts.caseId() && !(wanted === null && this.parts.ownFile())) {
        try {
          await this.parts.openCase(wanted);
        } catch (error) {
          this.parts.onIgnored(error instanceof Error ? error.message : String(error));
        }
      }
      if (state.preset) {
        const preset = presetById(state.preset);
        const { values, ignored } = preset ? typedValues(preset, state.values) : { values: {}, ignored: [] };
        if (!preset || !this.parts.panel.restore(state.preset, values)) {
          this.parts.onIgnored(`The link names a preset this app does not offer ("${state.preset}").`);
        } else if (ignored.length) {
          this.parts.onIgnored(`The link's ${ignored.join(', ')} ${ignored.length === 1 ? 'was' : 'were'} not understood and left as they were.`);
        }
      }
      this.parts.up.set(state.up ?? 'auto');
    } finally {
      this.restoring = false;
    }
  }
}
