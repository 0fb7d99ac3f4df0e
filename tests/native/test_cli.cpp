// The geoshift command-line tool, run as a user runs it: files in, files and messages out.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "geoshift/io.hpp"
#include "geoshift/shapes.hpp"
#include "cli_support.hpp"

using namespace geoshift;
namespace fs = std::filesystem;

using namespace geoshift::test;

TEST_CASE("cli: info reports counts, boundary loops and defects", "[cli]") {
  const fs::path dir = test::tempDir("cli-info");
  writeOff(dir / "grid.off", shapes::grid(5));
  Run r = geoshiftCli("info " + q(dir / "grid.off"));
  REQUIRE(r.code == 0);
  REQUIRE_THAT(r.out, Catch::Contains("vertices            25"));
  REQUIRE_THAT(r.out, Catch::Contains("boundary loops      1 (lengths 16)"));
  REQUIRE_THAT(r.out, Catch::Contains("average edge length"));

  TriangleSoup bad = shapes::cube();
  bad.faces.push_back({0, 0, 1});
  writeOff(dir / "bad.off", bad);
  r = geoshiftCli("info " + q(dir / "bad.off"));
  REQUIRE(r.code == 0);
  REQUIRE_THAT(r.out, Catch::Contains("degenerate faces    1 (repeated index 1"));
  REQUIRE_THAT(r.err, Catch::Contains("face 12 (0, 0, 1)"));
  REQUIRE_THAT(r.out, Catch::Contains("pieces              1 (1 of fewer than 50 vertices)\n"));
  writeOff(dir / "ball.off", shapes::icosphere(2));
  REQUIRE_THAT(geoshiftCli("info " + q(dir / "ball.off")).out, Catch::Contains("pieces              1\n"));
}

TEST_CASE("cli: noise is reproducible by seed, smoothing brings it back towards the clean mesh", "[cli]") {
  const fs::path dir = test::tempDir("cli-noise");
  writeOff(dir / "sphere.off", shapes::icosphere(3));
  const std::string in = q(dir / "sphere.off");
  REQUIRE(geoshiftCli("noise " + in + " -o " + q(dir / "a.off") + " --seed 7 --amount 0.3").code == 0);
  REQUIRE(geoshiftCli("noise " + in + " -o " + q(dir / "b.off") + " --seed 7 --amount 0.3").code == 0);
  REQUIRE(geoshiftCli("noise " + in + " -o " + q(dir / "c.off") + " --seed 8 --amount 0.3").code == 0);
  REQUIRE(slurp(dir / "a.off") == slurp(dir / "b.off"));
  REQUIRE(slurp(dir / "a.off") != slurp(dir / "c.off"));

  REQUIRE(geoshiftCli("smooth " + q(dir / "a.off") + " -o " + q(dir / "s.off") + " --iterations 5").code == 0);
  auto rmsAgainstClean = [&](const fs::path& p) {
    Run r = geoshiftCli("compare --json " + q(p) + " " + in);
    REQUIRE(r.code == 0);
    return nlohmann::json::parse(r.out)["perVertexRms"].get<double>();
  };
  const double noisy = rmsAgainstClean(dir / "a.off"), smoothed = rmsAgainstClean(dir / "s.off");
  REQUIRE(noisy > 0);
  REQUIRE(smoothed < 0.8 * noisy);
}

