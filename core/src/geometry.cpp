#include "geoshift/geometry.hpp"

#include <algorithm>
#include <cmath>

#include "geoshift/error.hpp"

namespace geoshift {
namespace {

// Angle between two vectors via atan2(|a x b|, a.b): acos of a normalised dot product loses half
// the digits near 0 and π, which is where needles and caps live.
double angleBetween(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

}  // namespace

double averageEdgeLength(const Mesh& mesh) {
  double sum = 0;
  long long count = 0;
  for (int h = 0; h < mesh.halfedgeCount(); ++h) {
    // Each interior edge has two half-edges; count it from the smaller one only.
    const int t = mesh.twin(h);
    if (t >= 0 && t < h) continue;
    sum += (mesh.position(mesh.head(h)) - mesh.position(mesh.tail(h))).norm();
    ++count;
  }
  if (count == 0 || !(sum > 0)) throw InputError("the mesh has no edge of positive length");
  return sum / static_cast<double>(count);
}

std::vector<Vec3> faceNormals(const Mesh& mesh) {
  std::vector<Vec3> normals(mesh.faceCount(), Vec3::Zero());
  for (int f = 0; f < mesh.faceCount(); ++f) {
    const Vec3 n = faceCross(mesh, f);
    const double len = n.norm();
    if (len > 0) normals[f] = n / len;
  }
  return normals;
}

double meanNormalTurn(const Mesh& mesh, const std::vector<Vec3>& positions) {
  if (positions.size() != static_cast<size_t>(mesh.vertexCount()))
    throw InputError("meanNormalTurn: " + std::to_string(positions.size()) + " positions for a mesh of " +
                     std::to_string(mesh.vertexCount()) + " vertices");
  // Each face's normal computed where it is needed (twice per face), so that nothing the size of
  // the mesh is allocated: the denoiser calls this while it holds several copies of the positions.
  auto normal = [&](int f) -> Vec3 {
    const Face& t = mesh.face(f);
    const Vec3 c = (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
    const double len = c.norm();
    return len > 0 ? Vec3(c / len) : Vec3::Zero();
  };
  double sum = 0;
  long edges = 0;
  for (int h = 0; h < mesh.halfedgeCount(); ++h) {
    const int o = mesh.twin(h);
    if (o <= h) continue;
    sum += std::acos(std::clamp(normal(Mesh::faceOf(h)).dot(normal(Mesh::faceOf(o))), -1.0, 1.0));
    ++edges;
  }
  return edges > 0 ? sum / static_cast<double>(edges) : 0.0;
}

std::vector<double> faceAreas(const Mesh& mesh) {
  std::vector<double> areas(mesh.faceCount());
  for (int f = 0; f < mesh.faceCount(); ++f) {
    areas[f] = 0.5 * faceCross(mesh, f).norm();
  }
  return areas;
}

std::vector<Vec3> vertexNormals(const Mesh& mesh) {
  // Thürmer–Wüthrich: weighting each face normal by the corner angle makes the result independent
  // of how a flat region around the vertex is triangulated (area weights are not).
  std::vector<Vec3> sums(mesh.vertexCount(), Vec3::Zero());
  for (int f = 0; f < mesh.faceCount(); ++f) {
    const Face& t = mesh.face(f);
    const Vec3 n = faceCross(mesh, f);
    const double len = n.norm();
    if (!(len > 0)) continue;
    const Vec3 unit = n / len;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.position(t[k]);
      const double angle = angleBetween(mesh.position(t[(k + 1) % 3]) - p,
                                        mesh.position(t[(k + 2) % 3]) - p);
      sums[t[k]] += angle * unit;
    }
  }
  for (Vec3& n : sums) {
    const double len = n.norm();
    n = len > 0 ? Vec3(n / len) : Vec3(Vec3::Zero());
  }
  return sums;
}

std::vector<double> mixedVoronoiAreas(const Mesh& mesh) {
  // Meyer et al. 2003, section 3.3, with vcglib's obtuse rule: a non-obtuse triangle gives each
  // corner its Voronoi part (|e|² cot(opposite)/8 over the two incident edges; the three parts sum
  // to the triangle's area), an obtuse one gives half its area to the obtuse corner and a quarter to
  // each other corner. Either way every triangle's area is distributed exactly once.
  std::vector<double> areas(mesh.vertexCount(), 0.0);
  for (int f = 0; f < mesh.faceCount(); ++f) {
    const Face& t = mesh.face(f);
    const Vec3& p0 = mesh.position(t[0]);
    const Vec3& p1 = mesh.position(t[1]);
    const Vec3& p2 = mesh.position(t[2]);
    const double doubleArea = (p1 - p0).cross(p2 - p0).norm();
    if (!(doubleArea > 0)) continue;
    const double area = 0.5 * doubleArea;
    // Corner dot products: negative means that corner is obtuse.
    const double d0 = (p1 - p0).dot(p2 - p0);
    const double d1 = (p0 - p1).dot(p2 - p1);
    const double d2 = (p0 - p2).dot(p1 - p2);
    if (d0 > 0 && d1 > 0 && d2 > 0) {
      // cot(angle at k) = d_k / (2 area)
      const double c0 = d0 / doubleArea, c1 = d1 / doubleArea, c2 = d2 / doubleArea;
      const double e01 = (p1 - p0).squaredNorm();
      const double e12 = (p2 - p1).squaredNorm();
      const double e20 = (p0 - p2).squaredNorm();
      areas[t[0]] += (e20 * c1 + e01 * c2) / 8.0;
      areas[t[1]] += (e01 * c2 + e12 * c0) / 8.0;
      areas[t[2]] += (e12 * c0 + e20 * c1) / 8.0;
    } else {
      const int obtuse = d0 <= 0 ? 0 : (d1 <= 0 ? 1 : 2);
      for (int k = 0; k < 3; ++k) areas[t[k]] += k == obtuse ? area / 2.0 : area / 4.0;
    }
  }
  return areas;
}

Eigen::AlignedBox3d boundingBox(const std::vector<Vec3>& positions) {
  Eigen::AlignedBox3d box;  // default-constructed box is empty
  for (const Vec3& p : positions) box.extend(p);
  return box;
}

Similarity unitCubeTransform(const std::vector<Vec3>& positions) {
  Similarity s;
  const Eigen::AlignedBox3d box = boundingBox(positions);
  if (box.isEmpty()) return s;
  const double longest = box.sizes().maxCoeff();
  // A single point (or all points coincident) has no size to normalise: only centre it.
  s.scale = longest > 0 ? 1.0 / longest : 1.0;
  s.offset = Vec3::Constant(0.5) - s.scale * box.center();
  return s;
}

Similarity normalizeToUnitCube(Mesh& mesh) {
  const Similarity s = unitCubeTransform(mesh.positions());
  for (Vec3& p : mesh.positions()) p = s.apply(p);
  return s;
}

}  // namespace geoshift
