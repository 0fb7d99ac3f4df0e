#include "geoshift/vertex_update.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/parallel.hpp"

namespace geoshift {
namespace {

constexpr int kMaxHalvings = 8;

std::string vecText(const Vec3& v) {
  return "(" + std::to_string(v.x()) + ", " + std::to_string(v.y()) + ", " + std::to_string(v.z()) + ")";
}

[[gnu::always_inline]] inline Vec3 crossOf(const std::vector<Vec3>& x, const Face& t) {
  return (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]);
}

// Per vertex, the faces it gathers over (VertexUpdatePlan): those with a target, in the mesh's
// counter-clockwise order from its first half-edge (a fixed order, so the sums, and so the
// results, do not depend on the threads), none for a vertex that does not move. Read as a list,
// the faces' planes are independent loads; walking the half-edges every iteration made each wait
// on the one before (docs/denoising.md#speed-and-memory). `first` (nv + 1 entries) gets the lists'
// starts; `allocate(n)` returns the array of n entries they are written to.
template <class HasTarget, class Allocate>
auto listGatherFaces(const Mesh& mesh, bool fixedBoundary, const ParallelOptions& par, HasTarget&& hasTarget,
                     int* first, Allocate&& allocate) {
  const int nv = mesh.vertexCount();
  const Progress quiet;
  parallelFor(nv, par, quiet, "", 0, 1, [&](int v, int) {
    int count = 0;
    if (!mesh.isIsolated(v) && !(fixedBoundary && mesh.isBoundaryVertex(v)))
      mesh.forEachOutgoing(v, [&](int h) { count += hasTarget(Mesh::faceOf(h)); });
    first[v + 1] = count;
  });
  first[0] = 0;
  for (int v = 0; v < nv; ++v) first[v + 1] += first[v];
  auto faces = allocate(first[nv]);
  int* gather = nullptr;
  if constexpr (requires { faces.data(); })
    gather = faces.data();
  else
    gather = faces.get();
  parallelFor(nv, par, quiet, "", 0, 1, [&](int v, int) {
    int at = first[v];
    if (at == first[v + 1]) return;
    mesh.forEachOutgoing(v, [&](int h) {
      const int f = Mesh::faceOf(h);
      if (hasTarget(f)) gather[at++] = f;
    });
  });
  return faces;
}

}  // namespace

