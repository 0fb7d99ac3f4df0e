// What both entries export besides createGeoshift.
export { GeoshiftError, type GeoshiftErrorKind } from './errors.js';
export type { Geoshift } from './geoshift.js';
export type * from './types.js';
export type * from './options.js';
export { coreNames } from './options.js';
