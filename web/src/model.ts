// The meshes of the open file as the filters see them: their arrays for the worker, their state
// before the last change (for before/after), the original (for revert) and the positions before
// noise was added (for the error figure). Results are written into the meshes' own geometry, in
// the file's vertex layout, so export writes them where the file had its vertices.

import { BufferAttribute, type BufferGeometry, type Mesh } from 'three';
import { geometryToMesh } from 'geoshift/three';
import type { MeshArrays, RunOutput } from './worker/client';
import { SCALAR_COLOR } from './materials';

export interface MeshState {
  /** Worker-side name; unique per mesh and file. */
  id: string;
  mesh: Mesh;
  original: BufferGeometry;
  before: BufferGeometry | null;
  /** Positions when noise was first added since the last load/revert; null without noise. */
  preNoise: Float32Array | null;
  /** Positions of a clean original that came with the file (a gallery case); kept across reverts. */
  reference: Float32Array | null;
  /**
   * While a live preview is on screen, the mesh's own geometry (mesh.geometry is then a copy with
   * the preview applied); runs, export and revert work on this one (baseGeometry).
   */
  previewBase: BufferGeometry | null;
}

/** The mesh's own geometry, whether or not a preview is on screen. */
export function baseGeometry(state: MeshState): BufferGeometry {
  return state.previewBase ?? state.mesh.geometry;
}

/** Takes a preview off screen: the mesh gets its own geometry back. */
export function dropPreview(state: MeshState): void {
  if (!state.previewBase) return;
  state.mesh.geometry.dispose();
  state.mesh.geometry = state.previewBase;
  state.previewBase = null;
}

let counter = 0;

export function meshStates(meshes: Mesh[]): MeshState[] {
  const file = ++counter;
  return meshes.map((mesh, i) => ({ id: `${file}:${i}`, mesh, original: mesh.geometry.clone(), before: null, preNoise: null, reference: null, previewBase: null }));
}

/** Scalar attributes of a geometry (one number per vertex, not one of three's standard ones). */
export function scalarNames(geometry: BufferGeometry): string[] {
  return Object.keys(geometry.attributes).filter((name) => geometry.getAttribute(name).itemSize === 1 && name !== SCALAR_COLOR);
}

/** The arrays the worker needs, as fresh copies it may keep (the package's conversion of any layout three produces). */
export function meshArrays(geometry: BufferGeometry): MeshArrays & { scalars: Record<string, Float32Array> } {
  const { positions, indices, colors, attributes = {} } = geometryToMesh(geometry);
  const arrays: MeshArrays & { scalars: Record<string, Float32Array> } = { positions, scalars: {} };
  if (indices) arrays.indices = indices;
  if (colors) arrays.colors = colors;
  for (const name of scalarNames(geometry)) if (attributes[name]) arrays.scalars[name] = attributes[name];
  return arrays;
}

/** Keeps the current geometry as "before" for the comparison. */
export function snapshot(state: MeshState): void {
  state.before?.dispose();
  state.before = state.mesh.geometry.clone();
}

/** Writes an op's output into the mesh's geometry. Colors only when the op filtered the colors. */
export function applyOutput(state: MeshState, output: RunOutput, replaceColors: boolean): void {
  const geometry = state.mesh.geometry;
  if (output.positions) {
    geometry.setAttribute('position', new BufferAttribute(output.positions, 3));
    // The file's normals were for the old shape; three computes them as the CLI does (per caller
    // vertex, seams kept).
    geometry.computeVertexNormals();
    geometry.computeBoundingSphere();
    geometry.computeBoundingBox();
  }
  if (output.colors && replaceColors) geometry.setAttribute('color', new BufferAttribute(output.colors, 3));
  // glTF custom attributes come out of three's loader lower-cased; results use the same spelling.
  for (const [name, values] of Object.entries(output.scalars)) geometry.setAttribute(name.toLowerCase(), new BufferAttribute(values, 1));
}

export function revert(state: MeshState): void {
  state.before?.dispose();
  state.before = state.mesh.geometry;
  state.mesh.geometry = state.original.clone();
  state.preNoise = state.reference;
}

/** RMS vertex distance between two position arrays, and the bounding-box diagonal of `b`. */
export function rmsError(a: Float32Array, b: Float32Array): { rms: number; diagonal: number } {
  let sum = 0;
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < a.length; i++) {
    const d = a[i]! - b[i]!;
    sum += d * d;
    const k = i % 3;
    min[k] = Math.min(min[k]!, b[i]!);
    max[k] = Math.max(max[k]!, b[i]!);
  }
  const diagonal = Math.hypot(max[0]! - min[0]!, max[1]! - min[1]!, max[2]! - min[2]!);
  return { rms: Math.sqrt(sum / Math.max(1, a.length / 3)), diagonal };
}
