#include "geoshift/presets.hpp"

#include <algorithm>
#include <sstream>

#include "geoshift/error.hpp"

namespace geoshift {

namespace {

FilterPreset make(std::string name, std::string description, std::string signal, double hs, double hr, double eps,
                  int kmax, int passes, int levels = 0, double gain = 1) {
  FilterPreset p;
  p.name = std::move(name);
  p.description = std::move(description);
  p.signal = std::move(signal);
  p.options.spatialBandwidth = hs;
  p.options.rangeBandwidth = hr;
  p.options.epsilon = eps;
  p.options.maxIterations = kmax;
  p.options.passes = passes;
  p.levels = levels;
  p.detailGain = gain;
  return p;
}

}  // namespace

std::vector<std::string> splitSignalNames(const std::string& list) {
  std::vector<std::string> names;
  std::stringstream s(list);
  for (std::string name; std::getline(s, name, ',');)
    if (!name.empty()) names.push_back(name);
  return names;
}

double spreadBandwidth(const std::vector<double>& values, int dim) {
  if (values.empty() || dim < 1) return 1;
  double widest = 0;
  for (int d = 0; d < dim; ++d) {
    std::vector<double> column;
    for (size_t i = d; i < values.size(); i += dim) column.push_back(values[i]);
    std::sort(column.begin(), column.end());
    widest = std::max(widest, column[column.size() * 9 / 10] - column[column.size() / 10]);
  }
  return widest > 0 ? widest / 10 : 1;
}

const std::vector<FilterPreset>& filterPresets() {
  // Terrain values are the paper's §4.2.1 (its BMS line prints h_s and h_r swapped; §0.4), the
  // curvature ones §4.2.2 (absolute curvature, two wavelet levels with the details dropped). The
  // color set is ours: h_r = 0.1 in linear RGB keeps edges between colors that differ by more
  // than about a quarter of the range.
  static const std::vector<FilterPreset> presets = {
      make("color", "smooth vertex colors, keep color edges (mean shift)", "color", 3, 0.1, 0.2, 50, 1),
      make("curvature-ms", "filter absolute curvature (paper 4.2.2, mean shift)", "curvature", 3, 0.25, 0.2, 50, 1, 2, 0),
      make("curvature-bms", "filter absolute curvature (paper 4.2.2, blurring mean shift)", "curvature", 5, 0.1, 0.2, 5,
           10, 2, 0),
      make("terrain-ms", "filter terrain attributes (paper 4.2.1, mean shift)", "terrain", 8, 4, 0.05, 50, 1, 6, 0),
      make("terrain-bms", "filter terrain attributes (paper 4.2.1, blurring mean shift)", "terrain", 5, 5, 0.2, 5, 10, 6,
           0),
  };
  return presets;
}

const FilterPreset& filterPreset(std::string_view name) {
  std::string known;
  for (const FilterPreset& p : filterPresets()) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  throw InputError("unknown preset '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace geoshift
