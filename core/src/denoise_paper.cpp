// The paper preset (denoise.hpp; docs/denoising.md#the-paper-preset).
#include <chrono>
#include <cmath>

#include "denoise_detail.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"
#include "geoshift/geometry.hpp"

namespace geoshift::denoise_detail {

namespace {

// FaceNormalRule::Consensus (denoise.hpp).
std::vector<Vec3> consensusFaceNormals(const Mesh& mesh, const std::vector<Vec3>& vertexNormals, double bandwidth) {
  const std::vector<Vec3> own = faceNormals(mesh);
  std::vector<Vec3> out(mesh.faceCount());
  const double k = 0.5 / (bandwidth * bandwidth);
  for (int f = 0; f < mesh.faceCount(); ++f) {
    Vec3 sum = Vec3::Zero();
    for (int v : mesh.face(f)) sum += std::exp(-(vertexNormals[v] - own[f]).squaredNorm() * k) * vertexNormals[v];
    // All three far from the face's own normal (weights underflow) or cancelling: the plain mean.
    if (!(sum.norm() > 1e-12)) sum = vertexNormals[mesh.face(f)[0]] + vertexNormals[mesh.face(f)[1]] + vertexNormals[mesh.face(f)[2]];
    out[f] = sum.norm() > 1e-12 ? Vec3(sum.normalized()) : own[f];
  }
  return out;
}

}  // namespace

DenoiseResult denoisePaper(Mesh& mesh, const DenoiseOptions& all, const Progress& progress) {
  const PaperDenoiseOptions& options = all.paper;
  const auto start = std::chrono::steady_clock::now();
  if (options.passes < 1) throw InputError("denoise (paper preset): passes must be at least 1 (got " + std::to_string(options.passes) + ")");
  if (mesh.faceCount() == 0) throw InputError("denoise: the mesh has no faces");
  const std::vector<Vec3> input = mesh.positions();

  DenoiseResult result;
  try {
    Mesh support = mesh;
    TaubinOptions supportSmoothing = options.support;
    supportSmoothing.parallel = options.meanShift.parallel;
    taubinSmooth(support, supportSmoothing, progress.slice(0, 0.02));
    const SurfaceGeometry supportGeometry(support);
    MeanShiftOptions ms = options.meanShift;
    ms.channels = {{"NORMAL", ms.rangeBandwidth, ms.rangeKernel}};
    ms.segments = false;
    ms.passes = 1;
    const int n = mesh.vertexCount();
    double iterations = 0;
    VertexUpdateOptions update = options.vertexUpdate;
    if (update.referenceNormals.empty()) update.referenceNormals = referenceNormalsOf(mesh);  // the input's, every pass
    for (int pass = 0; pass < options.passes; ++pass) {
      const double from = 0.02 + 0.98 * pass / options.passes, to = 0.02 + 0.98 * (pass + 1) / options.passes;
      std::vector<double> flat;
      flat.reserve(3 * static_cast<size_t>(n));
      for (const Vec3& v : vertexNormals(mesh)) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
      AttributeSet signal(n);
      // Isolated or degenerate vertices have no normal; give them any unit vector (they are not
      // in any face, so no face normal reads it).
      for (int v = 0; v < n; ++v)
        if (!(std::abs(flat[3 * v]) + std::abs(flat[3 * v + 1]) + std::abs(flat[3 * v + 2]) > 0)) flat[3 * v + 2] = 1;
      signal.set("NORMAL", 3, AttributeKind::UnitVector, std::move(flat));
      const MeanShiftResult r = meanShift(supportGeometry, signal, ms, progress.slice(from, from + 0.8 * (to - from)));
      iterations += r.meanIterations;
      result.convergedFraction = r.convergedFraction;
      result.threads = r.threads;
      const Attribute& filtered = r.signal.get("NORMAL");
      std::vector<Vec3> normals(n);
      for (int v = 0; v < n; ++v) normals[v] = Vec3(filtered.row(v)[0], filtered.row(v)[1], filtered.row(v)[2]);
      progress.step(from + 0.8 * (to - from), "vertex update");
      std::vector<Vec3> targets = options.faceNormals == FaceNormalRule::Mean
                                            ? faceNormalsFromVertexNormals(mesh, normals)
                                            : consensusFaceNormals(mesh, normals,
                                                                   options.consensusBandwidth > 0 ? options.consensusBandwidth
                                                                                                  : ms.rangeBandwidth);
      VertexUpdateResult u = updateVertices(mesh, std::move(targets), update,
                                            progress.slice(from + 0.8 * (to - from), to));
      result.limitedSteps += u.limitedSteps;
      mesh.positions() = std::move(u.positions);
    }
    result.meanIterations = iterations / options.passes;
  } catch (...) {
    mesh.positions() = input;  // cancelled or failed half-way: the caller's mesh as it was
    throw;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.filteredVertices = mesh.vertexCount();
  return result;
}

}  // namespace geoshift::denoise_detail
