#include "geoshift/bilateral_normal.hpp"

#include <cmath>
#include <string>

#include "geoshift/check.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"

namespace geoshift {
namespace {

void checkOptions(const BilateralNormalOptions& o) {
  requireAtLeast("bilateral normal filter: normal iterations", o.normalIterations, 0);
  requireAtLeast("bilateral normal filter: spatial sigma (AEL)", o.sigmaSpatial, 0);
  requirePositive("bilateral normal filter: range sigma", o.sigmaRange);
  requireAtLeast("bilateral normal filter: vertex iterations", o.vertexUpdate.iterations, 0);
}

Vec3 centroid(const Mesh& mesh, int f) {
  const Face& t = mesh.face(f);
  return (mesh.position(t[0]) + mesh.position(t[1]) + mesh.position(t[2])) / 3.0;
}

// Neighbouring faces of each face, flat: face f's are [start[f], start[f+1]), without f itself.
struct FaceRing {
  std::vector<int> start, face;
};

FaceRing faceRing(const Mesh& mesh, FaceNeighborhood kind) {
  FaceRing r;
  const int nf = mesh.faceCount();
  r.start.reserve(nf + 1);
  std::vector<int> stamp(nf, -1);
  for (int f = 0; f < nf; ++f) {
    r.start.push_back(static_cast<int>(r.face.size()));
    stamp[f] = f;
    auto add = [&](int g) {
      if (g >= 0 && stamp[g] != f) {
        stamp[g] = f;
        r.face.push_back(g);
      }
    };
    if (kind == FaceNeighborhood::Edge) {
      for (int k = 0; k < 3; ++k) {
        const int t = mesh.twin(3 * f + k);
        if (t >= 0) add(Mesh::faceOf(t));
      }
    } else {
      for (int v : mesh.face(f)) mesh.forEachOutgoing(v, [&](int h) { add(Mesh::faceOf(h)); });
    }
  }
  r.start.push_back(static_cast<int>(r.face.size()));
  return r;
}

}  // namespace

double meanAdjacentCentroidDistance(const Mesh& mesh) {
  double sum = 0;
  long count = 0;
  for (int h = 0; h < mesh.halfedgeCount(); ++h) {
    const int t = mesh.twin(h);
    if (t <= h) continue;  // each interior edge once; boundary edges (-1) skipped
    sum += (centroid(mesh, Mesh::faceOf(h)) - centroid(mesh, Mesh::faceOf(t))).norm();
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

std::vector<Vec3> bilateralFilterFaceNormals(const Mesh& mesh, std::vector<Vec3> normals,
                                             double sigmaSpatial, const BilateralNormalOptions& options,
                                             const Progress& progress) {
  checkOptions(options);
  const int nf = mesh.faceCount();
  if (static_cast<int>(normals.size()) != nf) {
    throw InputError("bilateral normal filter: " + std::to_string(normals.size()) + " normals for " +
                     std::to_string(nf) + " faces");
  }
  requirePositive("bilateral normal filter: spatial sigma", sigmaSpatial);
  for (int f = 0; f < nf; ++f) {
    if (!normals[f].allFinite()) {
      throw InputError("bilateral normal filter: normal of face " + std::to_string(f) + " is not finite");
    }
  }
  const FaceRing ring = faceRing(mesh, options.neighborhood);
  const std::vector<double> area = faceAreas(mesh);
  std::vector<Vec3> c(nf);
  for (int f = 0; f < nf; ++f) c[f] = centroid(mesh, f);
  // The positions stay put while the normals are filtered, so area × spatial weight is computed once.
  std::vector<double> fixedWeight(ring.face.size());
  const double spatial = -0.5 / (sigmaSpatial * sigmaSpatial);
  for (int f = 0; f < nf; ++f) {
    for (int k = ring.start[f]; k < ring.start[f + 1]; ++k) {
      const int g = ring.face[k];
      fixedWeight[k] = area[g] * std::exp(spatial * (c[f] - c[g]).squaredNorm());
    }
  }
  const double range = -0.5 / (options.sigmaRange * options.sigmaRange);
  std::vector<Vec3> next(nf);
  for (int it = 0; it < options.normalIterations; ++it) {
    progress.step(static_cast<double>(it) / options.normalIterations, "bilateral normals");
    for (int f = 0; f < nf; ++f) {
      // The face itself enters with spatial and range weight 1, as in any bilateral filter; it
      // also keeps a face without neighbours (or with all weights underflowing) defined.
      Vec3 sum = area[f] * normals[f];
      for (int k = ring.start[f]; k < ring.start[f + 1]; ++k) {
        const Vec3& n = normals[ring.face[k]];
        sum += fixedWeight[k] * std::exp(range * (normals[f] - n).squaredNorm()) * n;
      }
      const double len = sum.norm();
      next[f] = len > 0 ? Vec3(sum / len) : normals[f];
    }
    normals.swap(next);
  }
  progress.step(1.0, "bilateral normals");
  return normals;
}

BilateralNormalResult bilateralNormalDenoise(Mesh& mesh, const BilateralNormalOptions& options,
                                             const Progress& progress) {
  checkOptions(options);
  BilateralNormalResult result;
  const double unit = options.sigmaSpatial > 0 ? averageEdgeLength(mesh) : 0.0;
  result.sigmaSpatial = options.sigmaSpatial > 0 ? options.sigmaSpatial * unit
                                                 : meanAdjacentCentroidDistance(mesh);
  // A mesh of isolated triangles has no adjacent centroids: any positive σ_c then does the same.
  if (!(result.sigmaSpatial > 0)) result.sigmaSpatial = averageEdgeLength(mesh);
  result.faceNormals = bilateralFilterFaceNormals(mesh, faceNormals(mesh), result.sigmaSpatial,
                                                  options, progress);
  result.vertexUpdate = updateVertices(mesh, result.faceNormals, options.vertexUpdate, progress);
  mesh.positions() = result.vertexUpdate.positions;
  return result;
}

}  // namespace geoshift
