// Opens a mesh file by extension and returns what the viewer shows: an Object3D whose meshes have
// indexed-or-welded triangle geometry, normals, and validated positions.

import { BufferAttribute, BufferGeometry, Color, Group, Mesh, SRGBColorSpace, type Object3D } from 'three';
import { LoadError } from './load-error';
import { markClosed } from './materials';
import { OffError, parseOff, type OffMesh } from './off';
import { weld } from './weld';

export { LoadError };

/** Extensions the file picker offers; keep in sync with the accept attribute in index.html. */
export const SUPPORTED_EXTENSIONS = ['.glb', '.gltf', '.obj', '.ply', '.stl', '.off'] as const;

export interface MeshCounts {
  vertices: number;
  triangles: number;
}

export interface LoadedModel {
  /** Root to add to the scene; node transforms from the file are kept. */
  root: Object3D;
  /** The triangle meshes under root (points and lines in a file are not shown). */
  meshes: Mesh[];
  counts: MeshCounts;
  /** True when at least one mesh has a per-vertex color attribute. */
  hasVertexColors: boolean;
}

function extensionOf(name: string): string {
  const dot = name.lastIndexOf('.');
  return dot < 0 ? '' : name.slice(dot).toLowerCase();
}

function decodeText(data: ArrayBuffer, format: string): string {
  const text = new TextDecoder().decode(data);
  // A NUL byte never occurs in these text formats; it means a binary (or wrong) file.
  if (text.includes('\0')) throw new LoadError(`it is not a text ${format} file`);
  return text;
}

function offToGeometry(off: OffMesh): BufferGeometry {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(off.positions, 3));
  geometry.setIndex(new BufferAttribute(off.indices, 1));
  if (off.normals) geometry.setAttribute('normal', new BufferAttribute(off.normals, 3));
  if (off.colors) {
    // Files store display (sRGB) colors; three shades vertex colors in linear space.
    const color = new Color();
    const linear = new Float32Array(off.colors.length);
    for (let i = 0; i < linear.length; i += 3) {
      color.setRGB(off.colors[i]!, off.colors[i + 1]!, off.colors[i + 2]!, SRGBColorSpace);
      linear[i] = color.r;
      linear[i + 1] = color.g;
      linear[i + 2] = color.b;
    }
    geometry.setAttribute('color', new BufferAttribute(linear, 3));
  }
  return geometry;
}

function single(geometry: BufferGeometry): Group {
  const group = new Group();
  group.add(new Mesh(geometry));
  return group;
}

// Format loaders other than OFF are imported on first use: the startup sample is OFF, so the page
// shows it without downloading GLTFLoader and friends.
async function parseByExtension(extension: string, data: ArrayBuffer): Promise<Object3D> {
  switch (extension) {
    case '.glb':
    case '.gltf': {
      const { parseGltf } = await import('./gltf');
      return parseGltf(data, extension);
    }
    case '.off':
      try {
        return single(offToGeometry(parseOff(decodeText(data, 'OFF'))));
      } catch (e) {
        throw e instanceof OffError ? new LoadError(e.message) : e;
      }
    case '.obj': {
      const { OBJLoader } = await import('three/examples/jsm/loaders/OBJLoader.js');
      const text = decodeText(data, 'OBJ');
      const root = new OBJLoader().parse(text);
      // Without "vn" lines OBJLoader fills in per-face normals, which would keep every corner apart
      // when welding; smooth normals are computed after welding instead.
      const hasNormals = /^\s*vn\s/m.test(text);
      root.traverse((object) => {
        if (!(object instanceof Mesh)) return;
        if (!hasNormals) object.geometry.deleteAttribute('normal');
        object.geometry = weld(object.geometry);
      });
      return root;
    }
    case '.ply': {
      const { PLYLoader } = await import('three/examples/jsm/loaders/PLYLoader.js');
      return single(new PLYLoader().parse(data));
    }
    case '.stl': {
      const { STLLoader } = await import('three/examples/jsm/loaders/STLLoader.js');
      // STL normals are per face; dropping them lets identical corners weld and get smooth normals.
      const geometry = new STLLoader().parse(data);
      geometry.deleteAttribute('normal');
      return single(weld(geometry));
    }
    default:
      throw new LoadError(
        `${extension ? `"${extension}" files are` : 'files without an extension are'} not supported; open one of ${SUPPORTED_EXTENSIONS.join(' ')}`,
      );
  }
}

