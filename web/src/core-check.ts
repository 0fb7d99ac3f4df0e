// A file the user opens goes through the core's own readers first, in the worker (readFile, the
// CLI's readers compiled to wasm): a damaged file is refused with the CLI's message, word for word,
// before three's loaders see it. What the core accepts is then shown through three's loaders as
// before (glTF scenes keep their materials for export). docs/io.md#the-app.
//
// Compressed glTF (Draco, meshopt) is the exception: the app decodes it with three's decoders, the
// core cannot, so such files skip this check and keep the app's own (gltf.ts).

import { LoadError } from './load-error';
import { GeoshiftError } from 'geoshift';
import type { ReadInfo } from './worker/client';

/** The worker client's part used here (client.ts). */
export interface CoreReader {
  ready(): Promise<unknown>;
  read(fileName: string, bytes: ArrayBuffer): Promise<ReadInfo>;
}

/**
 * The core refused the file. The message is the CLI's, which begins with the file's name (and a
 * line number where there is one): the page shows it after "Could not read ".
 */
export class CoreReadError extends LoadError {
  override name = 'CoreReadError';
}

const COMPRESSION = /"(KHR_draco_mesh_compression|EXT_meshopt_compression|KHR_meshopt_compression)"/;

/** True for a .glb/.gltf whose JSON names a compression extension. */
export function isCompressedGltf(fileName: string, data: ArrayBuffer): boolean {
  if (!/\.(glb|gltf)$/i.test(fileName)) return false;
  const view = new DataView(data);
  let json: Uint8Array;
  if (data.byteLength >= 20 && view.getUint32(0, true) === 0x46546c67) {
    const length = Math.min(view.getUint32(12, true), data.byteLength - 20);
    json = new Uint8Array(data, 20, length);
  } else {
    json = new Uint8Array(data);
  }
  return COMPRESSION.test(new TextDecoder().decode(json));
}

/**
 * One line: tinygltf's messages may hold several, and the sentence ends with the page's own '.'.
 * The readers' hint at the CLI's --max-vertices says here whose option it is: the page's limit is fixed.
 */
function sentence(message: string): string {
  return message
    .split('\n')
    .map((line) => line.trim())
    .filter(Boolean)
    .join('; ')
    .replace(/\.+$/, '')
    .replace(/ \(raise (?:it|the limit) with --max-vertices\)/g, " (this page's limit; the command-line tool can raise it with --max-vertices)");
}

/**
 * Reads the file with the core. Resolves with what it found, or with null when the core was not
 * asked (a compressed glTF, or a page whose module could not start: three's loaders and the app's
 * own checks then decide). Rejects with CoreReadError (the CLI's message) or LoadError.
 */
export async function checkWithCore(reader: CoreReader, fileName: string, data: ArrayBuffer): Promise<ReadInfo | null> {
  if (isCompressedGltf(fileName, data)) return null;
  try {
    await reader.ready();
  } catch {
    return null;
  }
  for (let attempt = 0; ; attempt++) {
    try {
      return await reader.read(fileName, data);
    } catch (error) {
      if (!(error instanceof GeoshiftError)) throw error;
      switch (error.kind) {
        case 'input':
          throw new CoreReadError(sentence(error.message));
        case 'out-of-memory':
          // The heap grew as far as it may; the package has started a fresh worker, whose heap is small.
          throw new LoadError(
            'it is too large for the memory this browser tab may use (reading it needs more than the WebAssembly heap can grow to); try the command-line tool',
          );
        case 'cancelled':
          // The worker was replaced while the read waited behind a run that was cancelled.
          if (attempt === 0) continue;
          throw new LoadError('reading it was interrupted twice by a cancelled filter; open it again');
        default:
          console.error(`geoshift: the core's reader failed on ${fileName}`, error);
          throw new LoadError('the file reader stopped with an internal error (details in the browser console); the file is probably damaged');
      }
    }
  }
}

/**
 * What building each part as the filters do repairs (welding aside): one line per kind of repair,
 * the core's summary without its list of indices, prefixed with the part's label where the file has
 * several parts; and the core's full messages, for the status line's tooltip. docs/denoising.md#bad-input.
 */
export function repairsOf(info: ReadInfo | null): { summary: string[]; full: string[] } {
  const summary: string[] = [];
  const full: string[] = [];
  const parts = info?.parts ?? [];
  for (const part of parts) {
    const prefix = parts.length > 1 ? `${part.label}: ` : '';
    for (const message of part.report.messages) {
      const cut = message.indexOf(': ');
      summary.push(prefix + (cut >= 0 ? message.slice(0, cut) : message));
      full.push(prefix + message);
    }
  }
  return { summary, full };
}
