// `geoshift filter`: the signals it reads and writes back, presets, errors, thread independence.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <random>

#include "cli_support.hpp"
#include "geoshift/io.hpp"
#include "geoshift/shapes.hpp"
#include "support.hpp"

using namespace geoshift;
using namespace geoshift::test;

namespace {

// A sphere, red above z = 0 and blue below, with Gaussian color noise, as COFF (colors in [0, 1]).
fs::path noisyColoredSphere(const fs::path& dir) {
  const TriangleSoup s = shapes::icosphere(4);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, 0.08);
  const fs::path path = dir / "sphere.off";
  std::ofstream o(path);
  o.precision(17);
  o << "COFF\n" << s.positions.size() << " " << s.faces.size() << " 0\n";
  for (const Vec3& p : s.positions) {
    const bool up = p.z() > 0;
    o << p.x() << " " << p.y() << " " << p.z() << " " << (up ? 1.0 : 0.0) + noise(rng) << " " << 0.0 + noise(rng)
      << " " << (up ? 0.0 : 1.0) + noise(rng) << " 1\n";
  }
  for (const Face& f : s.faces) o << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
  return path;
}

// Over the vertices farther than `band` from the step at z = 0.
double regionVariance(const MeshPart& part, bool up, double band = 0) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sq = Eigen::Vector3d::Zero();
  int n = 0;
  for (size_t v = 0; v < part.positions.size(); ++v) {
    if ((part.positions[v].z() > 0) != up || std::abs(part.positions[v].z()) < band) continue;
    const Eigen::Vector3d c = part.colors[v].head<3>();
    sum += c;
    sq += c.cwiseProduct(c);
    ++n;
  }
  return (sq / n - (sum / n).cwiseProduct(sum / n)).sum();
}

}  // namespace

TEST_CASE("filter smooths vertex colors and keeps the color edge", "[cli][filter]") {
  const fs::path dir = tempDir("cli-filter-color");
  const fs::path in = noisyColoredSphere(dir), out = dir / "out.glb";
  const Run r = geoshiftCli("filter " + q(in) + " -o " + q(out) + " --hs 3 --hr 0.3 --segments");
  INFO(r.err);
  REQUIRE(r.code == 0);
  REQUIRE_THAT(r.out, Catch::Contains("vertices") && Catch::Contains("converged") && Catch::Contains("threads"));
  const Document before = readDocument(in.string()), after = readDocument(out.string());
  const MeshPart& a = before.parts.at(0);
  const MeshPart& b = after.parts.at(0);
  REQUIRE(b.positions.size() == a.positions.size());
  for (bool up : {true, false}) REQUIRE(regionVariance(b, up) * 10 <= regionVariance(a, up));
  const auto segment = std::find_if(b.extras.begin(), b.extras.end(), [](const ExtraAttribute& e) { return e.name == "_SEGMENT"; });
  REQUIRE(segment != b.extras.end());
  REQUIRE(*std::max_element(segment->values.begin(), segment->values.end()) == 1.0);  // labels 0 and 1
  REQUIRE_THAT(r.err, Catch::Contains("2 segments"));
}

TEST_CASE("filter gives the same file for any thread count", "[cli][filter]") {
  const fs::path dir = tempDir("cli-filter-threads");
  const fs::path in = noisyColoredSphere(dir);
  REQUIRE(geoshiftCli("filter " + q(in) + " -o " + q(dir / "one.glb") + " --mode bms --passes 2 --threads 1").code == 0);
  REQUIRE(geoshiftCli("filter " + q(in) + " -o " + q(dir / "two.glb") + " --mode bms --passes 2 --threads 2").code == 0);
  REQUIRE(slurp(dir / "one.glb") == slurp(dir / "two.glb"));
}

TEST_CASE("filter --double-weights computes the kernel in double precision, to the same result within 1e-4", "[cli][filter]") {
  const fs::path dir = tempDir("cli-filter-precision");
  const fs::path in = noisyColoredSphere(dir);
  REQUIRE(geoshiftCli("filter " + q(in) + " -o " + q(dir / "single.glb") + " --hs 2 --hr 0.3").code == 0);
  REQUIRE(geoshiftCli("filter " + q(in) + " -o " + q(dir / "double.glb") + " --hs 2 --hr 0.3 --double-weights").code == 0);
  const MeshPart a = readDocument((dir / "single.glb").string()).parts.at(0);
  const MeshPart b = readDocument((dir / "double.glb").string()).parts.at(0);
  REQUIRE(a.colors.size() == b.colors.size());
  double worst = 0;
  for (size_t v = 0; v < a.colors.size(); ++v) worst = std::max(worst, (a.colors[v] - b.colors[v]).cwiseAbs().maxCoeff());
  REQUIRE(worst > 0);  // the flag reached the filter: single-precision weights round differently
  REQUIRE(worst < 1e-4);
}

