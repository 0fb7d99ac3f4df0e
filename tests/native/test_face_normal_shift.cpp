// Face neighbourhoods and the blurring mean shift of face normals (face_normal_shift.hpp): rows
// against a brute-force search, geodesic and straight distances on a plane, the shift's fixed
// points and crease keeping, threads.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <map>

#include "geoshift/error.hpp"
#include "geoshift/face_normal_shift.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/shapes.hpp"

using namespace geoshift;

namespace {

Mesh build(const TriangleSoup& soup) { return buildMesh(soup).mesh; }

Vec3 centroid(const Mesh& m, int f) {
  const Face& t = m.face(f);
  return (m.position(t[0]) + m.position(t[1]) + m.position(t[2])) / 3;
}

std::map<int, float> row(const FaceNeighborhoods& h, int f) {
  std::map<int, float> out;
  const auto faces = h.row(f);
  for (size_t j = 0; j < faces.size(); ++j) out[faces[j]] = h.spatialWeight(f, static_cast<int>(j));
  return out;
}

}  // namespace

// On a plane every face within r of a face's centroid is reachable across edges inside the disc, so
// the rows must be exactly the brute-force search over all faces.
TEST_CASE("face neighbourhoods on a plane are the faces within r, with Gaussian weights", "[face-normal-shift]") {
  const Mesh plane = build(shapes::grid(24));
  FaceNeighborhoodOptions o;
  const FaceNeighborhoods h = faceNeighborhoods(plane, o);
  const double ael = averageEdgeLength(plane);
  REQUIRE(h.radius == Approx(o.radius * ael));
  REQUIRE(static_cast<int>(h.start.size()) == plane.faceCount() + 1);
  for (int f = 0; f < plane.faceCount(); f += 7) {
    REQUIRE(h.row(f).front() == f);  // the face itself first
    std::map<int, float> expected;
    for (int g = 0; g < plane.faceCount(); ++g) {
      const double d2 = (centroid(plane, g) - centroid(plane, f)).squaredNorm();
      if (d2 <= h.radius * h.radius)
        expected[g] = static_cast<float>(std::exp(-d2 / (2 * h.spatialBandwidth * h.spatialBandwidth)));
    }
    const std::map<int, float> got = row(h, f);
    REQUIRE(got.size() == expected.size());
    for (const auto& [g, w] : expected) {
      REQUIRE(got.count(g) == 1);
      REQUIRE(got.at(g) == Approx(w).epsilon(1e-5));
    }
  }
}

TEST_CASE("geodesic face neighbourhoods agree with straight ones on a plane", "[face-normal-shift]") {
  const Mesh plane = build(shapes::grid(16));
  FaceNeighborhoodOptions straight, geodesic;
  geodesic.geodesic = true;
  const FaceNeighborhoods a = faceNeighborhoods(plane, straight), b = faceNeighborhoods(plane, geodesic);
  for (int f = 0; f < plane.faceCount(); ++f) {
    const std::map<int, float> ra = row(a, f), rb = row(b, f);
    // Faces exactly at r may fall either side by round-off: compare those well inside.
    for (const auto& [g, w] : ra) {
      const double d = (centroid(plane, g) - centroid(plane, f)).norm();
      if (d > 0.98 * a.radius) continue;
      REQUIRE(rb.count(g) == 1);
      REQUIRE(rb.at(g) == Approx(w).epsilon(1e-4));
    }
  }
}

TEST_CASE("the face normal shift keeps constant normals and creases, and ignores threads", "[face-normal-shift]") {
  const Mesh box = build(shapes::box(8, 8, 8));
  const FaceNeighborhoods h = faceNeighborhoods(box);
  const std::vector<Vec3> normals = faceNormals(box);
  const std::vector<double> areas = faceAreas(box);
  // The normals of a box: each face's neighbours across a crease differ by |n_g − n_f| = √2,
  // far outside h_r = 0.35 (kernel weight e^-8.2 against 1), so every normal stays within 0.1°.
  const std::vector<Vec3> shifted = shiftFaceNormals(h, areas, normals, 0.35);
  for (int f = 0; f < box.faceCount(); ++f) REQUIRE((shifted[f] - normals[f]).norm() < 2e-3);
  // A wide range kernel averages across the crease: the faces beside an edge turn.
  const std::vector<Vec3> blurred = shiftFaceNormals(h, areas, normals, 5.0);
  double turned = 0;
  for (int f = 0; f < box.faceCount(); ++f) turned = std::max(turned, (blurred[f] - normals[f]).norm());
  REQUIRE(turned > 0.1);

  // Noisy normals: 1 and 2 threads give the same bits, and the shift moves them towards the truth.
  std::vector<Vec3> noisy = normals;
  for (int f = 0; f < box.faceCount(); ++f)
    noisy[f] = (normals[f] + 0.2 * Vec3(std::sin(3.1 * f), std::cos(1.7 * f), std::sin(0.9 * f + 1))).normalized();
  ParallelOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const std::vector<Vec3> a = shiftFaceNormals(h, areas, noisy, 0.35, one), b = shiftFaceNormals(h, areas, noisy, 0.35, two);
  REQUIRE(a == b);
  double before = 0, after = 0;
  for (int f = 0; f < box.faceCount(); ++f) {
    before += (noisy[f] - normals[f]).squaredNorm();
    after += (a[f] - normals[f]).squaredNorm();
  }
  REQUIRE(after < 0.5 * before);

  FaceNeighborhoodOptions bad;
  bad.radius = -1;
  REQUIRE_THROWS_AS(faceNeighborhoods(box, bad), InputError);
  REQUIRE_THROWS_AS(shiftFaceNormals(h, areas, noisy, 0), InputError);
  REQUIRE_THROWS_AS(shiftFaceNormals(h, std::vector<double>(3), noisy, 0.35), InputError);
}

// The shift's wider-instruction form (AVX2 on x86-64 processors that have it) runs the portable
// form's operations in the same order: every normal must be the same bits, for straight and stored
// (geodesic) weights, a zero normal, and range bandwidths whose exponents reach the clamp. (On a
// processor without AVX2 both calls run the portable form.)
TEST_CASE("the face normal shift gives the same bits with and without the processor's wider instructions",
          "[face-normal-shift]") {
  const Mesh sphere = build(shapes::icosphere(4));
  FaceNeighborhoodOptions geodesic;
  geodesic.geodesic = true;
  const FaceNeighborhoods straight = faceNeighborhoods(sphere), stored = faceNeighborhoods(sphere, geodesic);
  const std::vector<double> areas = faceAreas(sphere);
  std::vector<Vec3> noisy = faceNormals(sphere);
  for (int f = 0; f < sphere.faceCount(); ++f)
    noisy[f] = (noisy[f] + 0.4 * Vec3(std::sin(3.1 * f), std::cos(1.7 * f), std::sin(0.9 * f + 1))).normalized();
  noisy[17] = Vec3::Zero();
  ParallelOptions portable;
  portable.portableKernels = true;
  for (const FaceNeighborhoods* h : {&straight, &stored}) {
    for (double hr : {0.02, 0.35, 0.5, 3.0}) {
      const std::vector<Vec3> a = shiftFaceNormals(*h, areas, noisy, hr), b = shiftFaceNormals(*h, areas, noisy, hr, portable);
      REQUIRE(a.size() == b.size());
      REQUIRE(std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0);
      REQUIRE(b[17] == Vec3::Zero());
      REQUIRE(std::abs(b[5].norm() - 1) < 1e-12);
    }
  }
}
