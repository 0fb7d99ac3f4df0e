// geoshift denoise, run as a user runs it.
#include <catch2/catch.hpp>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geoshift/noise.hpp"
#include "geoshift/shapes.hpp"
#include "cli_support.hpp"

using namespace geoshift;
using namespace geoshift::test;

namespace {

// The vertex lines of an OFF file the CLI wrote, as text: equal lines are equal numbers.
std::vector<std::string> offVertexLines(const fs::path& file) {
  std::istringstream in(slurp(file));
  std::string line;
  std::getline(in, line);  // OFF
  std::getline(in, line);
  const int nv = std::stoi(line);
  std::vector<std::string> out(nv);
  for (std::string& v : out) std::getline(in, v);
  return out;
}

double rmsToClean(const fs::path& result, const fs::path& clean) {
  const Run r = geoshiftCli("compare --json " + q(result) + " " + q(clean));
  REQUIRE(r.code == 0);
  return nlohmann::json::parse(r.out)["resultToReference"]["rms"].get<double>();
}

}  // namespace

// On a smooth closed shape the result is far closer to the truth than the noise: the estimated
// error is a small fraction of the noise level. Given a level above the noise's, the unbiased risk
// estimate comes out at or below zero: the CLI says so in words, not as an error of 0.
TEST_CASE("cli: denoise reports an estimated error too small to resolve in words", "[cli][denoise]") {
  const fs::path dir = tempDir("cli-denoise-resolve");
  writeOff(dir / "clean.off", shapes::torus(100, 40));
  REQUIRE(geoshiftCli("noise " + q(dir / "clean.off") + " -o " + q(dir / "noisy.off") + " --amount 0.3 --seed 2").code == 0);
  Run r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "out.off"));
  REQUIRE(r.code == 0);
  std::smatch m;
  REQUIRE(std::regex_search(r.err, m, std::regex("noise level ([0-9.]+) AEL .*estimated error ([0-9.]+) AEL")));
  const double level = std::stod(m[1].str()), error = std::stod(m[2].str());
  CHECK(level > 0.1);
  CHECK(error > 0);
  CHECK(error < 0.5 * level);
  r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "out2.off") + " --noise 0.3");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("chosen by SURE (estimated error too small to resolve, "));
  CHECK_THAT(r.err, !Catch::Contains("estimated error 0 AEL"));
}

// Impulsive noise (a tenth of the vertices moved) is recognised and said; noise on every vertex is not
// (docs/denoising.md#impulsive-noise).
TEST_CASE("cli: denoise says when the noise looks impulsive", "[cli][denoise]") {
  const fs::path dir = tempDir("cli-denoise-impulsive");
  writeOff(dir / "clean.off", shapes::icosphere(4));
  const std::string said = "the noise looks impulsive: outliers corrected, the other vertices mostly kept (kurtosis ";
  REQUIRE(geoshiftCli("noise " + q(dir / "clean.off") + " -o " + q(dir / "spikes.off") + " --amount 0.5 --dist impulsive --seed 6").code == 0);
  Run r = geoshiftCli("denoise " + q(dir / "spikes.off") + " -o " + q(dir / "out.off"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains(said));
  CHECK(rmsToClean(dir / "out.off", dir / "clean.off") < 0.2 * rmsToClean(dir / "spikes.off", dir / "clean.off"));
  REQUIRE(geoshiftCli("noise " + q(dir / "clean.off") + " -o " + q(dir / "gauss.off") + " --amount 0.3 --dist gaussian --seed 6").code == 0);
  r = geoshiftCli("denoise " + q(dir / "gauss.off") + " -o " + q(dir / "out2.off"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, !Catch::Contains(said));
  // --impulse on corrects outliers there too and says it was asked; --impulse off never corrects.
  r = geoshiftCli("denoise " + q(dir / "gauss.off") + " -o " + q(dir / "out3.off") + " --impulse on");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("; outliers (--impulse on) corrected, the other vertices mostly kept (kurtosis "));
  r = geoshiftCli("denoise " + q(dir / "spikes.off") + " -o " + q(dir / "out4.off") + " --impulse off");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, !Catch::Contains("outliers"));
  CHECK(rmsToClean(dir / "out4.off", dir / "clean.off") > rmsToClean(dir / "out.off", dir / "clean.off"));
}

