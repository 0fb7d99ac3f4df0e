// Exact vertex welding for triangle soups. STL stores three separate corners per triangle and
// OBJLoader expands every face corner, so without welding a mesh has no shared vertices: smooth
// normals cannot be computed, the vertex count is three times the triangle count, and the filters
// would see disconnected triangles.
//
// Only bit-identical corners are merged (all attributes equal, not just positions), unlike
// BufferGeometryUtils.mergeVertices, whose tolerance is absolute and would merge distinct vertices of
// a model measured in metres at millimetre detail, or fail to merge anything at kilometre scale.

import { BufferAttribute, BufferGeometry } from 'three';

type Numbers = ArrayLike<number> & { length: number };

const scratch = new Float64Array(1);
const scratchBits = new Uint32Array(scratch.buffer);

function hashVertex(arrays: Numbers[], sizes: number[], vertex: number): number {
  let h = 0x811c9dc5;
  for (let a = 0; a < arrays.length; a++) {
    const array = arrays[a]!;
    const size = sizes[a]!;
    for (let k = 0; k < size; k++) {
      // +0 turns -0 into 0 so that both hash alike, as they compare equal below.
      scratch[0] = array[vertex * size + k]! + 0;
      h = Math.imul(h ^ scratchBits[0]!, 0x01000193);
      h = Math.imul(h ^ scratchBits[1]!, 0x01000193);
    }
  }
  return h >>> 0;
}

function sameVertex(arrays: Numbers[], sizes: number[], a: number, b: number): boolean {
  for (let i = 0; i < arrays.length; i++) {
    const array = arrays[i]!;
    const size = sizes[i]!;
    for (let k = 0; k < size; k++) {
      if (array[a * size + k] !== array[b * size + k]) return false;
    }
  }
  return true;
}

/**
 * Returns an indexed copy of a non-indexed geometry in which identical corners share one vertex.
 * Every attribute takes part in the comparison, so seams in normals, UVs or colors stay split as the
 * file had them. Indexed geometries are returned unchanged. Interleaved attributes are not expected
 * from the loaders that call this and are rejected.
 */
export function weld(geometry: BufferGeometry): BufferGeometry {
  if (geometry.index) return geometry;
  const names = Object.keys(geometry.attributes);
  const attributes = names.map((name) => {
    const attribute = geometry.getAttribute(name);
    if (!(attribute instanceof BufferAttribute)) throw new Error(`cannot weld interleaved attribute "${name}"`);
    return attribute;
  });
  const arrays = attributes.map((a) => a.array as Numbers);
  const sizes = attributes.map((a) => a.itemSize);
  const corners = geometry.getAttribute('position').count;

  // Open addressing with linear probing; the table holds first-seen corner ids (+1, 0 = empty).
  let capacity = 1;
  while (capacity < corners * 2) capacity *= 2;
  const table = new Int32Array(capacity);
  const remap = new Uint32Array(corners);
  const firstCorner: number[] = [];
  for (let c = 0; c < corners; c++) {
    let slot = hashVertex(arrays, sizes, c) & (capacity - 1);
    for (;;) {
      const held = table[slot]!;
      if (held === 0) {
        table[slot] = c + 1;
        remap[c] = firstCorner.length;
        firstCorner.push(c);
        break;
      }
      if (sameVertex(arrays, sizes, held - 1, c)) {
        remap[c] = remap[held - 1]!;
        break;
      }
      slot = (slot + 1) & (capacity - 1);
    }
  }

  const welded = new BufferGeometry();
  names.forEach((name, i) => {
    const source = attributes[i]!;
    const size = sizes[i]!;
    const Ctor = source.array.constructor as new (n: number) => typeof source.array;
    const out = new Ctor(firstCorner.length * size);
    firstCorner.forEach((c, v) => {
      for (let k = 0; k < size; k++) out[v * size + k] = source.array[c * size + k]!;
    });
    welded.setAttribute(name, new BufferAttribute(out, size, source.normalized));
  });
  welded.setIndex(new BufferAttribute(remap, 1));
  for (const group of geometry.groups) welded.addGroup(group.start, group.count, group.materialIndex);
  return welded;
}
