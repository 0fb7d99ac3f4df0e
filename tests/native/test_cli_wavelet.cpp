// geoshift wavelet and geoshift info --levels, run as a user runs them.
#include <catch2/catch.hpp>

#include <cmath>
#include <regex>

#include "cli_support.hpp"
#include "geoshift/io.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;
using namespace geoshift::test;

namespace {

double rmsTo(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  REQUIRE(a.size() == b.size());
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]).squaredNorm();
  return std::sqrt(s / a.size());
}

// A noisy icosphere with noisy colors, as an OFF (positions) and a GLB (positions and COLOR_0).
struct Fixture {
  fs::path dir, off, glb;
  TriangleSoup clean, noisy;
  std::vector<Eigen::Vector4d> colors;
};

Fixture makeFixture(const std::string& name) {
  Fixture f;
  f.dir = tempDir(name);
  f.clean = shapes::icosphere(4);
  f.noisy = f.clean;
  Mesh m = buildMesh(f.noisy).mesh;
  addNoise(m, NoiseOptions{0.3, NoiseDistribution::Gaussian, NoiseDirection::Normal, 5});
  f.noisy.positions = m.positions();  // icosphere soups are welded already: same vertex order
  f.off = f.dir / "noisy.off";
  writeOff(f.off, f.noisy);
  Document doc = readDocument(f.off.string());
  unsigned state = 12345;
  for (const Vec3& p : doc.parts[0].positions) {
    state = state * 1103515245u + 12345u;
    const double jitter = 0.1 * ((state >> 16) % 1000 / 1000.0 - 0.5);
    f.colors.emplace_back(0.5 + 0.3 * p.x() + jitter, 0.5, 0.5 - 0.3 * p.z(), 1.0);
  }
  doc.parts[0].colors = f.colors;
  f.glb = f.dir / "noisy.glb";
  writeDocument(doc, f.glb.string());
  return f;
}

}  // namespace

TEST_CASE("cli: wavelet with alpha 1 gives the input back; alpha 0 smooths a noisy sphere", "[cli][wavelet]") {
  const Fixture f = makeFixture("cli-wavelet");
  const fs::path same = f.dir / "same.off", smooth = f.dir / "smooth.off";
  Run r = geoshiftCli("wavelet " + q(f.off) + " -o " + q(same) + " --levels 3 --alpha 1");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.err.find("vertices per level 2562 -> ") != std::string::npos);
  const Document back = readDocument(same.string());
  CHECK(back.parts[0].faces == f.noisy.faces);
  CHECK(rmsTo(back.parts[0].positions, f.noisy.positions) < 1e-9);

  r = geoshiftCli("wavelet " + q(f.off) + " -o " + q(smooth) + " --levels 3 --alpha 0,0,0");
  REQUIRE(r.code == 0);
  const Document smoothed = readDocument(smooth.string());
  CHECK(rmsTo(smoothed.parts[0].positions, f.clean.positions) < 0.8 * rmsTo(f.noisy.positions, f.clean.positions));
}

TEST_CASE("cli: wavelet filters vertex colors too and keeps them in [0, 1]", "[cli][wavelet]") {
  const Fixture f = makeFixture("cli-wavelet-colors");
  const fs::path same = f.dir / "same.glb", smooth = f.dir / "smooth.glb", sharp = f.dir / "sharp.glb";
  REQUIRE(geoshiftCli("wavelet " + q(f.glb) + " -o " + q(same) + " --levels 2 --alpha 1").code == 0);
  REQUIRE(geoshiftCli("wavelet " + q(f.glb) + " -o " + q(smooth) + " --levels 2 --alpha 0").code == 0);
  REQUIRE(geoshiftCli("wavelet " + q(f.glb) + " -o " + q(sharp) + " --levels 2 --alpha 4").code == 0);
  const auto colorsOf = [](const fs::path& p) { return readDocument(p.string()).parts[0].colors; };
  // Roughness of the red channel: mean squared difference across edges.
  const auto roughness = [&](const std::vector<Eigen::Vector4d>& c) {
    double s = 0;
    for (const Face& t : f.noisy.faces)
      for (int k = 0; k < 3; ++k) s += std::pow(c[t[k]][0] - c[t[(k + 1) % 3]][0], 2);
    return s;
  };
  const auto c1 = colorsOf(same), c0 = colorsOf(smooth), c4 = colorsOf(sharp);
  REQUIRE(c1.size() == f.colors.size());
  double worst = 0;
  for (size_t i = 0; i < c1.size(); ++i) worst = std::max(worst, (c1[i] - f.colors[i]).cwiseAbs().maxCoeff());
  CHECK(worst < 1e-6);  // glTF stores colors as float
  CHECK(roughness(c0) < 0.7 * roughness(f.colors));
  CHECK(roughness(c4) > roughness(f.colors));
  for (const auto& c : c4) CHECK(((c.array() >= 0.0).all() && (c.array() <= 1.0).all()));
}

TEST_CASE("cli: wavelet rejects bad levels and alpha counts without writing", "[cli][wavelet]") {
  const Fixture f = makeFixture("cli-wavelet-bad");
  const fs::path out = f.dir / "out.off";
  Run r = geoshiftCli("wavelet " + q(f.off) + " -o " + q(out) + " --levels 3 --alpha 1,0.5");
  CHECK(r.code == 1);
  CHECK(r.err.find("--alpha has 2 values for 3 levels") != std::string::npos);
  r = geoshiftCli("wavelet " + q(f.off) + " -o " + q(out) + " --levels -1");
  CHECK(r.code == 1);
  CHECK(r.err.find("wavelet: parameter levels must be >= 0 (got -1)") != std::string::npos);  // as the wasm op says it
  r = geoshiftCli("wavelet " + q(f.off) + " -o " + q(out) + " --alpha nan");
  CHECK(r.code != 0);
  CHECK(!fs::exists(out));
}

TEST_CASE("cli: info --levels prints the vertex count after each level", "[cli][wavelet]") {
  const Fixture f = makeFixture("cli-wavelet-info");
  const Run r = geoshiftCli("info " + q(f.off) + " --levels 3");
  INFO(r.err);
  REQUIRE(r.code == 0);
  std::smatch m;
  const std::regex line(R"(wavelet levels +3: 2562 -> (\d+) -> (\d+) -> (\d+) vertices)");
  REQUIRE(std::regex_search(r.out, m, line));
  const int a = std::stoi(m[1]), b = std::stoi(m[2]), c = std::stoi(m[3]);
  CHECK(a < 2562);
  CHECK(b < a);
  CHECK(c < b);
  CHECK(a > 0.65 * 2562);
}
