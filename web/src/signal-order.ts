// The order in which a terrain's attributes are offered, the first being the default: heights are
// what smoothing is for, categories (classes, labels, segments) are not quantities to average and
// come last. Results of other presets (curvature, geodesic distance) are not terrain attributes.

const HEIGHT_LIKE = /height|elev|altitude|hag|depth|^_?z$/i;
const CATEGORY_LIKE = /class|label|segment|categor|(^|_)id$|index$/i;
const RESULTS = /^_curvature|^_geodesic$/i;

/**
 * File attributes that look like heights, then the file's other quantities, then `computed` (the
 * app's own height, always available), then categories.
 */
export function orderSignals(fileNames: string[], computed: string): string[] {
  const names = [...new Set(fileNames.filter((n) => !RESULTS.test(n) && n !== computed))];
  const heights = names.filter((n) => HEIGHT_LIKE.test(n) && !CATEGORY_LIKE.test(n));
  const categories = names.filter((n) => CATEGORY_LIKE.test(n));
  const others = names.filter((n) => !heights.includes(n) && !categories.includes(n));
  return [...heights, ...others, computed, ...categories];
}
