/**
 * three.js helpers (`geoshift/three`; three is a peer dependency): jobs on a BufferGeometry, indexed
 * or not, with any attribute layout three produces (interleaved, quantized, normalized). Each
 * returns a new geometry, a clone of the input with the job's positions, colors and attributes
 * filled and its normals recomputed where the positions moved; groups, draw range, morph targets,
 * other attributes and userData are kept. The input geometry is not modified.
 *
 * ```ts
 * import { createGeoshift } from 'geoshift';
 * import { denoiseGeometry } from 'geoshift/three';
 * mesh.geometry = await denoiseGeometry(gs, mesh.geometry);
 * ```
 * @packageDocumentation
 */

import { BufferAttribute, BufferGeometry } from 'three';

import { GeoshiftError } from './errors.js';
import type { Geoshift } from './geoshift.js';
import type { CurvatureOptions, DenoiseOptions, FilterOptions, GeodesicOptions, NoiseOptions, SmoothOptions, WaveletOptions } from './options.js';
import type { CallOptions, Mesh, MeshResult } from './types.js';

/** Attributes three gives a meaning of its own: not passed as signals. */
const STANDARD = /^(position|normal|color|tangent|uv\d*|skinIndex|skinWeight)$/;

/** An attribute as plain floats, itemSize per vertex (getComponent undoes normalization and interleaving). */
function floats(attribute: BufferGeometry['attributes'][string], itemSize = attribute.itemSize): Float32Array {
  const out = new Float32Array(attribute.count * itemSize);
  const size = Math.min(itemSize, attribute.itemSize);
  for (let i = 0; i < attribute.count; i++) {
    for (let k = 0; k < size; k++) out[i * itemSize + k] = attribute.getComponent(i, k);
  }
  return out;
}

/**
 * The geometry's arrays as a geoshift {@link Mesh}: positions, the index (none: a triangle soup),
 * vertex colors, and every other attribute of 1 to 16 numbers per vertex under its own name (not
 * normals, tangents, uvs or skinning: the filters take normals from the surface itself).
 */
export function geometryToMesh(geometry: BufferGeometry): Mesh & { indices?: Uint32Array } {
  const position = geometry.getAttribute('position');
  if (!position || position.itemSize !== 3) throw new GeoshiftError('the geometry needs a position attribute of 3 numbers per vertex', 'input');
  const mesh: Mesh & { indices?: Uint32Array } = { positions: floats(position) };
  if (geometry.index) mesh.indices = Uint32Array.from(geometry.index.array as ArrayLike<number>);
  const color = geometry.getAttribute('color');
  if (color) mesh.colors = floats(color, color.itemSize === 4 ? 4 : 3);
  const attributes: Record<string, Float32Array> = {};
  for (const [name, attribute] of Object.entries(geometry.attributes)) {
    if (STANDARD.test(name) || attribute.itemSize < 1 || attribute.itemSize > 16 || attribute.count !== position.count) continue;
    attributes[name] = floats(attribute);
  }
  if (Object.keys(attributes).length) mesh.attributes = attributes;
  return mesh;
}

/**
 * A clone of `geometry` with a job's result written in: positions (normals recomputed and bounds
 * updated when they moved), colors (the alpha of RGBA colors kept), filtered normals, and the
 * result's attributes under the core's names (`_CURVATURE`, `_GEODESIC`, ...).
 */
export function applyResult(geometry: BufferGeometry, result: Pick<MeshResult, 'positions' | 'colors' | 'normals' | 'attributes'>): BufferGeometry {
  const out = geometry.clone();
  const count = geometry.getAttribute('position').count;
  const moved = result.positions !== undefined && !sameValues(geometry, result.positions);
  if (result.positions) out.setAttribute('position', new BufferAttribute(result.positions, 3));
  if (result.colors) {
    const old = geometry.getAttribute('color');
    if (old && old.itemSize === 4) {
      const rgba = new Float32Array(4 * count);
      for (let i = 0; i < count; i++) {
        rgba.set(result.colors.subarray(3 * i, 3 * i + 3), 4 * i);
        rgba[4 * i + 3] = old.getComponent(i, 3);
      }
      out.setAttribute('color', new BufferAttribute(rgba, 4));
    } else {
      out.setAttribute('color', new BufferAttribute(result.colors, 3));
    }
  }
  for (const [name, values] of Object.entries(result.attributes)) out.setAttribute(name, new BufferAttribute(values, values.length / count));
  if (result.normals) out.setAttribute('normal', new BufferAttribute(result.normals, 3));
  else if (moved) out.computeVertexNormals();
  if (moved) {
    out.computeBoundingBox();
    out.computeBoundingSphere();
  }
  return out;
}

