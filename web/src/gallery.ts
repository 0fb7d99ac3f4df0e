// The gallery: real meshes opened in one click, each with the preset that suits it and a line of
// what to try. The files ship in web/public/gallery (scripts/build-gallery.mjs made them; sources
// and licenses in web/public/gallery/LICENSE.md). A case with a clean original reports the error of
// every run against it.

import type { App } from './app';
import type { FilterControls } from './filter-controls';
import { loadModel } from './loaders';
import { meshArrays } from './model';
import type { ParameterPanel } from './panel';

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
    tryThis: 'Run, then compare the error against the clean scan under Result; lower the feature preservation to keep the rims sharp.',
    credit: 'Fertility with Gaussian noise and its clean original (AIM@SHAPE, via GCN-Denoiser, BSD-3-Clause)',
  },
  {
    id: 'colored-mesh',
    title: 'Colored LiDAR scene',
    file: 'b9-colors.glb',
    preset: 'smooth-colors',
    values: { segments: true },
    tryThis: 'Run to even out the colors and label regions; raise the color tolerance to merge roofs, trees and lawns into fewer segments.',
    credit: 'The b9 aerial LiDAR scene of CGAL\'s classification example (CC0-1.0)',
  },
  {
    id: 'terrain',
    title: 'Terrain with vegetation',
    file: 'autzen-terrain.glb',
    preset: 'terrain',
    values: { signal: '_height_above_ground' },
    tryThis: 'Smooth the height above ground: trees and buildings keep their edges while small bumps flatten; compare before | after with the split view.',
    credit: 'Autzen Stadium LiDAR (Oregon LiDAR Consortium, via PDAL, BSD), simplified to 30,000 vertices',
  },
  {
    id: 'cad-part',
    title: 'CAD part: curvature',
    file: 'fandisk.glb',
    preset: 'filter-curvature',
    values: {},
    tryThis: 'Run to see curvature filtered along the sharp edges; a smaller curvature tolerance keeps creases apart from the flat faces.',
    credit: 'Fandisk (H. Hoppe\'s CAD model, via GCN-Denoiser, BSD-3-Clause)',
  },
];

export function caseById(id: string): GalleryCase | undefined {
  return CASES.find((c) => c.id === id);
}

export interface GalleryParts {
  app: App;
  panel: ParameterPanel;
  filters: FilterControls;
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
    this.hint.textContent = `${c.title}: ${c.tryThis}`;
    this.hint.hidden = false;
    for (const b of document.querySelectorAll<HTMLElement>('[data-testid="gallery-item"]')) b.setAttribute('aria-pressed', String(b.dataset.case === c.id));
  }

  /** A file of the person's own replaces the case. */
  leave(): void {
    this.currentId = null;
    this.hint.hidden = true;
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