TEST_CASE("filter reads normals, curvature and named attributes", "[cli][filter]") {
  const fs::path dir = tempDir("cli-filter-signals");
  const fs::path in = dir / "box.off";
  writeOff(in, shapes::box(6, 6, 6));
  const fs::path normals = dir / "normals.glb", curvature = dir / "curvature.glb", named = dir / "named.glb";
  REQUIRE(geoshiftCli("filter " + q(in) + " -o " + q(normals) + " --signal normal").code == 0);
  const MeshPart n = readDocument(normals.string()).parts.at(0);
  REQUIRE(n.normals.size() == n.positions.size());
  for (const Vec3& v : n.normals) REQUIRE(v.norm() == Approx(1).margin(1e-6));

  REQUIRE(geoshiftCli("filter " + q(in) + " -o " + q(curvature) + " --signal curvature --preset curvature-bms").code == 0);
  const MeshPart c = readDocument(curvature.string()).parts.at(0);
  REQUIRE(std::any_of(c.extras.begin(), c.extras.end(), [](const ExtraAttribute& e) { return e.name == "_CURVATURE"; }));
  REQUIRE(c.colors.size() == c.positions.size());

  // The filtered curvature is itself a named attribute now: filter it again by name.
  const Run r = geoshiftCli("filter " + q(curvature) + " -o " + q(named) + " --signal _CURVATURE --mode bms");
  INFO(r.err);
  REQUIRE(r.code == 0);
}

TEST_CASE("filter explains bad requests", "[cli][filter]") {
  const fs::path dir = tempDir("cli-filter-errors");
  const fs::path in = dir / "box.off", out = dir / "out.glb";
  writeOff(in, shapes::box(2, 2, 2));
  Run r = geoshiftCli("filter " + q(in) + " -o " + q(out));  // color by default; an OFF without colors
  REQUIRE(r.code == 1);
  REQUIRE_THAT(r.err, Catch::Contains("no vertex colors"));
  r = geoshiftCli("filter " + q(in) + " -o " + q(out) + " --signal _HEIGHT");
  REQUIRE(r.code == 1);
  REQUIRE_THAT(r.err, Catch::Contains("_HEIGHT"));
  r = geoshiftCli("filter " + q(in) + " -o " + q(out) + " --signal normal --preset smooth");
  REQUIRE(r.code == 1);
  REQUIRE_THAT(r.err, Catch::Contains("terrain-bms"));
  r = geoshiftCli("filter " + q(in) + " -o " + q(out) + " --signal normal --hs -2");
  REQUIRE(r.code == 1);
  REQUIRE_THAT(r.err, Catch::Contains("filter: parameter hs is outside (0, 1e+06] (got -2)"));  // as the wasm op says it
  REQUIRE_FALSE(fs::exists(out));
}

TEST_CASE("filter --levels runs the hybrid filter and says what it filtered", "[cli][filter]") {
  const fs::path dir = tempDir("cli-filter-levels");
  const fs::path in = noisyColoredSphere(dir), out = dir / "out.glb";
  const Run r = geoshiftCli("filter " + q(in) + " -o " + q(out) + " --hr 0.3 --levels 2 --alpha 0");
  INFO(r.err);
  REQUIRE(r.code == 0);
  REQUIRE_THAT(r.err, Catch::Contains("vertices per level 2562"));
  const MeshPart a = readDocument(in.string()).parts.at(0), b = readDocument(out.string()).parts.at(0);
  // Away from the step (two edges of the sphere): dropping the details blends the vertices next to it.
  for (bool up : {true, false}) REQUIRE(regionVariance(b, up, 0.15) * 5 <= regionVariance(a, up, 0.15));
  REQUIRE(geoshiftCli("filter " + q(in) + " -o " + q(out) + " --levels 2 --alpha 0,0,0").code == 1);
}
