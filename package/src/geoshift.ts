// The public API: createGeoshift() starts a worker and returns a Geoshift, one typed method per job.
// Both entries (index.ts for browsers and bundlers, node.ts for Node) call `create` with their
// platform; everything else is shared.

import { Client, type Ready, type Spawn } from './client.js';
import { GeoshiftError } from './errors.js';
import { meshArrays } from './mesh.js';
import { coreNames, type OpName, type OpOptions, type CurvatureOptions, type DenoiseOptions, type FilterOptions, type GeodesicOptions, type NoiseOptions, type SmoothOptions, type WaveletOptions } from './options.js';
import { arraysOf, transferables, type LoadInfo, type Params, type Response, type RunOutput } from './protocol.js';
import type { CallOptions, CreateOptions, GeoshiftInfo, GeoshiftMesh, Mesh, MeshResult, MeshUpdate, ReadOptions, ReadPart, ReadResult } from './types.js';
import { version } from './version.js';

/**
 * What differs between browsers and Node (platform-browser.ts, platform-node.ts).
 * @internal
 */
export interface Platform {
  /** Whether SharedArrayBuffer (and so the threaded build) is usable. */
  sharedMemory(): boolean;
  cores(): number;
  /** Said in info.note when threads were asked for and shared memory is missing. */
  noThreads: string;
  spawn: Spawn;
}

/** The module's files by flavour (wasm/CMakeLists.txt). */
const FILES = {
  single: ['geoshift_web.js', 'geoshift_web.wasm'],
  threaded: ['geoshift_web_mt.js', 'geoshift_web_mt.wasm'],
};

/** Threads of threads: 'auto': one per core up to this many (each pool worker instantiates the module). */
const AUTO_MAX_THREADS = 8;
const MAX_THREADS = 64;

/**
 * A started geoshift worker. Every job takes a mesh and options and resolves with fresh arrays in
 * the mesh's vertex layout; the input is never modified. Jobs run one after another in the worker,
 * in the order they were called. Spatial options (hs, radius, amount, ...) are in multiples of the
 * mesh's average edge length (AEL).
 */
export interface Geoshift {
  /** Which build runs, with how many threads, and what it knows. */
  readonly info: GeoshiftInfo;
  /**
   * Removes noise from a scanned surface, moving its vertices (the command-line tool's `denoise`).
   * The default method is the mean shift of the face normals with parameters it chooses itself.
   */
  denoise(mesh: Mesh, options?: DenoiseOptions & CallOptions): Promise<MeshResult>;
  /**
   * Riemannian mean shift of a vertex signal (`filter`): colors, normals, curvature, a terrain's
   * height or a named attribute; edges of the signal are kept, noise between them flattened.
   */
  filter(mesh: Mesh, options?: FilterOptions & CallOptions): Promise<MeshResult>;
  /** Discrete curvature per vertex as `_CURVATURE`, and a color map of it (`curvature`). */
  curvature(mesh: Mesh, options?: CurvatureOptions & CallOptions): Promise<MeshResult>;
  /** Taubin (lambda/mu) smoothing of the positions (`smooth`). */
  smooth(mesh: Mesh, options?: SmoothOptions & CallOptions): Promise<MeshResult>;
  /** Geodesic distance from a vertex, as `_GEODESIC` (-1 where not reached) (`geodesic`). */
  geodesic(mesh: Mesh, options?: GeodesicOptions & CallOptions): Promise<MeshResult>;
  /** Multiresolution smoothing (alpha < 1) or enhancement (alpha > 1) of positions and colors (`wavelet`). */
  wavelet(mesh: Mesh, options?: WaveletOptions & CallOptions): Promise<MeshResult>;
  /** Adds noise to the positions: test data for the denoisers (`noise`). */
  noise(mesh: Mesh, options?: NoiseOptions & CallOptions): Promise<MeshResult>;
  /**
   * Reads a file's bytes with the core's readers (OBJ, OFF, PLY, STL, glTF/GLB; the name's
   * extension picks one). A damaged file fails with kind 'input' and the command-line tool's
   * message, which names the file and the line, element or accessor.
   */
  read(bytes: Uint8Array | ArrayBuffer, name: string, options?: ReadOptions): Promise<ReadResult>;
  /**
   * Keeps a mesh in the worker for several runs (ops chain) and previews (which reuse a coarse level
   * analysed once). Meshes kept by a worker that was replaced (after a cancel without threads, or an
   * out-of-memory or internal error) are gone: their calls fail with kind 'input'.
   */
  load(mesh: Mesh, options?: CallOptions): Promise<GeoshiftMesh>;
  /** Ends the worker. Pending and later calls fail with kind 'cancelled'. */
  terminate(): void;
}

