// geoshift terrain, run as a user runs it.
#include <catch2/catch.hpp>

#include <cmath>

#include "cli_support.hpp"
#include "geoshift/io.hpp"
#include "geoshift/terrain.hpp"

using namespace geoshift;
using namespace geoshift::test;

namespace {

const ExtraAttribute* extra(const MeshPart& p, const std::string& name) {
  for (const auto& e : p.extras)
    if (e.name == name) return &e;
  return nullptr;
}

}  // namespace

TEST_CASE("cli: terrain from a LAS file writes a glb with the attributes, georeferenced and y-up", "[cli][terrain]") {
  const auto las = sharedData("pdal_testdata/las/simple.las");
  GEOSHIFT_SKIP_IF_MISSING(las, "pdal_testdata/las/simple.las");
  const fs::path dir = tempDir("cli-terrain-las");
  const Run r = geoshiftCli("terrain " + q(*las) + " -o " + q(dir / "t.glb"));
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("points read: 1065") != std::string::npos);
  CHECK(r.out.find("vertices: 1065") != std::string::npos);
  CHECK(r.out.find("_HEIGHT_ABOVE_GROUND:") != std::string::npos);
  CHECK(r.out.find("(classes: 1 2)") != std::string::npos);

  const Document doc = readDocument((dir / "t.glb").string());
  REQUIRE(doc.parts.size() == 1u);
  const MeshPart& part = doc.parts[0];
  REQUIRE(part.positions.size() == 1065u);
  CHECK(part.colors.size() == 1065u);
  REQUIRE(extra(part, "_CLASS"));
  REQUIRE(extra(part, "_HEIGHT_ABOVE_GROUND"));
  // The node puts the float32 local coordinates back at their place, with z up turned into y up.
  const TerrainPoints pts = readLas(las->string());
  const TriangleSoup world = worldSoup(doc);
  for (size_t i = 0; i < pts.positions.size(); i += 97) {
    const Vec3& p = pts.positions[i];
    CHECK(world.positions[i].x() == Approx(p.x()).margin(1e-3));
    CHECK(world.positions[i].y() == Approx(p.z()).margin(1e-3));
    CHECK(world.positions[i].z() == Approx(-p.y()).margin(1e-3));
    CHECK(extra(part, "_CLASS")->values[i] == pts.classes[i]);
  }
}

TEST_CASE("cli: procedural terrain and DEM input", "[cli][terrain]") {
  const fs::path dir = tempDir("cli-terrain-proc");
  Run r = geoshiftCli("terrain --procedural 33 --seed 3 -o " + q(dir / "p.glb"));
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("vertices: 1089, faces: 2048") != std::string::npos);
  const Document doc = readDocument((dir / "p.glb").string());
  CHECK(extra(doc.parts[0], "_VEGETATION_HEIGHT"));
  CHECK(extra(doc.parts[0], "_CLASS"));
  // Same seed, same file content.
  REQUIRE(geoshiftCli("terrain --procedural 33 --seed 3 -o " + q(dir / "p2.glb")).code == 0);
  CHECK(slurp(dir / "p.glb") == slurp(dir / "p2.glb"));

  const auto dem = sharedData("dem_debian_r_packages/stars/olinda_dem_utm25s.tif");
  GEOSHIFT_SKIP_IF_MISSING(dem, "dem_debian_r_packages/stars/olinda_dem_utm25s.tif");
  r = geoshiftCli("terrain " + q(*dem) + " -o " + q(dir / "d.glb"));
  REQUIRE(r.code == 0);
  CHECK(r.out.find("vertices: 12321, faces: 24200") != std::string::npos);
  CHECK(r.out.find("_ELEVATION: -1 .. 88") != std::string::npos);
}

TEST_CASE("cli: terrain errors exit 1 with a message and write nothing", "[cli][terrain][errors]") {
  const fs::path dir = tempDir("cli-terrain-err");
  Run r = geoshiftCli("terrain -o " + q(dir / "a.glb"));
  CHECK(r.code == 1);
  CHECK(r.err.find("--procedural") != std::string::npos);
  spit(dir / "bad.las", "LASF but not really");
  r = geoshiftCli("terrain " + q(dir / "bad.las") + " -o " + q(dir / "b.glb"));
  CHECK(r.code == 1);
  CHECK(r.err.find("bad.las") != std::string::npos);
  CHECK(!fs::exists(dir / "b.glb"));
  spit(dir / "p.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "end_header\n0 0 0\n1 0 0\n0 1 0\n");
  r = geoshiftCli("terrain " + q(dir / "p.ply") + " --procedural 5 -o " + q(dir / "c.glb"));
  CHECK(r.code == 1);
  CHECK(r.err.find("not both") != std::string::npos);
  r = geoshiftCli("terrain " + q(dir / "p.ply") + " --ground-only -o " + q(dir / "c.glb"));
  CHECK(r.code == 1);
  CHECK(r.err.find("no classification") != std::string::npos);
  CHECK(!fs::exists(dir / "c.glb"));
}
