#pragma once
// What `geoshift filter` reads from a part and writes back: the signal named on the command line
// as attributes of the welded mesh, and the filtered values in the part's own vertex layout.
#include <string>

#include "commands.hpp"
#include "geoshift/hybrid.hpp"

namespace geoshift::cli {

struct FilterSettings {
  std::string signal;        // color, normal, curvature, terrain, attribute names; comma-separated
  MeanShiftOptions options;
  bool rangeGiven = false;   // h_r came from the command line or a preset (else per-signal defaults)
  HybridOptions hybrid;       // levels > 0: Algorithm 2 (wavelet analysis, filter, synthesis)
};

struct FilterSummary {
  int vertices = 0, maxIterations = 0, threads = 1;
  double iterationSum = 0, convergedSum = 0, seconds = 0;
  void add(const MeanShiftResult& r, int vertices);
  double meanIterations() const { return vertices ? iterationSum / vertices : 0; }
  double convergedFraction() const { return vertices ? convergedSum / vertices : 1; }
};

// Why the part cannot give the signal (no colors, no such attribute), or "" when it can.
std::string missingSignal(const Document& doc, const MeshPart& part, const FilterSettings& settings);

// Filters the part's signal on its welded mesh and writes the result into the part.
HybridResult filterPart(const Document& doc, MeshPart& part, const MeshBuild& build, const FilterSettings& settings);

}  // namespace geoshift::cli