// docs/denoising.md#small-pieces: a tetrahedron beside a noisy sphere keeps its positions and the
// report counts it; --min-piece 0 denoises it with the rest; a mesh of small pieces alone is left as it was.
TEST_CASE("cli: denoise leaves pieces too small to denoise as they were and says so", "[cli][denoise]") {
  const fs::path dir = tempDir("cli-denoise-pieces");
  TriangleSoup soup = shapes::icosphere(3);
  const int n = static_cast<int>(soup.positions.size());
  for (const Vec3& p : shapes::tetrahedron().positions) soup.positions.push_back(Vec3(3, 0, 0) + 0.1 * p);
  for (const Face& f : shapes::tetrahedron().faces) soup.faces.push_back({f[0] + n, f[1] + n, f[2] + n});
  writeOff(dir / "clean.off", soup);
  REQUIRE(geoshiftCli("noise " + q(dir / "clean.off") + " -o " + q(dir / "noisy.off") + " --amount 0.3 --seed 4").code == 0);
  Run r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "out.off"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("geoshift: 1 piece of fewer than 50 vertices (4 vertices) kept as it was (--min-piece)\n"));
  const std::vector<std::string> noisy = offVertexLines(dir / "noisy.off"), out = offVertexLines(dir / "out.off");
  REQUIRE(out.size() == static_cast<size_t>(n + 4));
  for (int v = n; v < n + 4; ++v) CHECK(out[v] == noisy[v]);
  CHECK(out[0] != noisy[0]);
  r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "every.off") + " --min-piece 0");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, !Catch::Contains("kept as"));
  CHECK(offVertexLines(dir / "every.off")[n] != noisy[n]);

  // Written by the CLI, so that the two files' numbers are printed alike.
  writeOff(dir / "tetra-in.off", shapes::tetrahedron());
  REQUIRE(geoshiftCli("smooth " + q(dir / "tetra-in.off") + " -o " + q(dir / "tetra.off") + " --iterations 0").code == 0);
  r = geoshiftCli("denoise " + q(dir / "tetra.off") + " -o " + q(dir / "tetra-out.off"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("geoshift: nothing denoised: 1 piece of fewer than 50 vertices (4 vertices) kept as it was"));
  CHECK(offVertexLines(dir / "tetra-out.off") == offVertexLines(dir / "tetra.off"));
}

// A file wound inconsistently (every seventh face given the other way round, as some exporters
// write) is the same surface: its faces are turned to agree, the note says how many, the result is
// the consistently wound file's to the digit, and the faces are written back as the file gave them.
TEST_CASE("cli: denoise turns faces wound against their neighbours and says so", "[cli][denoise][orientation]") {
  const fs::path dir = tempDir("cli-denoise-orientation");
  writeOff(dir / "clean.off", shapes::icosphere(3));
  REQUIRE(geoshiftCli("noise " + q(dir / "clean.off") + " -o " + q(dir / "noisy.off") + " --amount 0.3 --seed 2").code == 0);
  std::istringstream in(slurp(dir / "noisy.off"));
  std::ostringstream mixed;
  std::string line;
  std::getline(in, line);
  mixed << line << "\n";
  std::getline(in, line);
  mixed << line << "\n";
  const int nv = std::stoi(line), nf = std::stoi(line.substr(line.find(' ')));
  for (int v = 0; v < nv && std::getline(in, line); ++v) mixed << line << "\n";
  std::vector<std::string> givenFaces;
  for (int f = 0; f < nf; ++f) {
    int k = 0, a = 0, b = 0, c = 0;
    in >> k >> a >> b >> c;
    givenFaces.push_back("3 " + std::to_string(a) + " " + std::to_string(f % 7 == 3 ? c : b) + " " +
                         std::to_string(f % 7 == 3 ? b : c));
    mixed << givenFaces.back() << "\n";
  }
  {
    std::ofstream(dir / "mixed.off") << mixed.str();
  }
  Run r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "out.off"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, !Catch::Contains("re-oriented"));
  r = geoshiftCli("denoise " + q(dir / "mixed.off") + " -o " + q(dir / "mixed-out.off"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("re-oriented " + std::to_string((nf + 3) / 7) + " face(s) to agree with their neighbours"));
  CHECK_THAT(r.err, !Catch::Contains("non-manifold"));
  CHECK_THAT(r.err, !Catch::Contains("kept as"));
  CHECK(offVertexLines(dir / "mixed-out.off") == offVertexLines(dir / "out.off"));
  std::istringstream written(slurp(dir / "mixed-out.off"));
  for (int i = 0; i < nv + 2; ++i) std::getline(written, line);
  for (int f = 0; f < nf && std::getline(written, line); ++f) {
    CAPTURE(f);
    CHECK(line == givenFaces[f]);
  }
}

