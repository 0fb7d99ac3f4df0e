// geoshift geodesic / logmap / expmap, run as a user runs them.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/io.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;
using namespace geoshift::test;

namespace {

struct Row {
  int vertex;
  double u, theta, x, y;
};

std::vector<Row> parseCsv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "vertex,u,theta,x,y");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    Row r{};
    char c;
    std::istringstream l(line);
    l >> r.vertex >> c >> r.u >> c >> r.theta >> c >> r.x >> c >> r.y;
    REQUIRE(!l.fail());
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

TEST_CASE("cli: logmap on a plane gives Euclidean polar coordinates, expmap walks them back", "[cli][geodesic]") {
  const fs::path dir = tempDir("cli-logmap");
  const TriangleSoup grid = shapes::grid(21, 0.2);
  writeOff(dir / "plane.off", grid);
  const int source = 10 * 21 + 10;  // the centre vertex
  Run r = geoshiftCli("logmap " + q(dir / "plane.off") + " --source " + std::to_string(source) + " --radius 0.3 --absolute");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto rows = parseCsv(r.out);
  REQUIRE(rows.size() > 20);
  REQUIRE(rows[0].vertex == source);
  REQUIRE(rows[0].u == 0.0);
  for (const Row& row : rows) {
    const Vec3 d = grid.positions[row.vertex] - grid.positions[source];
    REQUIRE(row.u == Approx(d.norm()).margin(1e-9));
    REQUIRE(std::hypot(row.x, row.y) == Approx(d.norm()).margin(1e-9));
    REQUIRE(row.u <= 0.3 + 1e-12);
  }
  // Feed a few rows back: from the source vertex (bary 1,0,0 of one of its faces is the same point,
  // but --source is what logmap used) along x,y lands on the row's vertex.
  int checked = 0;
  for (size_t i = 1; i < rows.size(); i += 7, ++checked) {
    const Row& row = rows[i];
    std::ostringstream cmd;
    cmd.precision(17);
    cmd << "expmap " << q(dir / "plane.off") << " --source " << source << " --absolute --json --vector=" << row.x << ","
        << row.y;
    Run e = geoshiftCli(cmd.str());
    INFO(e.err);
    REQUIRE(e.code == 0);
    const auto j = nlohmann::json::parse(e.out);
    const Vec3 p(j["point"][0], j["point"][1], j["point"][2]);
    REQUIRE((p - grid.positions[row.vertex]).norm() < 1e-9);
    REQUIRE(j["hitBoundary"] == false);
  }
  REQUIRE(checked > 2);
}

// A face point is given and reported in the file's corners, also on a face the build turned over
// to agree with its neighbours (docs/denoising.md#bad-input).
TEST_CASE("cli: expmap face points on faces wound backwards use the file's corners", "[cli][geodesic][orientation]") {
  const fs::path dir = tempDir("cli-facepoint-orientation");
  const TriangleSoup grid = shapes::grid(21, 0.1);
  TriangleSoup mixed = grid;
  for (size_t f = 6; f < mixed.faces.size(); f += 7) std::swap(mixed.faces[f][1], mixed.faces[f][2]);  // face 300 among them
  writeOff(dir / "plane.off", grid);
  writeOff(dir / "mixed.off", mixed);
  const auto walk = [&](const std::string& file, const std::string& bary, const std::string& vector = "2.5,1.5") {
    const Run r = geoshiftCli("expmap " + q(dir / file) + " --face 300 --bary " + bary + " --vector=" + vector + " --json");
    INFO(r.err);
    REQUIRE(r.code == 0);
    return nlohmann::json::parse(r.out);
  };
  // The same point: (0.2, 0.3, 0.5) of face 300's corners, which the mixed file lists as 0, 2, 1.
  const auto a = walk("plane.off", "0.2,0.3,0.5"), b = walk("mixed.off", "0.2,0.5,0.3");
  const Vec3 pa(a["point"][0], a["point"][1], a["point"][2]), pb(b["point"][0], b["point"][1], b["point"][2]);
  REQUIRE((pa - pb).norm() < 1e-12);
  REQUIRE(a["face"] == b["face"]);
  // The end's barycentric coordinates weigh the file's corners of the end face, as the file lists
  // them: after the long walk, and after a short one that ends in face 300, a face turned over.
  const auto shortA = walk("plane.off", "0.2,0.3,0.5", "0.01,0.01"), shortB = walk("mixed.off", "0.2,0.5,0.3", "0.01,0.01");
  REQUIRE(shortB["face"] == 300);
  for (const auto& [j, soup] : {std::pair{a, grid}, std::pair{b, mixed}, std::pair{shortA, grid}, std::pair{shortB, mixed}}) {
    const Face& f = soup.faces[j["face"].get<int>()];
    const Vec3 fromBary = j["bary"][0].get<double>() * soup.positions[f[0]] + j["bary"][1].get<double>() * soup.positions[f[1]] +
                          j["bary"][2].get<double>() * soup.positions[f[2]];
    const Vec3 point(j["point"][0], j["point"][1], j["point"][2]);
    REQUIRE((fromBary - point).norm() < 1e-12);
  }
}