/** Checks what a corrupt file would otherwise turn into a blank screen or NaN bounding sphere. */
function validate(geometry: BufferGeometry): void {
  const position = geometry.getAttribute('position');
  if (!position || position.itemSize !== 3) throw new LoadError('a mesh in it has no vertex positions');
  for (let i = 0; i < position.count; i++) {
    if (!Number.isFinite(position.getX(i) + position.getY(i) + position.getZ(i))) {
      throw new LoadError(`vertex ${i} has an invalid position (not a number); the file is probably damaged`);
    }
  }
  const index = geometry.index;
  if (index) {
    for (let i = 0; i < index.count; i++) {
      if (index.getX(i) >= position.count) {
        throw new LoadError(`triangle ${Math.floor(i / 3)} refers to vertex ${index.getX(i)}, but there are only ${position.count}`);
      }
    }
  }
}

function triangleCount(geometry: BufferGeometry): number {
  const corners = geometry.index ? geometry.index.count : geometry.getAttribute('position').count;
  return Math.floor(corners / 3);
}

/**
 * Validates and completes one mesh's geometry in place. The vertex layout is kept as loaded (only
 * OBJ and STL triangle soups are welded, above): results of the filters must map one for one onto
 * the file's own glTF/PLY/OFF vertices. A non-indexed glTF without normals thus gets flat normals,
 * as the glTF spec asks.
 */
function prepare(mesh: Mesh): void {
  const geometry = mesh.geometry;
  validate(geometry);
  if (!geometry.getAttribute('normal')) geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
  if (isClosed(geometry)) markClosed(mesh);
}

/**
 * Whether a surface is closed (at most 0.1% of its edges on a border, as a scan with a few tiny
 * holes): the view then draws the outside only (materials.ts). Edges are compared by vertex index,
 * so a non-indexed soup counts as open.
 */
export function isClosed(geometry: BufferGeometry): boolean {
  const index = geometry.index;
  if (!index || index.count < 3) return false;
  const n = geometry.getAttribute('position').count;
  // Undirected edges as numbers (lower * n + higher, exact below 2^53), sorted: an edge seen once
  // lies on a border.
  const keys = new Float64Array(index.count - (index.count % 3));
  for (let t = 0; t < keys.length; t += 3) {
    for (let k = 0; k < 3; k++) {
      const a = index.getX(t + k);
      const b = index.getX(t + ((k + 1) % 3));
      keys[t + k] = Math.min(a, b) * n + Math.max(a, b);
    }
  }
  keys.sort();
  let border = 0;
  let edges = 0;
  for (let i = 0; i < keys.length; ) {
    let j = i + 1;
    while (j < keys.length && keys[j] === keys[i]) j++;
    edges++;
    if (j - i === 1) border++;
    i = j;
  }
  return border <= 0.001 * edges;
}

/**
 * Parses a mesh file. The extension picks the format (glTF is further recognized by content).
 * Throws LoadError with a plain-words reason; other exceptions from three's loaders are
 * reworded by describeLoadFailure.
 */
export async function loadModel(fileName: string, data: ArrayBuffer): Promise<LoadedModel> {
  const root = await parseByExtension(extensionOf(fileName), data);
  const meshes: Mesh[] = [];
  root.traverse((object) => {
    if (object instanceof Mesh && object.geometry instanceof BufferGeometry) meshes.push(object);
  });
  for (const mesh of meshes) prepare(mesh);
  const withTriangles = meshes.filter((mesh) => triangleCount(mesh.geometry) > 0);
  if (withTriangles.length === 0) {
    throw new LoadError('it contains no triangles (is it a point cloud, a line drawing, or damaged?)');
  }
  const counts: MeshCounts = { vertices: 0, triangles: 0 };
  for (const mesh of withTriangles) {
    counts.vertices += mesh.geometry.getAttribute('position').count;
    counts.triangles += triangleCount(mesh.geometry);
  }
  const hasVertexColors = withTriangles.some((mesh) => mesh.geometry.getAttribute('color') !== undefined);
  return { root, meshes: withTriangles, counts, hasVertexColors };
}

/** The reason part of "Could not read NAME: REASON" for any error thrown while loading. */
export function describeLoadFailure(error: unknown): string {
  if (error instanceof LoadError) return error.message;
  // Typed array allocation failures (RangeError) mean the tab ran out of memory, not a bad file.
  if (error instanceof RangeError && /alloc|memory|Invalid array length|Invalid typed array length/i.test(error.message)) {
    return 'it is too large for the memory this browser tab may use (try a smaller file, or the command-line tool)';
  }
  // Anything else is an exception of three's loaders or of the browser, whose text ("Cannot read
  // properties of undefined ...") means nothing to users: it goes to the console, the page says
  // what failed.
  console.error('geoshift: the loader failed', error);
  return 'the file is damaged or not in the format its extension says (the loader stopped on it; details in the browser console)';
}