VertexUpdateResult updateVertices(const Mesh& mesh, std::vector<Vec3> targetNormals,
                                  const VertexUpdateOptions& options, const Progress& progress) {
  const int nv = mesh.vertexCount(), nf = mesh.faceCount();
  if (static_cast<int>(targetNormals.size()) != nf) {
    throw InputError("vertex update: " + std::to_string(targetNormals.size()) +
                     " target normals for " + std::to_string(nf) + " faces");
  }
  if (options.iterations < 0) {
    throw InputError("vertex update: iterations must be >= 0 (got " +
                     std::to_string(options.iterations) + ")");
  }
  ParallelOptions par = options.parallel;
  par.chunk = 1024;
  const Progress quiet;  // the iterations report; the parallel loops inside them do not

  // Per face, what its corners read: its unit target normal with the offset n·c of its target
  // plane (c the centroid) and its weight, side by side for the gather's memory accesses. The
  // normals do not change between iterations. The per-call arrays are left uninitialised and first
  // written by the parallel loops: filled by the calling thread alone (with the page faults of their
  // fresh memory), they were about a sixth of a 2-thread denoise's work (docs/denoising.md#speed-and-memory).
  // A face without a target pulls on nothing: it is left out of its corners' lists below, and
  // every other face weighs 1, or its area when areaWeighted (then kept beside the planes).
  struct Plane {
    Vec3 n;
    double offset;
  };
  const std::unique_ptr<Plane[]> plane(new Plane[nf]);
  const std::unique_ptr<double[]> weight(options.areaWeighted ? new double[nf] : nullptr);
  // A face's weight and target plane offset at positions p, so that a corner x_v is pulled by
  // (n·c − n·x_v) n; `cross` is its cross product there.
  auto setPlane = [&](int f, const std::vector<Vec3>& p, const Vec3& cross) {
    const Face& t = mesh.face(f);
    if (weight) weight[f] = 0.5 * cross.norm();
    plane[f].offset = plane[f].n.dot(p[t[0]] + p[t[1]] + p[t[2]]) * (1.0 / 3);  // no division: it stalled the loop
  };
  // Per face, its cross product at the current positions in single precision (the guard reads only
  // the sign of a dot product with it): the cross product the last check computed at the candidate
  // positions that became the current ones, kept instead of computed again at every check.
  const std::unique_ptr<Eigen::Vector3f[]> currentCross(new Eigen::Vector3f[nf]);
  // Per face in one loop: its unit target, the first iteration's plane (later ones are set by the
  // guard's checks) and its cross product.
  std::atomic<bool> nonFinite{false}, targetless{false};
  parallelFor(nf, par, quiet, "", 0, 1, [&](int f, int) {
    const Vec3& n = targetNormals[f];
    if (!n.allFinite()) nonFinite.store(true, std::memory_order_relaxed);
    const double len = n.norm();
    if (!(len > 0)) targetless.store(true, std::memory_order_relaxed);
    plane[f].n = len > 0 ? Vec3(n / len) : Vec3::Zero();
    const Vec3 c = crossOf(mesh.positions(), mesh.face(f));
    setPlane(f, mesh.positions(), c);
    currentCross[f] = c.cast<float>();
  });
  if (nonFinite)  // the first such face, whatever the threads
    for (int f = 0; f < nf; ++f)
      if (!targetNormals[f].allFinite())
        throw InputError("vertex update: target normal of face " + std::to_string(f) + " is not finite " + vecText(targetNormals[f]));
  std::vector<Vec3>().swap(targetNormals);

  // The reference each face must stay on the positive side of (zero for degenerate input faces).
  if (!options.referenceNormals.empty() && options.referenceNormals.size() != static_cast<size_t>(mesh.faceCount()))
    throw InputError("vertex update: " + std::to_string(options.referenceNormals.size()) + " reference normals for " +
                     std::to_string(mesh.faceCount()) + " faces");
  // The caller's reference is read in place (a denoiser's passes share one); only the default is made.
  std::vector<Eigen::Vector3f> ownReference;
  if (options.referenceNormals.empty()) ownReference = referenceNormalsOf(mesh);
  const std::vector<Eigen::Vector3f>& inputNormal = options.referenceNormals.empty() ? ownReference : options.referenceNormals;

  VertexUpdateResult result;
  // Vec3's default constructor writes nothing: these are first written by the loops below.
  std::vector<Vec3> x(nv), candidate(nv), step(nv);
  const VertexUpdatePlan* plan = options.plan;
  if (plan && (plan->vertexCount != nv || plan->faceCount != nf || plan->fixedBoundary != options.fixedBoundary ||
               static_cast<int>(plan->firstFace.size()) != nv + 1))
    throw InputError("vertex update: the plan was made for " + std::to_string(plan->vertexCount) + " vertices and " +
                     std::to_string(plan->faceCount) + " faces" + (plan->fixedBoundary ? " with" : " without") +
                     " fixed boundary, not for this mesh (" + std::to_string(nv) + " vertices, " + std::to_string(nf) +
                     " faces)" + (options.fixedBoundary ? " with it" : " without it"));
  if (targetless) plan = nullptr;  // the plan lists every face: the lists are built for this call
  auto hasTarget = [&](int f) { return plane[f].n.squaredNorm() != 0; };
  parallelFor(nv, par, quiet, "", 0, 1, [&](int v, int) { x[v] = mesh.position(v); });
  std::unique_ptr<int[]> ownFirst, ownGather;
  if (!plan) {
    ownFirst.reset(new int[nv + 1]);
    ownGather = listGatherFaces(mesh, options.fixedBoundary, par, hasTarget, ownFirst.get(),
                                [](int n) { return std::unique_ptr<int[]>(new int[n]); });
  }
  const int* firstFace = plan ? plan->firstFace.data() : ownFirst.get();
  const int* gatherFace = plan ? plan->gatherFace.data() : ownGather.get();
  // Per face: bad at the first check of an iteration, then queued in the round under way (so that a
  // face is queued once a round). bool, not char: a store of a char may alias anything, and in the
  // check's loop it made every array's address be read again for each face.
  const std::unique_ptr<bool[]> bad(new bool[nf]);
  // Per vertex, how many times its step has been halved in this iteration; kFrozen once it no longer
  // moves. Its scale 2^-halvings is exact, as a halved double was.
  constexpr signed char kFrozen = -1;
  const std::unique_ptr<signed char[]> halvings(new signed char[nv]);
  auto scaleOf = [&](int v) { return halvings[v] == kFrozen ? 0.0 : std::ldexp(1.0, -halvings[v]); };
  std::vector<char> halvedThisRound(nv);
  std::vector<int> badFaces, touched;
  // Whether face f passes the guard at the candidate positions, against its cross product at the
  // current ones `current` (compared in single precision: only the sign of a dot product with it is
  // read). The candidate's plane and cross product are kept on the way: if the candidate stays, the
  // next iteration starts from them. Each face is checked last at its corners' final candidates
  // (a halved corner's faces are all checked again), so currentCross holds the cross product at the
  // next iteration's positions, the same bits as computing it there.
  auto faceOkAgainst = [&](int f, const Eigen::Vector3f& current) {
    const Face& t = mesh.face(f);
    const Vec3 c = crossOf(candidate, t);
    setPlane(f, candidate, c);
    currentCross[f] = c.cast<float>();
    const bool keepsInputSide = inputNormal[f].squaredNorm() == 0.0f || c.dot(inputNormal[f].cast<double>()) > 0.0 ||
                                (options.flipGuard == FlipGuard::InputOrTarget && c.dot(plane[f].n) > 0.0);
    const bool keepsCurrentSide = (current.array() == 0.0f).all() || c.dot(current.cast<double>()) > 0.0;
    return keepsInputSide && keepsCurrentSide;
  };
  // A face checked again within an iteration: what is kept is already the candidate's cross product,
  // so the current one is computed from the positions.
  auto faceOkAgain = [&](int f) { return faceOkAgainst(f, crossOf(x, mesh.face(f)).cast<float>()); };

  for (int it = 0; it < options.iterations; ++it) {
    progress.step(static_cast<double>(it) / options.iterations, "vertex update");
    parallelFor(nv, par, quiet, "", 0, 1, [&](int v, int) {
      Vec3 sum = Vec3::Zero();
      double wsum = 0;
      const Vec3 xv = x[v];
      const int begin = firstFace[v], end = firstFace[v + 1];
      if (weight) {
        for (int i = begin; i < end; ++i) {
          const int f = gatherFace[i];
          const Plane& p = plane[f];
          sum += (weight[f] * (p.offset - p.n.dot(xv))) * p.n;
          wsum += weight[f];
        }
      } else {
        for (int i = begin; i < end; ++i) {
          const Plane& p = plane[gatherFace[i]];
          sum += (p.offset - p.n.dot(xv)) * p.n;
        }
        wsum = end - begin;
      }
      step[v] = wsum > 0 ? Vec3(sum * (1.0 / wsum)) : Vec3::Zero();
      candidate[v] = xv + step[v];
    });
    // Apart from the gather: a store of a char may alias anything, and in the loop it made every
    // array's address be read again for each vertex.
    std::memset(halvings.get(), 0, nv);

    parallelFor(nf, par, quiet, "", 0, 1, [&](int f, int) {
      const Eigen::Vector3f current = currentCross[f];  // a copy: the check overwrites what is kept
      bad[f] = !faceOkAgainst(f, current);
    });
    badFaces.clear();
    // Bad faces are few: memchr skips the runs of good ones many bytes at a time.
    const char* flags = reinterpret_cast<const char*>(bad.get());  // a bool's bytes are 0 or 1
    for (const char* at = flags; (at = static_cast<const char*>(std::memchr(at, 1, flags + nf - at))); ++at)
      badFaces.push_back(static_cast<int>(at - flags));
    while (!badFaces.empty()) {
      // Shorten the steps of every vertex of a bad face once per round, then re-check only the
      // faces those vertices touch.
      touched.clear();
      for (int f : badFaces) {
        bad[f] = false;
        for (int v : mesh.face(f)) {
          if (halvedThisRound[v] || halvings[v] == kFrozen) continue;
          halvedThisRound[v] = 1;
          touched.push_back(v);
          if (halvings[v] == 0) ++result.limitedSteps;
          if (++halvings[v] > kMaxHalvings) {
            halvings[v] = kFrozen;
            ++result.frozenSteps;
          }
          candidate[v] = x[v] + scaleOf(v) * step[v];
        }
      }
      badFaces.clear();
      for (int v : touched) {
        halvedThisRound[v] = 0;
        mesh.forEachOutgoing(v, [&](int h) {
          const int f = Mesh::faceOf(h);
          if (!bad[f] && !faceOkAgain(f)) {
            bad[f] = true;
            badFaces.push_back(f);
          }
        });
      }
      // A bad face whose vertices are all frozen sits at its current, valid position; it cannot
      // stay bad, so the loop ends after at most kMaxHalvings + 1 rounds per vertex.
    }
    x.swap(candidate);  // every candidate entry is written again by the next gather
    result.iterations = it + 1;
  }
  progress.step(1.0, "vertex update");
  // Per worker, then over the workers: a maximum does not depend on the order.
  std::vector<double> farthest(resolveThreads(par.threads), 0.0);
  parallelFor(nv, par, quiet, "", 0, 1, [&](int v, int worker) {
    farthest[worker] = std::max(farthest[worker], (x[v] - mesh.position(v)).squaredNorm());
  });
  for (double d : farthest) result.maxDisplacement = std::max(result.maxDisplacement, std::sqrt(d));
  result.positions = std::move(x);
  return result;
}

