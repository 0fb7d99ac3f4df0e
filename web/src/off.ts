// Parser for Geomview's OFF format and its common variants (COFF, NOFF, CNOFF, STOFF...), the
// format CGAL and many research data sets use. three.js ships no OFF loader.
//
// Layout: an optional header keyword, then "nVertices nFaces nEdges", then one vertex per line
// ("x y z [nx ny nz] [r g b [a]] [s t]") and one face per line ("n i0 i1 ... [face color]").
// '#' starts a comment. Polygons are fan-triangulated; faces with fewer than three corners (points,
// edges) are skipped. Face colors are ignored: the app works with per-vertex signals.

import { counted } from './words';

/** A parsed OFF mesh as flat arrays, independent of three.js so that it can be tested alone. */
export interface OffMesh {
  /** x, y, z per vertex. */
  positions: Float32Array;
  /** Three vertex indices per triangle. */
  indices: Uint32Array;
  /** nx, ny, nz per vertex (NOFF), or null. */
  normals: Float32Array | null;
  /** r, g, b per vertex in [0, 1], sRGB as stored in the file (COFF), or null. */
  colors: Float32Array | null;
  /** Faces as listed in the file, before triangulation. */
  faceCount: number;
}

/** Thrown for anything that is not a well-formed OFF file; the message is meant for users. */
export class OffError extends Error {
  override name = 'OffError';
}

const HEADER = /^(ST)?(C)?(N)?(4)?(n)?OFF$/;

/** A cursor over the non-empty, comment-stripped lines, remembering line numbers for messages. */
class Lines {
  private readonly lines: string[];
  private next = 0;
  lineNumber = 0;

  constructor(text: string) {
    this.lines = text.split(/\r\n|\r|\n/);
  }

  /** Tokens of the next line that holds any, or null at the end of the file. */
  tokens(): string[] | null {
    while (this.next < this.lines.length) {
      const raw = this.lines[this.next++] ?? '';
      const hash = raw.indexOf('#');
      const line = (hash >= 0 ? raw.slice(0, hash) : raw).trim();
      if (line.length > 0) {
        this.lineNumber = this.next;
        return line.split(/\s+/);
      }
    }
    return null;
  }
}

function number(token: string | undefined, what: string, lines: Lines): number {
  const value = token === undefined ? NaN : Number(token);
  if (!Number.isFinite(value)) {
    const found = token === undefined ? 'the line ends' : `found "${token}"`;
    throw new OffError(`line ${lines.lineNumber}: expected ${what}, but ${found}`);
  }
  return value;
}

function count(token: string | undefined, what: string, lines: Lines): number {
  const value = number(token, `the number of ${what}`, lines);
  if (!Number.isInteger(value) || value < 0) {
    throw new OffError(`line ${lines.lineNumber}: the number of ${what} must be a whole number, not "${token}"`);
  }
  return value;
}

/**
 * Parses OFF text. Throws OffError with the offending line number on malformed input, on a face
 * that refers to a vertex that does not exist, and on variants it cannot read (binary OFF,
 * 4D or n-dimensional vertices).
 */
export function parseOff(text: string): OffMesh {
  const lines = new Lines(text);
  let tokens = lines.tokens();
  if (tokens === null) throw new OffError('the file is empty');

  // The keyword is optional in Geomview's spec; without it the first line holds the counts.
  let hasNormals = false;
  let hasColors = false;
  let hasTexCoords = false;
  const keyword = HEADER.exec(tokens[0] ?? '');
  if (keyword) {
    if (keyword[4] || keyword[5]) {
      throw new OffError(`"${tokens[0]}" files (vertices with more than three coordinates) are not supported`);
    }
    if (tokens[1] === 'BINARY') throw new OffError('binary OFF files are not supported; save it as text OFF');
    hasTexCoords = keyword[1] !== undefined;
    hasColors = keyword[2] !== undefined;
    hasNormals = keyword[3] !== undefined;
    tokens = tokens.length > 1 ? tokens.slice(1) : lines.tokens();
    if (tokens === null) throw new OffError('the file ends after the OFF keyword; expected vertex and face counts');
  } else if (!/^\d+$/.test(tokens[0] ?? '')) {
    throw new OffError(`line ${lines.lineNumber}: expected the OFF keyword or vertex and face counts, found "${tokens[0]}"`);
  }
  const vertexCount = count(tokens[0], 'vertices', lines);
  const faceCount = count(tokens[1], 'faces', lines);

  const positions = new Float32Array(vertexCount * 3);
  const normals = hasNormals ? new Float32Array(vertexCount * 3) : null;
  const colors = hasColors ? new Float32Array(vertexCount * 3) : null;
  for (let v = 0; v < vertexCount; v++) {
    const t = lines.tokens();
    if (t === null) {
      throw new OffError(`the header announces ${counted(vertexCount, 'vertex', 'vertices')}, but the file ends after ${v}`);
    }
    for (let k = 0; k < 3; k++) positions[3 * v + k] = number(t[k], `3 vertex coordinates`, lines);
    let at = 3;
    if (normals) {
      for (let k = 0; k < 3; k++) normals[3 * v + k] = number(t[at + k], 'a vertex normal (nx ny nz)', lines);
      at += 3;
    }
    if (colors) readColor(t.slice(at, hasTexCoords ? t.length - 2 : t.length), colors, v, lines);
  }

  const triangles: number[] = [];
  for (let f = 0; f < faceCount; f++) {
    const t = lines.tokens();
    if (t === null) throw new OffError(`the header announces ${faceCount} faces, but the file ends after ${f}`);
    const corners = count(t[0], 'face corners', lines);
    const face: number[] = [];
    for (let k = 1; k <= corners; k++) {
      const index = number(t[k], `${corners} vertex indices`, lines);
      if (!Number.isInteger(index) || index < 0 || index >= vertexCount) {
        throw new OffError(
          `line ${lines.lineNumber}: face ${f} refers to vertex ${t[k]}, but the file has ${counted(vertexCount, 'vertex', 'vertices')} (0 to ${vertexCount - 1})`,
        );
      }
      face.push(index);
    }
    for (let k = 1; k + 1 < face.length; k++) triangles.push(face[0]!, face[k]!, face[k + 1]!);
  }

  return { positions, indices: Uint32Array.from(triangles), normals, colors, faceCount };
}

/**
 * Geomview: integer components are 0..255, floating-point ones 0..1; alpha is optional and
 * dropped. A single value is a colormap index, which we cannot resolve: it reads as mid grey.
 */
function readColor(t: string[], colors: Float32Array, v: number, lines: Lines): void {
  if (t.length === 1) {
    colors.fill(0.5, 3 * v, 3 * v + 3);
    return;
  }
  if (t.length !== 3 && t.length !== 4) {
    throw new OffError(`line ${lines.lineNumber}: expected a vertex color (r g b or r g b a) after the coordinates`);
  }
  const integers = t.every((s) => /^[+-]?\d+$/.test(s));
  for (let k = 0; k < 3; k++) {
    const c = number(t[k], 'a color component', lines);
    colors[3 * v + k] = Math.min(1, Math.max(0, integers ? c / 255 : c));
  }
}
