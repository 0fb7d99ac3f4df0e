// Options of each op. TEMPORARY hand copy of the op table's parameters (wasm/ops.cpp) while the
// core's parameter specs (issue 29) are not on this branch; replaced by the generated file.

/** Options of `noise`: displaces vertices (test data for the denoisers). */
export interface NoiseOptions {
  amount?: number;
  distribution?: 'fixed' | 'uniform' | 'gaussian';
  direction?: 'random' | 'normal';
  seed?: number;
}
export interface SmoothOptions {
  iterations?: number;
  lambda?: number;
  mu?: number;
  weights?: 'uniform' | 'fujiwara' | 'cotangent';
}
export interface CurvatureOptions {
  kind?: 'abs' | 'mean' | 'gauss' | 'rms';
}
export interface GeodesicOptions {
  source?: number;
  radius?: number;
}
export interface FilterOptions {
  field?: string;
  mode?: 'ms' | 'bms';
  passes?: number;
  hs?: number;
  hr?: number;
  radius?: number;
  kmax?: number;
  eps?: number;
  rangeUpdate?: 'joint' | 'sampled';
  segments?: boolean;
  threads?: number;
  levels?: number;
  alpha?: number;
  filterGeometry?: boolean;
}
export interface DenoiseOptions {
  method?: 'meanshift' | 'bilateral' | 'taubin';
  preset?: 'default' | 'paper';
  noise?: number;
  strength?: number;
  hs?: number;
  hr?: number;
  radius?: number;
  kmax?: number;
  eps?: number;
  passes?: number;
  rangeUpdate?: 'joint' | 'sampled';
  faceNormals?: 'consensus' | 'mean';
  threads?: number;
  supportIterations?: number;
  vertexIterations?: number;
  normalIterations?: number;
  sigmaC?: number;
  sigmaS?: number;
  neighbors?: 'vertex' | 'edge';
  iterations?: number;
  lambda?: number;
  mu?: number;
  levels?: number;
  alpha?: number;
}
export interface WaveletOptions {
  levels?: number;
  alpha?: number | number[];
  positionsOnly?: boolean;
}

/** The options of every op, by op name. */
export interface OpOptions {
  noise: NoiseOptions;
  smooth: SmoothOptions;
  curvature: CurvatureOptions;
  geodesic: GeodesicOptions;
  filter: FilterOptions;
  denoise: DenoiseOptions;
  wavelet: WaveletOptions;
}

/** The name of an op. */
export type OpName = keyof OpOptions;

/** Option names of each op (what the core accepts; tests compare them with the module's). */
export const optionNames: { readonly [Op in OpName]: ReadonlyArray<keyof OpOptions[Op]> } = {
  noise: ['amount', 'distribution', 'direction', 'seed'],
  smooth: ['iterations', 'lambda', 'mu', 'weights'],
  curvature: ['kind'],
  geodesic: ['source', 'radius'],
  filter: ['field', 'mode', 'passes', 'hs', 'hr', 'radius', 'kmax', 'eps', 'rangeUpdate', 'segments', 'threads', 'levels', 'alpha', 'filterGeometry'],
  denoise: ['method', 'preset', 'noise', 'strength', 'hs', 'hr', 'radius', 'kmax', 'eps', 'passes', 'rangeUpdate', 'faceNormals', 'threads', 'supportIterations', 'vertexIterations', 'normalIterations', 'sigmaC', 'sigmaS', 'neighbors', 'iterations', 'lambda', 'mu', 'levels', 'alpha'],
  wavelet: ['levels', 'alpha', 'positionsOnly'],
};

/**
 * Options the package names differently from the core, by op: the core's `signal` of `filter` (the
 * values filtered) is `field` here, because `signal` is every call's AbortSignal, as in fetch().
 */
export const coreNames: { readonly [Op in OpName]?: { readonly [name: string]: string } } = {
  filter: { field: 'signal' },
};