TEST_CASE("cli: compare gives zero for a mesh against itself and the offset of a shifted plane", "[cli]") {
  const fs::path dir = test::tempDir("cli-compare");
  TriangleSoup plane = shapes::grid(9);
  writeOff(dir / "plane.off", plane);
  for (Vec3& p : plane.positions) p.z() += 0.01;
  writeOff(dir / "shifted.off", plane);
  Run r = geoshiftCli("compare --json " + q(dir / "plane.off") + " " + q(dir / "plane.off"));
  REQUIRE(r.code == 0);
  auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["resultToReference"]["rms"].get<double>() == Approx(0).margin(1e-12));
  REQUIRE(j["meanNormalAngleDeg"].get<double>() == Approx(0).margin(1e-9));
  r = geoshiftCli("compare --json " + q(dir / "shifted.off") + " " + q(dir / "plane.off"));
  j = nlohmann::json::parse(r.out);
  REQUIRE(j["resultToReference"]["rms"].get<double>() == Approx(0.01).epsilon(1e-9));
  REQUIRE(j["referenceToResult"]["max"].get<double>() == Approx(0.01).epsilon(1e-9));
  REQUIRE(j["perVertexRms"].get<double>() == Approx(0.01).epsilon(1e-9));
  r = geoshiftCli("compare " + q(dir / "shifted.off") + " " + q(dir / "plane.off"));
  REQUIRE_THAT(r.out, Catch::Contains("result -> reference") && Catch::Contains("hausdorff"));
}

TEST_CASE("cli: curvature writes _CURVATURE and COLOR_0 into a glb", "[cli]") {
  const fs::path dir = test::tempDir("cli-curvature");
  const double R = 2.0;
  writeOff(dir / "sphere.off", shapes::icosphere(4, R));
  REQUIRE(geoshiftCli("curvature " + q(dir / "sphere.off") + " -o " + q(dir / "k.glb") + " --kind mean").code == 0);
  const Document doc = readDocument((dir / "k.glb").string());
  REQUIRE(doc.parts.size() == 1);
  const MeshPart& part = doc.parts[0];
  REQUIRE(part.colors.size() == part.positions.size());
  const auto it = std::find_if(part.extras.begin(), part.extras.end(),
                               [](const ExtraAttribute& e) { return e.name == "_CURVATURE"; });
  REQUIRE(it != part.extras.end());
  REQUIRE(it->values.size() == part.positions.size());
  for (double h : it->values) REQUIRE(h == Approx(1 / R).epsilon(0.05));
}

TEST_CASE("cli: errors name the problem, exit non-zero and write nothing", "[cli][errors]") {
  const fs::path dir = test::tempDir("cli-errors");
  Run r = geoshiftCli("info " + q(dir / "missing.obj"));
  REQUIRE(r.code == 1);
  REQUIRE_THAT(r.err, Catch::Contains("missing.obj"));

  TriangleSoup s = shapes::tetrahedron();
  s.faces[2][1] = 17;
  writeOff(dir / "range.off", s);
  r = geoshiftCli("smooth " + q(dir / "range.off") + " -o " + q(dir / "out.off"));
  REQUIRE(r.code == 1);
  REQUIRE_THAT(r.err, Catch::Contains("17"));
  REQUIRE_FALSE(fs::exists(dir / "out.off"));

  writeOff(dir / "ok.off", shapes::tetrahedron());
  r = geoshiftCli("smooth " + q(dir / "ok.off") + " -o " + q(dir / "out.xyz"));
  REQUIRE(r.code == 1);
  REQUIRE_THAT(r.err, Catch::Contains("out.xyz"));
  REQUIRE_FALSE(fs::exists(dir / "out.xyz"));

  r = geoshiftCli("smooth " + q(dir / "ok.off") + " -o " + q(dir / "out.off") + " --lambda -1");
  REQUIRE(r.code == 1);
  REQUIRE_FALSE(fs::exists(dir / "out.off"));

  r = geoshiftCli("noise " + q(dir / "ok.off") + " -o " + q(dir / "n.off") + " --dist sideways");
  REQUIRE(r.code != 0);
  REQUIRE_FALSE(fs::exists(dir / "n.off"));
  REQUIRE(geoshiftCli("frobnicate").code != 0);
}

