// The gallery: real meshes opened in one click, each with the preset that suits it and a line of
// what to try. The files ship in web/public/gallery (scripts/build-gallery.mjs made them; sources
// and licenses in web/public/gallery/LICENSE.md). A case with a clean original reports the error of
// every run against it.

import type { App } from './app';
import type { FilterControls } from './filter-controls';
import { loadModel } from './loaders';
import { meshArrays } from './model';
import type { ParameterPanel } from './panel';
import type { ScalarView } from './scalar-view';
import type { ViewMode } from './materials';
import type { ViewModeControl } from './view-mode-control';

export interface GalleryCase {
  id: string;
  /** What it shows, as the button says it. */
  title: string;
  /** File under gallery/. */
  file: string;
  /** The clean original of a noisy file (same vertices in the same order), under gallery/. */
  reference?: { file: string; name: string };
  preset: string;
  /** Parameters set on opening; the rest keep the preset's defaults. */
  values: Record<string, unknown>;
  /** How it is shown on opening: a view mode, and the field of the scalar mode. */
  view: { mode: ViewMode; field?: string };
  /** One line: what to try. */
  tryThis: string;
  /** Where it comes from (shown as the button's tooltip). */
  credit: string;
}

export const CASES: GalleryCase[] = [
  {
    id: 'noisy-scan',
    title: 'Noisy scan to denoise',
    file: 'fertility-noisy.glb',
    reference: { file: 'fertility-clean.glb', name: 'the clean scan' },
    preset: 'denoise',
    values: {},
    view: { mode: 'shaded' },
    tryThis: 'Run, then compare the error against the clean scan under Result; a smaller Keep edges keeps the rims sharper.',
    credit: 'Fertility with Gaussian noise and its clean original (AIM@SHAPE, via GCN-Denoiser, BSD-3-Clause)',
  },
  {
    id: 'colored-mesh',
    title: 'Colored LiDAR scene',
    file: 'autzen-terrain.glb',
    preset: 'smooth-colors',
    values: { segments: true },
    view: { mode: 'colors' },
    tryThis: 'Run to even out the aerial photo\'s colors and label regions of one color; a larger color tolerance merges roofs, trees and lawns into fewer segments.',
    credit: 'Autzen Stadium LiDAR points with their RGB (Oregon LiDAR Consortium, via PDAL, BSD), simplified to 40,000 vertices',
  },
  {
    id: 'terrain',
    title: 'Terrain with vegetation',
    file: 'autzen-terrain.glb',
    preset: 'terrain',
    values: { signal: '_height_above_ground' },
    view: { mode: 'scalar', field: '_height_above_ground' },
    tryThis: 'Smooth the height above ground: trees and buildings keep their edges while small bumps flatten; compare before | after with the split view.',
    credit: 'Autzen Stadium LiDAR (Oregon LiDAR Consortium, via PDAL, BSD), simplified to 40,000 vertices',
  },
  {
    id: 'cad-part',
    title: 'Noisy CAD part: curvature',
    file: 'fandisk-noisy.glb',
    preset: 'filter-curvature',
    // h_r in the part's own units (1 / length; its creases have about 1.5): a fifth of a crease.
    values: { hr: 0.3 },
    view: { mode: 'shaded' },
    tryThis: 'Run, then drag the split view: the raw curvature (left) is speckled by the noise, the filtered one (right) has flat faces and clean creases; a larger curvature tolerance merges the creases into the faces.',
    credit: 'Fandisk (H. Hoppe\'s CAD model, via GCN-Denoiser, BSD-3-Clause) with Gaussian noise of 0.1 average edge length',
  },
];

export function caseById(id: string): GalleryCase | undefined {
  return CASES.find((c) => c.id === id);
}

export interface GalleryParts {
  app: App;
  panel: ParameterPanel;
  filters: FilterControls;
  viewMode: ViewModeControl;
  scalars: ScalarView;
  /** Base URL of the gallery files. */
  base: string;
  /** Told after a case was opened by a click (the URL records it). */
  onOpened: () => void;
  onError: (message: string) => void;
}

export class Gallery {
  private currentId: string | null = null;

  constructor(
    container: HTMLElement,
    private readonly hint: HTMLElement,
    private readonly parts: GalleryParts,
  ) {
    for (const c of CASES) {
      const button = document.createElement('button');
      button.type = 'button';
      button.className = 'button gallery-item';
      button.dataset.testid = 'gallery-item';
      button.dataset.case = c.id;
      button.textContent = c.title;
      button.title = c.credit;
      button.addEventListener('click', () => {
        this.open(c.id).then(
          () => parts.onOpened(),
          (error: unknown) => parts.onError(error instanceof Error ? error.message : String(error)),
        );
      });
      container.append(button);
    }
    hint.hidden = true;
  }

  /** The case on screen, or null. */
  current(): string | null {
    return this.currentId;
  }

  /** Opens a case: its mesh, its clean original if any, its preset and values. */
  async open(id: string): Promise<void> {
    const c = caseById(id);
    if (!c) throw new Error(`There is no gallery case "${id}" (there are: ${CASES.map((k) => k.id).join(', ')}).`);
    const { app, panel, filters, base } = this.parts;
    const reference = c.reference ? fetchPositions(`${base}${c.reference.file}`, c.reference.file) : null;
    reference?.catch(() => undefined);
    await app.openUrl(`${base}${c.file}`, c.file);
    if (app.stats()?.file !== c.file) throw new Error(`The gallery case "${c.title}" could not be opened.`);
    this.currentId = c.id;
    if (reference && c.reference) filters.setReference(await reference, c.reference.name);
    panel.restore(c.preset, c.values);
    if (c.view.field) this.parts.scalars.choose(c.view.field);
    this.parts.viewMode.show(c.view.mode);
    this.hint.textContent = `${c.title}: ${c.tryThis}`;
    this.hint.hidden = false;
    this.hint.dataset.kind = 'case';
    for (const b of document.querySelectorAll<HTMLElement>('[data-testid="gallery-item"]')) b.setAttribute('aria-pressed', String(b.dataset.case === c.id));
  }

  /** A file of the person's own replaces the case; `welcome` points a newcomer at the gallery instead. */
  leave(welcome = false): void {
    this.currentId = null;
    this.hint.textContent = welcome ? 'New here? Open a case above: each one loads a real mesh with the filter that suits it and says what to try.' : '';
    this.hint.hidden = !welcome;
    this.hint.dataset.kind = welcome ? 'welcome' : 'none';
    for (const b of document.querySelectorAll<HTMLElement>('[data-testid="gallery-item"]')) b.setAttribute('aria-pressed', 'false');
  }
}

/** Positions of every mesh of a file, as the filters see them (the file's own vertex layout). */
async function fetchPositions(url: string, fileName: string): Promise<Float32Array[]> {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${fileName} could not be downloaded (${response.status} ${response.statusText})`);
  const model = await loadModel(fileName, await response.arrayBuffer());
  return model.meshes.map((mesh) => meshArrays(mesh.geometry).positions);
}
