/**
 * A file could not be turned into a mesh. The message completes the sentence
 * "Could not read NAME: ..." and is shown to users as is, so it avoids loader jargon.
 */
export class LoadError extends Error {
  override name = 'LoadError';
}