TEST_CASE("cli: an OBJ written back in place keeps its other lines (its text read again to write)", "[cli]") {
  const fs::path dir = test::tempDir("cli-obj-in-place");
  const TriangleSoup ball = shapes::icosphere(2);
  {
    std::ofstream o(dir / "ball.obj", std::ios::binary);
    o.precision(17);
    o << "# a ball\r\nmtllib ball.mtl\r\ng ball\r\n";
    for (const Vec3& p : ball.positions) o << "v " << p.x() << " " << p.y() << " " << p.z() << "\r\n";
    o << "usemtl skin\r\n";
    for (const Face& f : ball.faces) o << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\r\n";
  }
  fs::copy_file(dir / "ball.obj", dir / "a.obj");
  const std::string noise = " --seed 4 --amount 0.3";
  REQUIRE(geoshiftCli("noise " + q(dir / "ball.obj") + " -o " + q(dir / "noisy.obj") + noise).code == 0);
  REQUIRE(geoshiftCli("noise " + q(dir / "a.obj") + " -o " + q(dir / "a.obj") + noise).code == 0);
  const std::string noisy = slurp(dir / "a.obj");
  CHECK(noisy == slurp(dir / "noisy.obj"));
  CHECK(noisy != slurp(dir / "ball.obj"));
  CHECK(noisy.rfind("# a ball\r\nmtllib ball.mtl\r\ng ball\r\nv ", 0) == 0);

  REQUIRE(geoshiftCli("denoise " + q(dir / "noisy.obj") + " -o " + q(dir / "denoised.obj")).code == 0);
  REQUIRE(geoshiftCli("denoise " + q(dir / "a.obj") + " -o " + q(dir / "a.obj")).code == 0);
  CHECK(slurp(dir / "a.obj") == slurp(dir / "denoised.obj"));
  CHECK(slurp(dir / "a.obj") != noisy);
  CHECK_THAT(slurp(dir / "a.obj"), Catch::Contains("\r\nusemtl skin\r\nf "));
  // Nothing left beside them (temporaries).
  size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  CHECK(files == 4);
}

TEST_CASE("cli: every command works on the real meshes of ../shared/data", "[cli][data]") {
  const auto fandiskNoisy = test::sharedData("guided_denoising_bldeng/models/Fandisk0.3/Noisy.obj");
  const auto fandiskClean = test::sharedData("guided_denoising_bldeng/models/Fandisk0.3/Original.obj");
  GEOSHIFT_SKIP_IF_MISSING(fandiskNoisy && fandiskClean, "the Fandisk 0.3 pair");
  const fs::path dir = test::tempDir("cli-data");

  // Smoothing a real noisy scan lowers its normal error against the ground truth.
  auto normalError = [&](const fs::path& result) {
    Run r = geoshiftCli("compare --json " + q(result) + " " + q(*fandiskClean));
    REQUIRE(r.code == 0);
    return nlohmann::json::parse(r.out)["meanNormalAngleDeg"].get<double>();
  };
  REQUIRE(geoshiftCli("smooth " + q(*fandiskNoisy) + " -o " + q(dir / "fandisk.obj")).code == 0);
  const double before = normalError(*fandiskNoisy), after = normalError(dir / "fandisk.obj");
  INFO("mean normal error " << before << " -> " << after << " degrees");
  REQUIRE(after < 0.6 * before);

  // Each format in, the same format out, with the file's vertex count kept.
  for (const char* rel : {"cgal_debian_libcgal_demo/data/meshes/sphere.off", "khronos_gltf_samples/Duck.glb",
                          "khronos_gltf_samples/BoxVertexColors.gltf", "khronos_gltf_samples/VertexColorTest.glb"}) {
    const auto in = test::sharedData(rel);
    if (!in) continue;
    INFO(rel);
    REQUIRE(geoshiftCli("info " + q(*in)).code == 0);
    const fs::path out = dir / ("out" + in->extension().string());
    for (const std::string cmd : {"noise", "smooth", "curvature"}) {
      fs::remove(out);
      Run r = geoshiftCli(cmd + " " + q(*in) + " -o " + q(out));
      INFO(cmd << ": " << r.err);
      REQUIRE(r.code == 0);
      const Document a = readDocument(in->string()), b = readDocument(out.string());
      REQUIRE(a.parts.size() == b.parts.size());
      for (size_t i = 0; i < a.parts.size(); ++i) REQUIRE(a.parts[i].positions.size() == b.parts[i].positions.size());
    }
    REQUIRE(geoshiftCli("compare " + q(out) + " " + q(*in)).code == 0);
  }
}