function check(condition: boolean, message: string): asserts condition {
  if (!condition) throw new GeoshiftError(message, 'input');
}

/** Splits call options from the op's parameters (in the core's names), checking the former. */
function split<T extends CallOptions>(options: T | undefined, what: string, op?: OpName): { params: Params; call: CallOptions } {
  if (options === undefined) return { params: {}, call: {} };
  check(typeof options === 'object' && options !== null && !Array.isArray(options), `${what}: options must be an object`);
  const { onProgress, signal, ...given } = options;
  check(onProgress === undefined || typeof onProgress === 'function', `${what}: onProgress must be a function`);
  const renamed = op ? coreNames[op] : undefined;
  const hint = renamed && Object.values(renamed).includes('signal') ? ` (the values to filter are option ${Object.keys(renamed).find((k) => renamed[k] === 'signal')})` : '';
  check(signal === undefined || (typeof AbortSignal !== 'undefined' && signal instanceof AbortSignal), `${what}: signal must be an AbortSignal${hint}`);
  const params: Params = {};
  for (const [name, value] of Object.entries(given)) params[renamed?.[name] ?? name] = value;
  return { params, call: { ...(onProgress ? { onProgress } : {}), ...(signal ? { signal } : {}) } };
}

function fileUrl(value: string | URL | undefined, file: string): string | undefined {
  if (value === undefined) return undefined;
  check(typeof value === 'string' || value instanceof URL, `locateFile("${file}") must return a string, a URL or undefined`);
  return String(value);
}

/**
 * Starts the worker on `platform`; the entries' createGeoshift.
 * @internal
 */
export async function create(platform: Platform, options: CreateOptions = {}): Promise<Geoshift> {
  check(typeof options === 'object' && options !== null, 'createGeoshift: options must be an object');
  const { threads = 'auto', locateFile, maxMemoryMB = 0 } = options;
  check(threads === 'auto' || (Number.isInteger(threads) && threads >= 1 && threads <= MAX_THREADS), `createGeoshift: threads must be 'auto' or a whole number from 1 to ${MAX_THREADS} (got ${String(threads)})`);
  check(locateFile === undefined || typeof locateFile === 'function', 'createGeoshift: locateFile must be a function');
  check(maxMemoryMB === 0 || (Number.isFinite(maxMemoryMB) && maxMemoryMB >= 64), `createGeoshift: maxMemoryMB must be at least 64 (got ${maxMemoryMB})`);
  const wanted = threads === 'auto' ? Math.min(platform.cores(), AUTO_MAX_THREADS) : threads;
  const threaded = wanted > 1 && platform.sharedMemory();
  const files: Record<string, string> = {};
  for (const file of FILES[threaded ? 'threaded' : 'single']) {
    const url = fileUrl(locateFile?.(file), file);
    if (url !== undefined) files[file] = url;
  }
  const client = new Client(platform.spawn, { threaded, threads: threaded ? wanted : 1, files, maxMemoryMB });
  let ready: Ready;
  try {
    ready = await client.ready();
  } catch (error) {
    client.terminate();
    throw error;
  }
  const note = wanted > 1 && !threaded ? platform.noThreads : undefined;
  return new GeoshiftWorker(client, { ...ready, ...(note ? { note } : {}), version });
}

class GeoshiftWorker implements Geoshift {
  constructor(
    private readonly client: Client,
    readonly info: GeoshiftInfo,
  ) {}

  denoise(mesh: Mesh, options?: DenoiseOptions & CallOptions): Promise<MeshResult> {
    return this.job('denoise', mesh, options);
  }
  filter(mesh: Mesh, options?: FilterOptions & CallOptions): Promise<MeshResult> {
    return this.job('filter', mesh, options);
  }
  curvature(mesh: Mesh, options?: CurvatureOptions & CallOptions): Promise<MeshResult> {
    return this.job('curvature', mesh, options);
  }
  smooth(mesh: Mesh, options?: SmoothOptions & CallOptions): Promise<MeshResult> {
    return this.job('smooth', mesh, options);
  }
  geodesic(mesh: Mesh, options?: GeodesicOptions & CallOptions): Promise<MeshResult> {
    return this.job('geodesic', mesh, options);
  }
  wavelet(mesh: Mesh, options?: WaveletOptions & CallOptions): Promise<MeshResult> {
    return this.job('wavelet', mesh, options);
  }
  noise(mesh: Mesh, options?: NoiseOptions & CallOptions): Promise<MeshResult> {
    return this.job('noise', mesh, options);
  }

