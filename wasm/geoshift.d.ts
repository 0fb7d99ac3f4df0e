// Types of the geoshift WebAssembly module's exports, hand-written beside bindings.cpp: change both
// together. They describe every flavour:
//   geoshift_web.js / geoshift_web_mt.js    ES modules; the default export is the factory below
//                                           (createGeoshift / createGeoshiftMT).
//   geoshift_node.js / geoshift_node_mt.js  CommonJS; `module.exports` is the factory.
// From the web app: `import type { GeoshiftFactory, GeoshiftModule } from '../../wasm/geoshift';`
// then `const create: GeoshiftFactory = (await import(/* @vite-ignore */ url)).default;`.

/** What mesh construction found and repaired (geoshift::BuildReport). */
export interface BuildReport {
  inputVertices: number;
  inputFaces: number;
  /** Caller vertices merged into an earlier coincident one. */
  weldedVertices: number;
  /** Faces dropped because they use one vertex twice. */
  repeatedIndexFaces: number;
  /** Faces dropped because their corners are collinear. */
  zeroAreaFaces: number;
  /** Edges with more than two faces or inconsistent orientation; cut apart. */
  nonManifoldEdges: number;
  /** Vertices whose faces form several fans; split. */
  nonManifoldVertices: number;
  /** Vertices added by that split. */
  splitVertexCopies: number;
  /** Vertices no face uses; kept and left untouched. */
  isolatedVertices: number;
  /** One plain-language line per kind of problem, naming the first offending indices. */
  messages: string[];
}

export interface ProcessMeshSuccess {
  ok: true;
  /** Vertices of the welded (and repaired) mesh. */
  weldedVertexCount: number;
  /** Faces of that mesh (degenerate input faces dropped). */
  faceCount: number;
  /** Caller vertex -> mesh vertex; length = positions.length / 3. */
  vertexOf: Int32Array;
  report: BuildReport;
  /** Mean edge length of the welded mesh: the unit of every spatial parameter. */
  averageEdgeLength: number;
  /** Per caller vertex: mean curvature H, positive on a sphere with outward normals. */
  meanCurvature: Float32Array;
  /** Per caller vertex: Gaussian curvature K. */
  gaussianCurvature: Float32Array;
  /** Per caller vertex: |k1| + |k2| (MeshLab's "absolute" curvature). */
  absoluteCurvature: Float32Array;
}

/** Every call reports failure as a value; nothing throws across the boundary. */
export interface Failure {
  ok: false;
  /** The core's message, meant for the user as it is (names the face, vertex or index). */
  error: string;
}

export type ProcessMeshResult = ProcessMeshSuccess | Failure;

export interface GeoshiftModule {
  /**
   * Welds coincident vertices, builds the mesh and computes its discrete curvatures. The arrays are
   * copied in; the result's arrays are fresh copies that stay valid whatever the module does next.
   * @param positions x, y, z per vertex, in the caller's layout
   * @param indices three vertex indices per triangle, counter-clockwise from outside
   */
  processMesh(positions: Float32Array, indices: Uint32Array): ProcessMeshResult;
}

/** Emscripten module options the app may need; all optional. */
export interface GeoshiftModuleOptions {
  /** The .wasm bytes; required under Node for the CommonJS flavours (no fetch from a path). */
  wasmBinary?: ArrayBuffer | Uint8Array;
  /** Where the .wasm (and the threaded flavours' .worker.js) are; default: beside the .js. */
  locateFile?: (path: string, scriptDirectory: string) => string;
  /** Threaded flavours: the URL their pthread workers import the module from. */
  mainScriptUrlOrBlob?: string | Blob;
  print?: (text: string) => void;
  printErr?: (text: string) => void;
}

export type GeoshiftFactory = (options?: GeoshiftModuleOptions) => Promise<GeoshiftModule>;

declare const createGeoshift: GeoshiftFactory;
export default createGeoshift;