/** Whether `positions` are the geometry's own, as geometryToMesh gave them (float32 of any layout). */
function sameValues(geometry: BufferGeometry, positions: Float32Array): boolean {
  const old = geometry.getAttribute('position');
  for (let i = 0; i < old.count; i++) {
    for (let k = 0; k < 3; k++) if (Math.fround(old.getComponent(i, k)) !== positions[3 * i + k]) return false;
  }
  return true;
}

/** Removes noise from the geometry's surface ({@link Geoshift.denoise}). */
export async function denoiseGeometry(gs: Geoshift, geometry: BufferGeometry, options?: DenoiseOptions & CallOptions): Promise<BufferGeometry> {
  return applyResult(geometry, await gs.denoise(geometryToMesh(geometry), options));
}

/** Mean shift of a vertex signal: its colors, normals, curvature or an attribute by name ({@link Geoshift.filter}). */
export async function filterGeometry(gs: Geoshift, geometry: BufferGeometry, options?: FilterOptions & CallOptions): Promise<BufferGeometry> {
  return applyResult(geometry, await gs.filter(geometryToMesh(geometry), options));
}

/** Curvature as the attribute `_CURVATURE` and a color map of it in `color` ({@link Geoshift.curvature}). */
export async function curvatureGeometry(gs: Geoshift, geometry: BufferGeometry, options?: CurvatureOptions & CallOptions): Promise<BufferGeometry> {
  return applyResult(geometry, await gs.curvature(geometryToMesh(geometry), options));
}

/** Taubin smoothing of the positions ({@link Geoshift.smooth}). */
export async function smoothGeometry(gs: Geoshift, geometry: BufferGeometry, options?: SmoothOptions & CallOptions): Promise<BufferGeometry> {
  return applyResult(geometry, await gs.smooth(geometryToMesh(geometry), options));
}

/** Geodesic distance from a vertex as the attribute `_GEODESIC` ({@link Geoshift.geodesic}). */
export async function geodesicGeometry(gs: Geoshift, geometry: BufferGeometry, options?: GeodesicOptions & CallOptions): Promise<BufferGeometry> {
  return applyResult(geometry, await gs.geodesic(geometryToMesh(geometry), options));
}

/** Multiresolution smoothing or enhancement of positions and colors ({@link Geoshift.wavelet}). */
export async function waveletGeometry(gs: Geoshift, geometry: BufferGeometry, options?: WaveletOptions & CallOptions): Promise<BufferGeometry> {
  return applyResult(geometry, await gs.wavelet(geometryToMesh(geometry), options));
}

/** Noise added to the positions ({@link Geoshift.noise}). */
export async function noiseGeometry(gs: Geoshift, geometry: BufferGeometry, options?: NoiseOptions & CallOptions): Promise<BufferGeometry> {
  return applyResult(geometry, await gs.noise(geometryToMesh(geometry), options));
}

/** A BufferGeometry of a geoshift mesh (e.g. a part from {@link Geoshift.read}), normals computed when it has none. */
export function meshToGeometry(mesh: Mesh & { normals?: Float32Array }): BufferGeometry {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(mesh.positions, 3));
  if (mesh.indices) geometry.setIndex(new BufferAttribute(mesh.indices, 1));
  const count = mesh.positions.length / 3;
  if (mesh.colors) geometry.setAttribute('color', new BufferAttribute(mesh.colors, mesh.colors.length / count));
  for (const [name, values] of Object.entries(mesh.attributes ?? {})) geometry.setAttribute(name, new BufferAttribute(values, values.length / count));
  if (mesh.normals) geometry.setAttribute('normal', new BufferAttribute(mesh.normals, 3));
  else geometry.computeVertexNormals();
  return geometry;
}
