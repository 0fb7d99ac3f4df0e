// The one error type of the package. Every failure a caller can meet (a bad argument, the core
// refusing an input, a cancel, the heap full, a bug) is a GeoshiftError with a kind, so callers
// switch on `kind` and show `message`, which is the core's own wording.

/**
 * Why a call failed:
 * - `input`: the mesh, the file or an option is not acceptable; the message names what and where
 *   (the option, the face, the vertex, the file and line), in the words of the command-line tool;
 * - `cancelled`: the call's AbortSignal fired (or `terminate()` was called);
 * - `out-of-memory`: the WebAssembly heap could not grow enough (the worker is then replaced, so
 *   the next call starts with a small heap again);
 * - `internal`: a defect, or the worker could not start (a missing .wasm file, a blocked URL).
 */
export type GeoshiftErrorKind = 'input' | 'cancelled' | 'out-of-memory' | 'internal';

/** A failed call; `kind` says why, `message` says what, in the core's words. */
export class GeoshiftError extends Error {
  override readonly name = 'GeoshiftError';
  constructor(
    message: string,
    /** Why the call failed. */
    readonly kind: GeoshiftErrorKind,
  ) {
    super(message);
  }
}
