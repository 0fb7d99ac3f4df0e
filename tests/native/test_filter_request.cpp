// What a filter request means (filter_request.hpp): the rules the CLI, the wasm op and Python share.
#include <catch2/catch.hpp>

#include "geoshift/curvature.hpp"
#include "geoshift/error.hpp"
#include "geoshift/filter_request.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/presets.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

// A mesh's inputs: colors when asked, and scalar attributes whose value at v is v times `scale`.
struct Fixture {
  Mesh mesh = buildMesh(shapes::icosphere(2)).mesh;
  std::vector<std::pair<std::string, double>> scalars;
  bool colors = true;

  SignalInputs inputs() const {
    SignalInputs in;
    in.where = "sphere";
    const int n = mesh.vertexCount();
    if (colors) in.colors = [n] { return std::vector<double>(3 * static_cast<size_t>(n), 0.5); };
    for (const auto& [name, scale] : scalars) in.attributeNames.push_back(name);
    in.attribute = [this, n](const std::string& name) {
      for (const auto& [known, scale] : scalars)
        if (known == name) {
          std::vector<double> values(n);
          for (int v = 0; v < n; ++v) values[v] = v * scale;
          return Attribute{name, 1, AttributeKind::Euclidean, values};
        }
      FAIL("asked for an attribute not listed: " << name);
      return Attribute{};
    };
    return in;
  }
};

std::vector<std::string> channelNames(const FilterSignal& s) {
  std::vector<std::string> names;
  for (const SignalChannel& c : s.channels) names.push_back(c.attribute);
  return names;
}

}  // namespace

TEST_CASE("attribute names are found as given, with a leading underscore, then ignoring case", "[filter_request]") {
  const std::vector<std::string> available = {"_HEIGHT", "height", "_class", "Temp"};
  CHECK(findSignalName(available, "height") == "height");    // exact beats "_" + name
  CHECK(findSignalName(available, "HEIGHT") == "_HEIGHT");   // "_" + name, exact case
  CHECK(findSignalName(available, "CLASS") == "_class");     // ignoring case
  CHECK(findSignalName(available, "temp") == "Temp");
  CHECK(findSignalName(available, "missing").empty());
  CHECK(findSignalName({}, "x").empty());
}

TEST_CASE("mode and passes combine as one rule", "[filter_request]") {
  CHECK(filterPasses("", std::nullopt) == 1);
  CHECK(filterPasses("", 4) == 4);
  CHECK(filterPasses("ms", std::nullopt) == 1);
  CHECK(filterPasses("ms", 1) == 1);
  CHECK_THROWS_WITH(filterPasses("ms", 3), Catch::Contains("mode \"ms\" runs one pass"));
  CHECK(filterPasses("bms", std::nullopt) == 10);
  CHECK(filterPasses("bms", 3) == 3);
  // Over a preset's count: bms keeps a blurring preset's passes, ms makes any preset one pass.
  CHECK(filterPasses("bms", std::nullopt, 5) == 5);
  CHECK(filterPasses("", std::nullopt, 10) == 10);
  CHECK(filterPasses("ms", std::nullopt, 10) == 1);
  CHECK_THROWS_AS(filterPasses("fast", std::nullopt), InputError);
}