VertexUpdatePlan planVertexUpdate(const Mesh& mesh, const VertexUpdateOptions& options) {
  VertexUpdatePlan plan;
  plan.vertexCount = mesh.vertexCount();
  plan.faceCount = mesh.faceCount();
  plan.fixedBoundary = options.fixedBoundary;
  plan.firstFace.resize(plan.vertexCount + 1);
  ParallelOptions par = options.parallel;
  par.chunk = 1024;
  plan.gatherFace = listGatherFaces(mesh, options.fixedBoundary, par, [](int) { return true; }, plan.firstFace.data(),
                                    [](int n) { return std::vector<int>(n); });
  return plan;
}

std::vector<Eigen::Vector3f> referenceNormalsOf(const Mesh& mesh) {
  const std::vector<Vec3> normals = faceNormals(mesh);
  std::vector<Eigen::Vector3f> out(normals.size());
  for (size_t f = 0; f < normals.size(); ++f) out[f] = normals[f].cast<float>();
  return out;
}

std::vector<Vec3> faceNormalsFromVertexNormals(const Mesh& mesh,
                                               const std::vector<Vec3>& vertexNormals) {
  if (static_cast<int>(vertexNormals.size()) != mesh.vertexCount()) {
    throw InputError("face normals from vertex normals: " + std::to_string(vertexNormals.size()) +
                     " vertex normals for " + std::to_string(mesh.vertexCount()) + " vertices");
  }
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    if (!vertexNormals[v].allFinite())
      throw InputError("face normals from vertex normals: normal of vertex " + std::to_string(v) + " is not finite " + vecText(vertexNormals[v]));
  }
  std::vector<Vec3> out(mesh.faceCount());
  for (int f = 0; f < mesh.faceCount(); ++f) {
    const Face& t = mesh.face(f);
    // Unit inputs are assumed by the paper; normalising each first keeps a long one from dominating.
    Vec3 sum = Vec3::Zero();
    for (int v : t) {
      const double len = vertexNormals[v].norm();
      if (len > 0) sum += vertexNormals[v] / len;
    }
    const double len = sum.norm();
    if (len > 1e-12) {
      out[f] = sum / len;
    } else {
      const Vec3 c = faceCross(mesh, f);
      const double cl = c.norm();
      out[f] = cl > 0 ? Vec3(c / cl) : Vec3::Zero();
    }
  }
  return out;
}

}  // namespace geoshift
