// glTF 2.0 (.glb and .gltf) through three's GLTFLoader, after a structural check of our own.
//
// The check exists because GLTFLoader's failures on bad input read poorly ("Unexpected token" from
// JSON.parse, a fetch of some relative URL against the page's origin) and because a single dropped
// file cannot carry the .bin or images a .gltf may point to: we name the missing file instead of
// letting the loader request it from our server.

import { Group } from 'three';
import { DRACO_GLTF_CONFIG, DRACOLoader } from 'three/examples/jsm/loaders/DRACOLoader.js';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { MeshoptDecoder } from 'three/examples/jsm/libs/meshopt_decoder.module.js';
import { LoadError } from './load-error';

const GLB_MAGIC = 0x46546c67; // "glTF"
const CHUNK_JSON = 0x4e4f534a; // "JSON"
const CHUNK_BIN = 0x004e4942; // "BIN\0"

interface GltfJson {
  asset?: { version?: unknown };
  extensionsUsed?: unknown;
  extensionsRequired?: unknown;
  buffers?: Array<{ uri?: unknown; byteLength?: unknown }>;
  images?: Array<{ uri?: unknown }>;
}

function isGlb(data: ArrayBuffer): boolean {
  return data.byteLength >= 4 && new DataView(data).getUint32(0, true) === GLB_MAGIC;
}

function parseJson(text: string): GltfJson {
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch (e) {
    throw new LoadError(`its glTF JSON is malformed (${e instanceof Error ? e.message : String(e)})`);
  }
  if (typeof json !== 'object' || json === null || Array.isArray(json)) {
    throw new LoadError('its glTF JSON is not an object');
  }
  return json as GltfJson;
}

/** Reads the JSON of a GLB after checking the container: signature, version, lengths, chunks. */
function readGlbJson(data: ArrayBuffer): { json: GltfJson; binLength: number } {
  const view = new DataView(data);
  if (data.byteLength < 20) throw new LoadError('the file is too short to be a GLB');
  const version = view.getUint32(4, true);
  if (version !== 2) throw new LoadError(`it is glTF version ${version}; only glTF 2.0 is supported`);
  const length = view.getUint32(8, true);
  if (length > data.byteLength) {
    throw new LoadError(`the file is truncated (the GLB header says ${length} bytes, the file has ${data.byteLength})`);
  }
  const jsonLength = view.getUint32(12, true);
  if (view.getUint32(16, true) !== CHUNK_JSON || 20 + jsonLength > length) {
    throw new LoadError('the GLB has no valid JSON chunk; the file is probably damaged');
  }
  const json = parseJson(new TextDecoder().decode(new Uint8Array(data, 20, jsonLength)));
  let binLength = -1;
  const binStart = 20 + jsonLength;
  if (binStart + 8 <= length && view.getUint32(binStart + 4, true) === CHUNK_BIN) {
    binLength = Math.min(view.getUint32(binStart, true), length - binStart - 8);
  }
  return { json, binLength };
}

function externalUri(uri: unknown): string | null {
  if (typeof uri !== 'string' || uri.startsWith('data:')) return null;
  try {
    return decodeURIComponent(uri);
  } catch {
    return uri;
  }
}

/** Rejects what GLTFLoader could not load from a single file, with the reason in plain words. */
function checkJson(json: GltfJson, binLength: number): void {
  const version = json.asset?.version;
  if (typeof version !== 'string' || !version.startsWith('2.')) {
    throw new LoadError(`it is not glTF 2.0 (asset.version is ${JSON.stringify(version ?? null)})`);
  }
  for (const [i, buffer] of (json.buffers ?? []).entries()) {
    const missing = externalUri(buffer.uri);
    if (missing !== null) {
      throw new LoadError(`it needs the separate file "${missing}", which was not given; open a .glb or a .gltf with embedded data instead`);
    }
    // In a GLB the first buffer without uri is the BIN chunk.
    if (buffer.uri === undefined && i === 0 && typeof buffer.byteLength === 'number' && binLength < buffer.byteLength) {
      throw new LoadError('its binary chunk is missing or shorter than the glTF JSON says; the file is probably truncated');
    }
  }
  for (const image of json.images ?? []) {
    const missing = externalUri(image.uri);
    if (missing !== null) {
      throw new LoadError(`it needs the separate image "${missing}", which was not given; open a .glb or a .gltf with embedded data instead`);
    }
  }
}

let loader: GLTFLoader | null = null;

function startsLikeJson(data: ArrayBuffer): boolean {
  const head = new TextDecoder().decode(new Uint8Array(data, 0, Math.min(64, data.byteLength)));
  return head.trimStart().startsWith('{');
}

/**
 * Parses .glb or .gltf bytes into a scene. The content decides between binary and JSON glTF, so a
 * misnamed file still opens; a .glb that is neither is reported as not a GLB.
 */
export async function parseGltf(data: ArrayBuffer, extension: '.glb' | '.gltf'): Promise<Group> {
  if (isGlb(data)) {
    const { json, binLength } = readGlbJson(data);
    checkJson(json, binLength);
  } else if (extension === '.glb' && !startsLikeJson(data)) {
    throw new LoadError('it is not a GLB file (it does not start with the glTF signature)');
  } else {
    checkJson(parseJson(new TextDecoder().decode(data)), -1);
  }
  if (!loader) {
    loader = new GLTFLoader();
    // The meshopt decoder is plain JS+wasm embedded in the three package: no extra files to serve.
    loader.setMeshoptDecoder(MeshoptDecoder);
    // The Draco decoder (three/examples/jsm/libs/draco/gltf) is referenced by DRACOLoader through
    // `new URL(..., import.meta.url)`, so Vite serves it and copies it into dist/ like any asset:
    // never a CDN, so files stay local and the page works offline and under COEP.
    loader.setDRACOLoader(new DRACOLoader().setDecoderPath(DRACO_GLTF_CONFIG));
  }
  const gltf = await loader.parseAsync(data, './');
  // A glTF without scenes is valid (a library of meshes) but has nothing to show.
  return gltf.scene ?? new Group();
}
