#pragma once
// What a filter request means, for every front end (the CLI's `filter`, the wasm op `filter`,
// Python's mean_shift): which channels a list of signal names stands for, their kernels and
// default range bandwidths, and how a mode and a pass count combine (docs/algorithms.md#filter-requests).
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geoshift/hybrid.hpp"
#include "geoshift/mean_shift.hpp"
#include "geoshift/mesh.hpp"
#include "geoshift/params.hpp"
#include "geoshift/presets.hpp"
#include "geoshift/progress.hpp"

namespace geoshift {

// Default h_r of the signals that have one of their own; scalars get spreadBandwidth().
inline constexpr double kColorRangeBandwidth = 0.1;   // linear RGB in [0, 1]
inline constexpr double kNormalRangeBandwidth = 0.45; // eq. 8, the paper's §4.1

// What a front end's mesh offers a request, in the welded mesh's vertex layout.
struct SignalInputs {
  // Names the mesh in error messages, e.g. "mesh.glb: mesh 0" or "filter: the mesh".
  std::string where = "the mesh";
  // RGB rows per mesh vertex; empty function: the mesh has no colors.
  std::function<std::vector<double>()> colors;
  // The named per-vertex attributes the mesh holds, spelled as it holds them.
  std::vector<std::string> attributeNames;
  // One of attributeNames as an attribute per mesh vertex (its dim, kind and values).
  std::function<Attribute(const std::string& name)> attribute;
};

// Where a filtered channel came from, so that a front end writes it back in its place.
enum class SignalSource { Color, Normal, Curvature, Attribute };

struct FilterSignal {
  AttributeSet values;                  // the channels' input values, per mesh vertex
  std::vector<SignalChannel> channels;  // per name: attribute, h_r, kernel (for MeanShiftOptions)
  std::vector<SignalSource> sources;    // per channel
};

// The attribute of `available` that `name` means: the name itself, with a leading '_', then either
// ignoring case (three.js lower-cases the glTF attributes it reads); "" when none.
std::string findSignalName(const std::vector<std::string>& available, const std::string& name);

// Why the mesh cannot give the comma-separated `signal` (no colors, no such attribute), or "".
std::string missingSignal(const std::string& signal, const SignalInputs& inputs);

// The channels of a comma-separated signal list: "color" (COLOR_0 RGB, Gaussian, h_r 0.1),
// "normal" (vertex normals of the mesh's geometry, eq. 8, h_r 0.45), "curvature" (absolute
// curvature), attribute names (findSignalName); "terrain" alone stands for _HEIGHT_ABOVE_GROUND
// (else _VEGETATION_HEIGHT) and _CLASS. Scalars' default h_r: spreadBandwidth of their values.
// A given rangeBandwidth replaces every default (meanShift refuses one that is not positive).
// Throws InputError, naming inputs.where, for a signal the mesh lacks, an empty list, or an
// attribute named twice.
FilterSignal filterSignal(const Mesh& mesh, const std::string& signal, const SignalInputs& inputs,
                          std::optional<double> rangeBandwidth = std::nullopt, const Progress& progress = {});

// The pass count of a request: mode "ms" is one pass (InputError if `passes` asks for more),
// "bms" blurring passes (`passes`, else 10 when `base` is 1), "" `passes` alone (else `base`,
// the preset's count or 1). Throws InputError for another mode.
int filterPasses(std::string_view mode, std::optional<int> passes, int base = 1);

// A request of the filter op (its table: paramSpecsOf("filter"), params.hpp) over a preset's
// values (the CLI's --preset; none: the table's defaults): what to filter and how.
struct FilterRequest {
  std::string signal;                    // comma-separated names (filterSignal)
  MeanShiftOptions options;              // without channels: filterSignal gives them
  std::optional<double> rangeBandwidth;  // given, or the preset's: replaces every signal's own h_r
  HybridOptions hybrid;                  // levels > 0: the hybrid filter
};
// InputError for a mode and pass count that do not go together (filterPasses).
FilterRequest filterRequest(const ParamRequest& request, const FilterPreset* preset = nullptr);

}  // namespace geoshift
