// Checks a caller's mesh at the JS edge and copies it for the worker (the copies are transferred,
// so the caller's arrays are never detached or modified). Messages name the field and the counts.

import { GeoshiftError } from './errors.js';
import type { MeshArrays } from './protocol.js';
import type { Mesh } from './types.js';

const MAX_ATTRIBUTE_DIM = 16; // setAttribute's limit (wasm/api.cpp)

function fail(message: string): never {
  throw new GeoshiftError(message, 'input');
}

function typeName(value: unknown): string {
  if (value === null) return 'null';
  if (typeof value !== 'object') return typeof value;
  return (value as object).constructor?.name ?? 'object';
}

function floats(value: unknown, what: string): Float32Array {
  if (!(value instanceof Float32Array)) fail(`${what} must be a Float32Array (got ${typeName(value)})`);
  return value;
}

/** Checked copies of a mesh's arrays, ready to transfer. */
export function meshArrays(mesh: Mesh, what = 'mesh'): MeshArrays {
  if (typeof mesh !== 'object' || mesh === null) fail(`${what} must be an object with positions (got ${typeName(mesh)})`);
  const positions = floats(mesh.positions, `${what}.positions`);
  if (positions.length % 3 !== 0) fail(`${what}.positions holds ${positions.length} numbers, not x, y, z per vertex`);
  const n = positions.length / 3;
  let indices: Uint32Array;
  if (mesh.indices === undefined) {
    if (n % 3 !== 0) fail(`${what} has no indices and ${n} vertices, not three per triangle`);
    indices = Uint32Array.from({ length: n }, (_, i) => i);
  } else if (mesh.indices instanceof Uint32Array || mesh.indices instanceof Uint16Array) {
    if (mesh.indices.length % 3 !== 0) fail(`${what}.indices holds ${mesh.indices.length} numbers, not three per triangle`);
    indices = Uint32Array.from(mesh.indices);
  } else {
    fail(`${what}.indices must be a Uint32Array or a Uint16Array (got ${typeName(mesh.indices)})`);
  }
  const arrays: MeshArrays = { positions: positions.slice(), indices };
  if (mesh.colors !== undefined) {
    const colors = floats(mesh.colors, `${what}.colors`);
    if (colors.length !== 3 * n && colors.length !== 4 * n) fail(`${what}.colors holds ${colors.length} numbers for ${n} vertices; give 3 (RGB) or 4 (RGBA) per vertex`);
    arrays.colors = colors.slice();
  }
  if (mesh.attributes !== undefined) {
    if (typeof mesh.attributes !== 'object' || mesh.attributes === null) fail(`${what}.attributes must be an object of Float32Arrays (got ${typeName(mesh.attributes)})`);
    arrays.attributes = {};
    for (const [name, value] of Object.entries(mesh.attributes)) {
      const label = `${what}.attributes["${name}"]`;
      const values = floats(value, label);
      if (name === '' || name === 'color' || name === 'normal') fail(`${label}: the name must not be empty, "color" or "normal" (colors go in colors; normals come from the geometry)`);
      const dim = n > 0 ? values.length / n : 0;
      if (!Number.isInteger(dim) || dim < 1 || dim > MAX_ATTRIBUTE_DIM) fail(`${label} holds ${values.length} numbers for ${n} vertices; give 1 to ${MAX_ATTRIBUTE_DIM} per vertex`);
      arrays.attributes[name] = values.slice();
    }
  }
  return arrays;
}
