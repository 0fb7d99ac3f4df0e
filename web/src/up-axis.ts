// Which way is up: guessed from the mesh when it opens, or picked in the bar's "Up" select. The
// view orbits about that axis and Reset view frames the mesh standing on it.
//
// The guess, in order: a flat surface whose area-weighted normals mostly agree (a terrain, a
// relief) has its up where they point; a surface seen from one side only but not flat (a scan from
// one viewpoint: its normals agree too) faces the scanner, which looks along −Z with +Y up; a solid
// standing on a flat base (a scanned statue, a CAD part on a table) has its up opposite the largest
// flat face at its extreme; otherwise glTF's convention (+Y, which the format prescribes) or, for
// the other formats, +Z when the mesh is clearly taller along Z than along Y (scanners and CAD
// tools mostly write Z-up) and +Y when not.
//
// The front, the side the default view looks at: a one-sided scan's scanned side; otherwise the side
// its upper part leans to (a figure's head and arms are ahead of its body: the armadillo opened seen
// from its back, issue 30); the default when neither says.

import { Quaternion, Vector3, type Mesh } from 'three';

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
  /** −1 when the front faces away from the default view's side (depthAxis), else 1. */
  front: 1 | -1;
}

/**
 * The horizontal direction the default view looks from, for an up axis: +Z when +Y is up, rotated
 * with the up axis (for +Z up: −Y), as the viewer's default view direction is.
 */
export function depthAxis(up: Vector3): Vector3 {
  return new Vector3(0, 0, 1).applyQuaternion(new Quaternion().setFromUnitVectors(new Vector3(0, 1, 0), up.clone().normalize()));
}

/** A relief is at most this thick along its normals, as a share of its other sides. */
const RELIEF_THICKNESS = 0.4;
/** The upper part's lean, as a share of the depth, that tells the front. */
const FRONT_LEAN = 0.05;

/** Faces looked at by the guess: every k-th beyond this many (the guess needs area shares only). */
const MAX_FACES = 200_000;

/** Guesses the up axis and front of meshes (world coordinates); `fileName` tells the format's convention. */
export function guessUpAxis(meshes: Mesh[], fileName: string): UpGuess {
  const sample = sampleFaces(meshes);
  const guess = guessAxis(sample, fileName);
  // A part on a flat base or a relief has no front to speak of: the default side shows it as its
  // file was drawn.
  const figure = guess.kind === 'scan' || guess.kind === 'convention';
  return { axis: guess.axis, reason: guess.reason, front: figure ? guessFront(sample, guess) : 1 };
}

/** What the axis was guessed from. */
type GuessKind = 'relief' | 'scan' | 'base' | 'convention';

/** Per sampled face: unit normal, area, centroid (7 numbers); their normal sum, area and box. */
interface FaceSample {
  faces: number[];
  normalSum: Vector3;
  area: number;
  min: Vector3;
  max: Vector3;
}

function sampleFaces(meshes: Mesh[]): FaceSample {
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
  return { faces, normalSum: normalSum.multiplyScalar(0.5), area, min, max };
}

function guessAxis({ faces, normalSum, area, min, max }: FaceSample, fileName: string): Omit<UpGuess, 'front'> & { kind: GuessKind } {
  if (!(area > 0)) return { axis: '+y', reason: 'no surface to guess from', kind: 'convention' };
  const extent = max.clone().sub(min);

  // One side of the surface faces one way: a relief or terrain when it is flat that way, else a
  // scan from one viewpoint (the rabbit scan read as a wavy sheet when taken for a relief).
  const agreement = normalSum.length() / area;
  if (agreement > 0.5) {
    const k = largestComponent(normalSum);
    const others = [0, 1, 2].filter((i) => i !== k).map((i) => extent.getComponent(i));
    if (extent.getComponent(k) <= RELIEF_THICKNESS * Math.min(...others)) {
      return { axis: axisOf(k, normalSum.getComponent(k)), reason: 'it is a relief: most of its surface faces this way', kind: 'relief' };
    }
    // Facing along Y it is taken for a steep relief in a Y-up file; along X or Z, for a scan.
    if (k === 1) return { axis: axisOf(k, normalSum.getComponent(k)), reason: 'most of its surface faces this way', kind: 'relief' };
    return { axis: '+y', reason: 'it is scanned from one side, and scanners look along −Z with +Y up', kind: 'scan' };
  }

  // A solid on a flat base: the largest flat area at an extreme, facing outwards.
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
    return { axis: up as Axis, reason: 'it stands on a flat base', kind: 'base' };
  }

  if (/\.(glb|gltf)$/i.test(fileName)) return { axis: '+y', reason: 'glTF files are Y-up', kind: 'convention' };
  if (extent.z > 1.2 * extent.y) return { axis: '+z', reason: 'it is taller along Z', kind: 'convention' };
  return { axis: '+y', reason: 'no clear sign; +Y is the usual default', kind: 'convention' };
}

/** The front (see the file comment) for a guessed up axis. */
function guessFront({ faces, normalSum, area, min, max }: FaceSample, guess: Omit<UpGuess, 'front'>): 1 | -1 {
  if (!(area > 0)) return 1;
  const up = axisVector(guess.axis);
  const depth = depthAxis(up);
  const depthExtent = Math.abs(max.clone().sub(min).dot(depth));
  if (!(depthExtent > 0)) return 1;
  // A scan from one side: the side it was scanned from.
  if (normalSum.length() / area > 0.5) return normalSum.dot(depth) < 0 ? -1 : 1;
  // The upper 30% against the whole, area-weighted, along the depth axis.
  const low = Math.min(min.dot(up), max.dot(up));
  const high = Math.max(min.dot(up), max.dot(up));
  const cut = high - 0.3 * (high - low);
  let all = 0, allArea = 0, top = 0, topArea = 0;
  const c = new Vector3();
  for (let f = 0; f < faces.length; f += 7) {
    c.set(faces[f + 4]!, faces[f + 5]!, faces[f + 6]!);
    const a = faces[f + 3]!;
    all += a * c.dot(depth);
    allArea += a;
    if (c.dot(up) >= cut) {
      top += a * c.dot(depth);
      topArea += a;
    }
  }
  if (!(topArea > 0)) return 1;
  const lean = (top / topArea - all / allArea) / depthExtent;
  return lean < -FRONT_LEAN ? -1 : 1;
}

function largestComponent(v: Vector3): number {
  const abs = [Math.abs(v.x), Math.abs(v.y), Math.abs(v.z)];
  return abs.indexOf(Math.max(...abs));
}

/** The bar's "Up" select: "Auto (guess)" or an axis the person picked, kept across files. */
export class UpAxisControl {
  private guess: UpGuess = { axis: '+y', reason: '', front: 1 };
  private readonly autoOption: HTMLOptionElement;

  constructor(
    private readonly select: HTMLSelectElement,
    /** Stands the view on an axis, looking at the front (1: the default side, −1: the other). */
    private readonly applyView: (axis: Axis, front: 1 | -1) => void,
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

  /** The guessed front holds for the guessed axis; another axis is seen from its default side. */
  private apply(axis: Axis): void {
    this.applyView(axis, axis === this.guess.axis ? this.guess.front : 1);
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
