// The CLI on PLY and STL files: read by extension, written by extension, damaged input reported
// with the reader's message and nothing written, and the --max-vertices limit (also on a GLB whose
// accessor without data declares 400 million vertices).
#include <catch2/catch.hpp>

#include "cli_support.hpp"
#include "geoshift/io.hpp"
#include "glb_bytes.hpp"

using namespace geoshift;
using namespace geoshift::test;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

TEST_CASE("cli: PLY and STL in, PLY and STL out, errors as messages", "[cli][io][ply][stl]") {
  const auto dir = tempDir("cli-ply-stl");
  // A quad and a triangle with normals, colors and a scalar property.
  spit(dir / "in.ply", "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                       "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\n"
                       "property uchar blue\nproperty short quality\nelement face 2\nproperty list uchar int vertex_indices\n"
                       "end_header\n0 0 0 0 0 1 255 0 0 -3\n1 0 0 0 0 1 0 255 0 0\n1 1 0 0 0 1 0 0 255 7\n"
                       "0 1 0 0 0 1 10 20 30 1000\n0.5 2 0 0 0 1 1 2 3 5\n4 0 1 2 3\n3 3 2 4\n");
  Run r = geoshiftCli("info " + q(dir / "in.ply"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("format  PLY") && Contains("POSITION, NORMAL, COLOR_0, _quality (1)"));
  r = geoshiftCli("smooth " + q(dir / "in.ply") + " -o " + q(dir / "out.ply") + " --iterations 2");
  REQUIRE(r.code == 0);
  const MeshPart before = readDocument((dir / "in.ply").string()).parts.at(0);
  const MeshPart after = readDocument((dir / "out.ply").string()).parts.at(0);
  CHECK(after.faces == before.faces);
  CHECK(after.colors == before.colors);
  REQUIRE(after.extras.size() == 1);
  CHECK(after.extras[0].values == before.extras[0].values);
  CHECK(after.positions != before.positions);

  r = geoshiftCli("smooth " + q(dir / "out.ply") + " -o " + q(dir / "out.stl") + " --iterations 1");
  REQUIRE(r.code == 0);
  r = geoshiftCli("info " + q(dir / "out.stl"));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("format  STL") && Contains("faces               3"));

  spit(dir / "bad.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n");
  r = geoshiftCli("smooth " + q(dir / "bad.ply") + " -o " + q(dir / "never.ply"));
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains("bad.ply:13: face 0: index 9 out of range (3 vertices)"));
  CHECK_FALSE(fs::exists(dir / "never.ply"));
  r = geoshiftCli("info " + q(dir / "in.ply") + " --max-vertices 4");
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains("declares 5 vertices, more than the limit of 4 (raise it with --max-vertices)"));
  CHECK(geoshiftCli("--max-vertices 5 info " + q(dir / "in.ply")).code == 0);

  // A file whose every face is degenerate: the message names the file (and the part, where the
  // format has parts), and nothing is written.
  spit(dir / "flat.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n");
  r = geoshiftCli("denoise " + q(dir / "flat.ply") + " -o " + q(dir / "never.ply"));
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains((dir / "flat.ply").string() + ": PLY: no valid triangles: all 1 faces are degenerate"));
  CHECK_FALSE(fs::exists(dir / "never.ply"));
}


TEST_CASE("cli: a tiny GLB declaring 400 million vertices is refused at once", "[cli][io][gltf]") {
  const auto dir = tempDir("cli-glb-limit");
  const nlohmann::json j = nlohmann::json::parse(R"({
    "asset": {"version": "2.0"},
    "accessors": [{"componentType": 5126, "count": 400000000, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}]})");
  spit(dir / "zeros.glb", glbBytes(j, ""));
  Run r = geoshiftCli("info " + q(dir / "zeros.glb"));
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains("zeros.glb: mesh 0 '' primitive 0 POSITION (accessor 0) declares 400000000 vertices, more than the "
                             "limit of 50000000 (raise it with --max-vertices)"));
  r = geoshiftCli("info " + q(dir / "zeros.glb") + " --max-vertices 1000");
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains("more than the limit of 1000"));
}