TEST_CASE("each signal gets its channel, kernel and default range bandwidth", "[filter_request]") {
  Fixture f;
  f.scalars = {{"_HEIGHT", 2.0}};
  const FilterSignal s = filterSignal(f.mesh, "color,normal,curvature,height", f.inputs());
  REQUIRE(channelNames(s) == std::vector<std::string>{"COLOR", "NORMAL", "_CURVATURE", "_HEIGHT"});
  CHECK(s.sources == std::vector<SignalSource>{SignalSource::Color, SignalSource::Normal, SignalSource::Curvature,
                                              SignalSource::Attribute});
  CHECK(s.channels[0].rangeBandwidth == kColorRangeBandwidth);
  CHECK(s.channels[0].kernel == RangeKernel::Gaussian);
  CHECK(s.channels[1].rangeBandwidth == kNormalRangeBandwidth);
  CHECK(s.channels[1].kernel == RangeKernel::NormalSimilarity);
  CHECK(s.values.get("NORMAL").kind == AttributeKind::UnitVector);
  const std::vector<double> k = curvatures(f.mesh).get(CurvatureKind::Absolute);
  CHECK(s.channels[2].rangeBandwidth == spreadBandwidth(k, 1));
  CHECK(s.values.get("_CURVATURE").values == k);
  // v * 2 over the vertices: a tenth of its 10-90% spread.
  CHECK(s.channels[3].rangeBandwidth == spreadBandwidth(s.values.get("_HEIGHT").values, 1));
  CHECK(s.channels[3].rangeBandwidth > 0);
  // Normals from the geometry.
  const std::vector<Vec3> normals = vertexNormals(f.mesh);
  CHECK(s.values.get("NORMAL").row(7)[2] == Approx(normals[7].z()));

  const FilterSignal given = filterSignal(f.mesh, "color,height", f.inputs(), 0.7);
  for (const SignalChannel& c : given.channels) CHECK(c.rangeBandwidth == 0.7);
  // A given bandwidth is passed on as it is, for meanShift to refuse when it is not positive.
  CHECK(filterSignal(f.mesh, "height", f.inputs(), -1.0).channels[0].rangeBandwidth == -1.0);
}

TEST_CASE("terrain stands for the height attribute and the class", "[filter_request]") {
  Fixture f;
  f.scalars = {{"_CLASS", 1.0}, {"_VEGETATION_HEIGHT", 1.0}};
  CHECK(channelNames(filterSignal(f.mesh, "terrain", f.inputs())) ==
        std::vector<std::string>{"_VEGETATION_HEIGHT", "_CLASS"});
  f.scalars.push_back({"_HEIGHT_ABOVE_GROUND", 1.0});
  CHECK(channelNames(filterSignal(f.mesh, "terrain", f.inputs())) ==
        std::vector<std::string>{"_HEIGHT_ABOVE_GROUND", "_CLASS"});
  f.scalars = {{"_CLASS", 1.0}};
  CHECK(channelNames(filterSignal(f.mesh, "terrain", f.inputs())) == std::vector<std::string>{"_CLASS"});
  f.scalars = {{"_ELEVATION", 1.0}};
  CHECK_THROWS_WITH(filterSignal(f.mesh, "terrain", f.inputs()), Catch::Contains("sphere has no terrain attribute"));
  CHECK(missingSignal("terrain", f.inputs()) != "");
  CHECK(missingSignal("elevation", f.inputs()) == "");
}

TEST_CASE("a signal the mesh lacks is named, with where and what it has", "[filter_request]") {
  Fixture f;
  f.colors = false;
  f.scalars = {{"_A", 1.0}, {"_B", 1.0}};
  CHECK_THROWS_WITH(filterSignal(f.mesh, "color", f.inputs()), Catch::Contains("sphere has no vertex colors"));
  CHECK(missingSignal("normal,color", f.inputs()) == "sphere has no vertex colors (COLOR_0)");
  CHECK_THROWS_WITH(filterSignal(f.mesh, "c", f.inputs()), Catch::Contains("no attribute 'c' (it has: _A, _B"));
  CHECK_THROWS_WITH(filterSignal(f.mesh, "a,_A", f.inputs()), Catch::Contains("'_A' is named twice"));
  CHECK_THROWS_WITH(filterSignal(f.mesh, ",", f.inputs()), Catch::Contains("names no attribute"));
  CHECK(missingSignal("normal,curvature,a", f.inputs()).empty());
}

TEST_CASE("the presets are complete parameter sets", "[filter_request][presets]") {
  for (const FilterPreset& p : filterPresets()) {
    INFO(p.name);
    CHECK(p.options.spatialBandwidth > 0);
    CHECK(p.options.rangeBandwidth > 0);
    CHECK(p.options.passes >= 1);
    CHECK((p.signal == "color" || p.signal == "curvature" || p.signal == "terrain"));
    CHECK(&filterPreset(p.name) == &p);
  }
}
