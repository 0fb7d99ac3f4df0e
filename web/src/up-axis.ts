// Which way is up: guessed from the mesh when it opens, or picked in the bar's "Up" select. The
// view orbits about that axis and Reset view frames the mesh standing on it.
//
// The guess, in order: a surface whose area-weighted normals mostly agree (a terrain, a relief) has
// its up where they point; a solid standing on a flat base (a scanned statue, a CAD part on a
// table) has its up opposite the largest flat face at its extreme; otherwise glTF's convention
// (+Y, which the format prescribes) or, for the other formats, +Z when the mesh is clearly taller
// along Z than along Y (scanners and CAD tools mostly write Z-up) and +Y when not.

import { Vector3, type Mesh } from 'three';

export const AXES = ['+y', '+z', '+x', '-y', '-z', '-x'] as const;
export type Axis = (typeof AXES)[number];

export function isAxis(value: string): value is Axis {
  return (AXES as readonly string[]).includes(value);
}

export function axisVector(axis: Axis): Vector3 {
  const v = new Vector3();
  v.setComponent('xyz'.indexOf(axis[1]!), axis[0] === '-' ? -1 : 1);
  return v;
}

function axisOf(component: number, sign: number): Axis {
  return `${sign < 0 ? '-' : '+'}${'xyz'[component]}` as Axis;
}

export interface UpGuess {
  axis: Axis;
  /** Why, in a few words (shown as the select's tooltip). */
  reason: string;
}

/** Faces looked at by the guess: every k-th beyond this many (the guess needs area shares only). */
const MAX_FACES = 200_000;

/** Guesses the up axis of meshes (world coordinates); `fileName` tells the format's convention. */
export function guessUpAxis(meshes: Mesh[], fileName: string): UpGuess {
  const a = new Vector3();
  const b = new Vector3();
  const c = new Vector3();
  const n = new Vector3();
  const normalSum = new Vector3();
  let area = 0;
  const min = new Vector3(Infinity, Infinity, Infinity);
  const max = new Vector3(-Infinity, -Infinity, -Infinity);
  let total = 0;
  for (const mesh of meshes) total += Math.floor((mesh.geometry.index?.count ?? mesh.geometry.getAttribute('position').count) / 3);
  const stride = Math.max(1, Math.ceil(total / MAX_FACES));
  // Per sampled face: unit normal, area, centroid (7 numbers).
  const faces: number[] = [];
  for (const mesh of meshes) {
    mesh.updateWorldMatrix(true, false);
    const position = mesh.geometry.getAttribute('position');
    const index = mesh.geometry.index;
    const corners = index ? index.count : position.count;
    const vertex = (k: number, into: Vector3) => into.fromBufferAttribute(position, index ? index.getX(k) : k).applyMatrix4(mesh.matrixWorld);
    for (let k = 0; k + 2 < corners; k += 3 * stride) {
      vertex(k, a);
      vertex(k + 1, b);
      vertex(k + 2, c);
      min.min(a).min(b).min(c);
      max.max(a).max(b).max(c);
      c.sub(a);
      n.subVectors(b, a).cross(c);
      const twice = n.length();
      if (!(twice > 0)) continue;
      normalSum.add(n);
      area += twice / 2;
      // c now holds c - a, so the centroid (a + b + c) / 3 is (2a + b + (c - a)) / 3.
      faces.push(n.x / twice, n.y / twice, n.z / twice, twice / 2, (2 * a.x + b.x + c.x) / 3, (2 * a.y + b.y + c.y) / 3, (2 * a.z + b.z + c.z) / 3);
    }
  }
  if (!(area > 0)) return { axis: '+y', reason: 'no surface to guess from' };

  // A relief or terrain: one side of the surface faces one way.
  const agreement = normalSum.length() / (2 * area);
  if (agreement > 0.5) {
    const k = largestComponent(normalSum);
    return { axis: axisOf(k, normalSum.getComponent(k)), reason: 'most of the surface faces this way' };
  }

  // A solid on a flat base: the largest flat area at an extreme, facing outwards.
  const extent = max.clone().sub(min);
  const cosLimit = Math.cos((10 * Math.PI) / 180);
  let bestArea = 0;
  let bestDown: Axis | null = null;
  for (let k = 0; k < 3; k++) {
    const tolerance = 0.02 * Math.max(extent.getComponent(k), 1e-30);
    for (const sign of [-1, 1]) {
      let flat = 0;
      const extreme = sign < 0 ? min.getComponent(k) : max.getComponent(k);
      for (let f = 0; f < faces.length; f += 7) {
        if (sign * faces[f + k]! > cosLimit && Math.abs(faces[f + 4 + k]! - extreme) <= tolerance) flat += faces[f + 3]!;
      }
      if (flat > bestArea) [bestArea, bestDown] = [flat, axisOf(k, sign)];
    }
  }
  if (bestDown && bestArea > 0.02 * area) {
    const up = (bestDown[0] === '-' ? '+' : '-') + bestDown[1];
    return { axis: up as Axis, reason: 'it stands on a flat base' };
  }

  if (/\.(glb|gltf)$/i.test(fileName)) return { axis: '+y', reason: 'glTF files are Y-up' };
  if (extent.z > 1.2 * extent.y) return { axis: '+z', reason: 'it is taller along Z' };
  return { axis: '+y', reason: 'no clear sign; +Y is the usual default' };
}

function largestComponent(v: Vector3): number {
  const abs = [Math.abs(v.x), Math.abs(v.y), Math.abs(v.z)];
  return abs.indexOf(Math.max(...abs));
}

/** The bar's "Up" select: "Auto (guess)" or an axis the person picked, kept across files. */
export class UpAxisControl {
  private guess: UpGuess = { axis: '+y', reason: '' };
  private readonly autoOption: HTMLOptionElement;

  constructor(
    private readonly select: HTMLSelectElement,
    private readonly apply: (axis: Axis) => void,
  ) {
    const auto = select.querySelector<HTMLOptionElement>('option[value="auto"]');
    if (!auto) throw new Error('the up-axis select lacks its "auto" option');
    this.autoOption = auto;
    select.addEventListener('change', () => this.apply(this.axis()));
  }

  /** A new model is on screen: guess again (used while the select says Auto). */
  modelChanged(meshes: Mesh[], fileName: string): void {
    this.guess = guessUpAxis(meshes, fileName);
    this.autoOption.textContent = `Auto (${label(this.guess.axis)})`;
    this.autoOption.title = `Guessed: ${label(this.guess.axis)}, because ${this.guess.reason}.`;
    this.apply(this.axis());
  }

  /** The axis in use. */
  axis(): Axis {
    return isAxis(this.select.value) ? this.select.value : this.guess.axis;
  }

  /** What the select says: 'auto' or an axis (the URL keeps it). */
  choice(): string {
    return this.select.value;
  }

  set(choice: string): void {
    if (choice !== 'auto' && !isAxis(choice)) return;
    this.select.value = choice;
    this.apply(this.axis());
  }
}

export function label(axis: Axis): string {
  return `${axis[0] === '-' ? '−' : '+'}${axis[1]!.toUpperCase()}`;
}