// docs/denoising.md#the-noise-level ("Planes left untouched"): a clean part of flat faces too
// coarse for the spectrum is measured against its planes and comes back as it went in.
TEST_CASE("cli: a clean coarse part is measured against its planes and kept", "[cli][denoise]") {
  const fs::path dir = tempDir("cli-denoise-planes");
  writeOff(dir / "part.off", shapes::box(5, 5, 5));
  const Run r = geoshiftCli("denoise " + q(dir / "part.off") + " -o " + q(dir / "out.off"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("(estimated from the mesh, against the planes the noise left)"));
  CHECK_THAT(r.err, Catch::Contains("kept as it was"));
  CHECK(rmsToClean(dir / "out.off", dir / "part.off") == 0);
}

TEST_CASE("cli: denoise removes noise with every method and says what it did", "[cli][denoise]") {
  const fs::path dir = tempDir("cli-denoise");
  const TriangleSoup clean = shapes::box(12, 10, 8, Vec3(1.0, 0.8, 0.6));
  writeOff(dir / "clean.off", clean);
  REQUIRE(geoshiftCli("noise " + q(dir / "clean.off") + " -o " + q(dir / "noisy.off") + " --amount 0.3 --seed 2").code == 0);
  const double noisy = rmsToClean(dir / "noisy.off", dir / "clean.off");
  REQUIRE(noisy > 0);

  // The default: the mean shift denoiser says what it estimated and what SURE chose.
  Run r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "meanshift.off"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("denoise meanshift: 594 vertices in 1 part"));
  CHECK_THAT(r.err, Catch::Contains("AEL (estimated from the mesh)"));
  CHECK_THAT(r.err, Catch::Contains("chosen by SURE"));
  CHECK(rmsToClean(dir / "meanshift.off", dir / "clean.off") < 0.5 * noisy);

  // A given noise level is used as given; a fixed pass count skips SURE.
  r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "fixed.off") + " --noise 0.2 --passes 3");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("noise level 0.2 AEL (given)"));
  CHECK_THAT(r.err, Catch::Contains("3 mean shift passes (fixed)"));
  CHECK(rmsToClean(dir / "fixed.off", dir / "clean.off") < 0.6 * noisy);

  // The paper's pipeline stays available.
  r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "paper.off") + " --preset paper --passes 2 --kmax 20");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("paper preset) 2 passes"));
  CHECK(rmsToClean(dir / "paper.off", dir / "clean.off") < 0.6 * noisy);

  r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "bilateral.off") + " --method bilateral");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("denoise bilateral: 594 vertices in 1 part"));
  CHECK_THAT(r.err, Catch::Contains(" ms"));
  CHECK(rmsToClean(dir / "bilateral.off", dir / "clean.off") < 0.5 * noisy);

  r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "edge.off") +
                  " --method bilateral --neighbors edge --normal-iterations 30 --sigma-s 0.3 --sigma-c 1 --vertex-iterations 20"
                  " --flip-guard input-or-target");
  REQUIRE(r.code == 0);
  CHECK(rmsToClean(dir / "edge.off", dir / "clean.off") < 0.6 * noisy);

  r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "taubin.off") + " --method taubin --taubin-iterations 5");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains("denoise taubin"));
  CHECK(rmsToClean(dir / "taubin.off", dir / "clean.off") < noisy);
}

