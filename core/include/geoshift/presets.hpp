#pragma once
// The paper's parameter sets (docs/algorithms.md#presets) and ours, by name, for the CLI and the web app.
#include <string>
#include <string_view>
#include <vector>

#include "geoshift/mean_shift.hpp"

namespace geoshift {

struct FilterPreset {
  std::string name;
  std::string description;
  std::string signal;       // what it filters: color, normal, curvature, terrain
  MeanShiftOptions options; // bandwidths in AEL (spatial) and signal units (range)
  int levels = 0;           // wavelet levels of the hybrid filter (0: filter the mesh directly)
  double detailGain = 1;    // α for every level of the hybrid filter
};

// "color,_HEIGHT" -> {"color", "_HEIGHT"}: the signal list of `filter` (empty names dropped).
std::vector<std::string> splitSignalNames(const std::string& list);

// The default h_r of a scalar signal given without one: a tenth of its widest 10–90% spread over
// the `dim` channels of `values` (rows of dim), 1 when that spread is 0.
double spreadBandwidth(const std::vector<double>& values, int dim);

// color, curvature-ms, curvature-bms, terrain-ms, terrain-bms.
const std::vector<FilterPreset>& filterPresets();
// Throws InputError listing the known names.
const FilterPreset& filterPreset(std::string_view name);

}  // namespace geoshift