TEST_CASE("cli: logmap and expmap from a face point, lengths in AEL by default", "[cli][geodesic]") {
  const fs::path dir = tempDir("cli-facepoint");
  const TriangleSoup grid = shapes::grid(21, 0.1);
  writeOff(dir / "plane.off", grid);
  const std::string face = " --face 300 --bary 0.2,0.3,0.5";
  Run r = geoshiftCli("logmap " + q(dir / "plane.off") + face + " --radius 3");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto rows = parseCsv(r.out);
  REQUIRE(!rows.empty());
  const Face& f = grid.faces[300];
  const Vec3 p = 0.2 * grid.positions[f[0]] + 0.3 * grid.positions[f[1]] + 0.5 * grid.positions[f[2]];
  const Row& far = rows.back();
  REQUIRE(far.u <= 3.0 + 1e-12);
  std::ostringstream cmd;
  cmd.precision(17);
  cmd << "expmap " << q(dir / "plane.off") << face << " --json --vector=" << far.x << "," << far.y;
  Run e = geoshiftCli(cmd.str());
  INFO(e.err);
  REQUIRE(e.code == 0);
  const auto j = nlohmann::json::parse(e.out);
  const Vec3 end(j["point"][0], j["point"][1], j["point"][2]);
  REQUIRE((end - grid.positions[far.vertex]).norm() < 1e-9);
  // u in AEL: the Euclidean distance over the average edge length
  REQUIRE(far.u * averageEdgeLength(buildMesh(grid).mesh) == Approx((grid.positions[far.vertex] - p).norm()).epsilon(1e-9));

  // --toward: walk 0.1 (absolute) in +x
  e = geoshiftCli("expmap " + q(dir / "plane.off") + face + " --toward 1,0,0 --length 0.1 --absolute --json");
  REQUIRE(e.code == 0);
  const auto t = nlohmann::json::parse(e.out);
  REQUIRE(Vec3(t["point"][0], t["point"][1], t["point"][2]).isApprox(p + Vec3(0.1, 0, 0), 1e-9));
  // toward the boundary: stops there
  e = geoshiftCli("expmap " + q(dir / "plane.off") + face + " --toward 1,0,0 --length 5 --absolute --json");
  REQUIRE(e.code == 0);
  const auto b = nlohmann::json::parse(e.out);
  REQUIRE(b["hitBoundary"] == true);
  REQUIRE(b["point"][0].get<double>() == Approx(1.0).margin(1e-9));
}

TEST_CASE("cli: geodesic writes the distance field of a sphere", "[cli][geodesic]") {
  const fs::path dir = tempDir("cli-geodesic");
  const double R = 1.5;
  const TriangleSoup sphere = shapes::icosphere(4, R);
  writeOff(dir / "sphere.off", sphere);
  Run r = geoshiftCli("geodesic " + q(dir / "sphere.off") + " -o " + q(dir / "d.glb") + " --source 0 --absolute");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const Document doc = readDocument((dir / "d.glb").string());
  const MeshPart& part = doc.parts[0];
  const ExtraAttribute* dist = nullptr;
  for (const ExtraAttribute& e : part.extras)
    if (e.name == "_GEODESIC_DISTANCE") dist = &e;
  REQUIRE(dist);
  REQUIRE(part.colors.size() == part.positions.size());
  const Vec3 s = part.positions[0];
  double worst = 0;
  for (size_t v = 0; v < part.positions.size(); ++v) {
    const double exact = R * std::acos(std::clamp(s.dot(part.positions[v]) / (R * R), -1.0, 1.0));
    worst = std::max(worst, std::abs(dist->values[v] - exact));
  }
  INFO("worst distance error " << worst);
  REQUIRE(worst < 0.02 * M_PI * R);

  // with a radius, vertices beyond it are marked -1
  r = geoshiftCli("geodesic " + q(dir / "sphere.off") + " -o " + q(dir / "r.glb") + " --source 0 --radius 3");
  REQUIRE(r.code == 0);
  const Document small = readDocument((dir / "r.glb").string());
  int beyond = 0;
  for (const ExtraAttribute& e : small.parts[0].extras)
    if (e.name == "_GEODESIC_DISTANCE")
      for (double d : e.values) beyond += d < 0;
  REQUIRE(beyond > static_cast<int>(part.positions.size()) / 2);
}

TEST_CASE("cli: geodesic commands reject bad sources clearly", "[cli][geodesic][errors]") {
  const fs::path dir = tempDir("cli-geodesic-errors");
  writeOff(dir / "t.off", shapes::tetrahedron());
  const std::string in = q(dir / "t.off");
  Run r = geoshiftCli("logmap " + in + " --source 9 --radius 1");
  REQUIRE(r.code == 1);
  REQUIRE_THAT(r.err, Catch::Contains("source vertex 9 is out of range (4 vertices"));
  r = geoshiftCli("expmap " + in + " --face 7 --bary 1,0,0 --vector 1,0");
  REQUIRE(r.code == 1);
  REQUIRE_THAT(r.err, Catch::Contains("face 7 is out of range"));
  r = geoshiftCli("expmap " + in + " --face 0 --bary 0.5,0.9,0 --vector 1,0");
  REQUIRE(r.code == 1);
  REQUIRE_THAT(r.err, Catch::Contains("sum to 1"));
  REQUIRE(geoshiftCli("logmap " + in + " --source 0 --face 0 --bary 1,0,0 --radius 1").code != 0);
  REQUIRE(geoshiftCli("expmap " + in + " --face 0 --bary 1,0,0").code == 1);
  r = geoshiftCli("geodesic " + in + " -o " + q(dir / "o.glb") + " --source 0 --radius -1");
  REQUIRE(r.code == 1);
  REQUIRE_FALSE(fs::exists(dir / "o.glb"));
}