TEST_CASE("cli: denoise refuses bad input without writing anything", "[cli][denoise]") {
  const fs::path dir = tempDir("cli-denoise-bad");
  writeOff(dir / "sphere.off", shapes::icosphere(2));
  Run r = geoshiftCli("denoise " + q(dir / "missing.off") + " -o " + q(dir / "out.off"));
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Catch::Contains("missing.off"));
  r = geoshiftCli("denoise " + q(dir / "sphere.off") + " -o " + q(dir / "out.off") + " --method magic");
  CHECK(r.code != 0);
  CHECK_THAT(r.err, Catch::Contains("magic"));
  r = geoshiftCli("denoise " + q(dir / "sphere.off") + " -o " + q(dir / "out.off") + " --sigma-s 0");
  CHECK(r.code != 0);
  // An option of the other preset is refused, naming it.
  r = geoshiftCli("denoise " + q(dir / "sphere.off") + " -o " + q(dir / "out.off") + " --kmax 10");
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Catch::Contains("parameter kmax belongs to preset \"paper\"; kmax does not apply to preset \"default\""));
  r = geoshiftCli("denoise " + q(dir / "sphere.off") + " -o " + q(dir / "out.off") + " --preset paper --strength 2");
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Catch::Contains("parameter strength belongs to preset \"default\"; strength does not apply to preset \"paper\""));
  r = geoshiftCli("denoise " + q(dir / "sphere.off") + " -o " + q(dir / "out.off") + " --method taubin --mu 0.1");
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Catch::Contains("mu"));
  CHECK_FALSE(fs::exists(dir / "out.off"));
}

// docs/denoising.md#the-input-as-a-candidate: a CAD block denoised once is, denoised again, written
// back as it was read, and the report says why; the first run, on real noise, did smooth.
TEST_CASE("cli: denoise leaves a mesh no candidate would improve as it was and says so", "[cli][denoise]") {
  const fs::path dir = tempDir("cli-denoise-input");
  writeOff(dir / "clean.off", shapes::box(12, 12, 12));
  REQUIRE(geoshiftCli("noise " + q(dir / "clean.off") + " -o " + q(dir / "noisy.off") + " --amount 0.5 --seed 3").code == 0);
  const std::string said = "kept as it was: no candidate is estimated closer to the noise-free surface than the input (";
  Run r = geoshiftCli("denoise " + q(dir / "noisy.off") + " -o " + q(dir / "once.off"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, !Catch::Contains(said));
  CHECK(offVertexLines(dir / "once.off") != offVertexLines(dir / "noisy.off"));
  r = geoshiftCli("denoise " + q(dir / "once.off") + " -o " + q(dir / "twice.off"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, Catch::Contains(said));
  CHECK_THAT(r.err, !Catch::Contains("chosen by SURE"));
  CHECK(offVertexLines(dir / "twice.off") == offVertexLines(dir / "once.off"));
  // Outliers asked to be corrected in any case are corrected: the rule does not overrule --impulse on.
  r = geoshiftCli("denoise " + q(dir / "once.off") + " -o " + q(dir / "forced.off") + " --impulse on");
  REQUIRE(r.code == 0);
  CHECK_THAT(r.err, !Catch::Contains(said));
  CHECK_THAT(r.err, Catch::Contains("outliers (--impulse on) corrected"));
}