  private async job(op: OpName, mesh: Mesh, options: CallOptions | undefined): Promise<MeshResult> {
    const { params, call } = split(options, op, op);
    const arrays = meshArrays(mesh);
    const response = await this.client.request({ type: 'job', op, params, ...arrays }, { ...call, transfer: transferables(arraysOf(arrays)) });
    const { output } = response as Extract<Response, { kind: 'job' }>;
    const result: MeshResult = { positions: output.positions, attributes: output.attributes, stats: output.stats, report: output.report };
    if (output.colors) result.colors = output.colors;
    if (output.normals) result.normals = output.normals;
    return result;
  }

  async read(bytes: Uint8Array | ArrayBuffer, name: string, options: ReadOptions = {}): Promise<ReadResult> {
    check(bytes instanceof Uint8Array || bytes instanceof ArrayBuffer, `read: bytes must be a Uint8Array or an ArrayBuffer`);
    check(typeof name === 'string' && name.length > 0, 'read: name must be the file name (its extension picks the format)');
    const { maxVertices = 0, meshes = true, ...rest } = options;
    check(maxVertices === 0 || (Number.isInteger(maxVertices) && maxVertices >= 1), `read: maxVertices must be a whole number of at least 1 (got ${maxVertices})`);
    const { call } = split(rest, 'read');
    const copy = bytes instanceof Uint8Array ? bytes.slice() : new Uint8Array(bytes.slice(0));
    const response = await this.client.request({ type: 'read', fileName: name, bytes: copy, maxVertices, arrays: meshes === true }, { ...call, transfer: [copy.buffer as ArrayBuffer] });
    const { info } = response as Extract<Response, { kind: 'read' }>;
    const parts = info.parts.map(({ label, vertices, triangles, instances, report, positions, indices, normals, colors, attributes, transforms }) => {
      const part: ReadPart = { label, vertices, triangles, instances, report };
      if (positions && indices) {
        part.mesh = { positions, indices, attributes: attributes ?? {} };
        if (normals) part.mesh.normals = normals;
        if (colors) part.mesh.colors = colors;
      }
      if (transforms) part.transforms = transforms;
      return part;
    });
    return { parts, vertices: info.vertices, triangles: info.triangles, warnings: info.warnings };
  }

  async load(mesh: Mesh, options?: CallOptions): Promise<GeoshiftMesh> {
    const { call } = split(options, 'load');
    const arrays = meshArrays(mesh);
    const meshId = `mesh ${++meshCounter}`;
    const response = await this.client.request({ type: 'load', meshId, ...arrays }, { ...call, transfer: transferables(arraysOf(arrays)) });
    // A load that ran has run in the current worker: a replacement would have failed it.
    return new KeptMesh(this.client, meshId, this.client.generation, (response as Extract<Response, { kind: 'load' }>).info);
  }

  terminate(): void {
    this.client.terminate();
  }
}

let meshCounter = 0;

class KeptMesh implements GeoshiftMesh {
  constructor(
    private readonly client: Client,
    private readonly meshId: string,
    private readonly generation: number,
    readonly info: LoadInfo,
  ) {}

  async run<Op extends OpName>(op: Op, options?: OpOptions[Op] & CallOptions): Promise<MeshUpdate> {
    const { params, call } = split(options, op, op);
    const response = await this.client.request({ type: 'run', meshId: this.meshId, op, params }, { ...call, generation: this.generation });
    return update((response as Extract<Response, { kind: 'run' }>).output);
  }

  async preview<Op extends OpName>(op: Op, options: OpOptions[Op] & CallOptions & { maxVertices: number }): Promise<MeshUpdate> {
    const { params, call } = split(options, op, op);
    const { maxVertices, ...opParams } = params;
    check(typeof maxVertices === 'number', `${op} preview: maxVertices must be a number`);
    const response = await this.client.request({ type: 'preview', meshId: this.meshId, op, params: opParams, maxVertices }, { ...call, generation: this.generation, soft: true });
    return update((response as Extract<Response, { kind: 'run' }>).output);
  }

  async free(): Promise<void> {
    try {
      await this.client.request({ type: 'free', meshId: this.meshId }, { generation: this.generation });
    } catch (error) {
      // Gone with a replaced worker: nothing left to free.
      if (this.generation !== this.client.generation) return;
      throw error;
    }
  }
}

function update(output: RunOutput): MeshUpdate {
  const result: MeshUpdate = { attributes: output.attributes, stats: output.stats };
  if (output.positions) result.positions = output.positions;
  if (output.colors) result.colors = output.colors;
  if (output.normals) result.normals = output.normals;
  return result;
}
