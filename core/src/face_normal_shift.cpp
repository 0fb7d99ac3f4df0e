// faceNeighborhoods and shiftFaceNormals (face_normal_shift.hpp).
#include "geoshift/face_normal_shift.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "mean_shift_detail.hpp"

namespace geoshift {

FaceNeighborhoods faceNeighborhoods(const Mesh& mesh, const FaceNeighborhoodOptions& options, const Progress& progress) {
  if (!(options.radius > 0) || !std::isfinite(options.radius))
    throw InputError("face neighbourhoods: radius must be > 0 (got " + std::to_string(options.radius) + ")");
  if (!(options.spatialBandwidth > 0) || !std::isfinite(options.spatialBandwidth))
    throw InputError("face neighbourhoods: spatial bandwidth must be > 0 (got " +
                     std::to_string(options.spatialBandwidth) + ")");
  const int nf = mesh.faceCount(), nv = mesh.vertexCount();
  const double ael = averageEdgeLength(mesh);
  FaceNeighborhoods out;
  out.radius = options.radius * ael;
  out.spatialBandwidth = options.spatialBandwidth * ael;
  const double reach = out.radius + ael;  // a face whose centroid is within r has its corners within r + AEL
  const double k = 0.5 / (out.spatialBandwidth * out.spatialBandwidth);

  // Faces in blocks: each block's rows are built in parallel into per-face buffers, then packed in
  // face order into the block's array, so the result does not depend on the threads.
  constexpr int kBlock = FaceNeighborhoods::kBlock;
  const int threads = resolveThreads(options.parallel.threads);
  struct Scratch {
    std::optional<LogMap> logMap;
    std::vector<int> slot;       // vertex -> entry index in the current log map, or -1
    std::vector<int> faceStamp;  // face -> the face whose neighbourhood last looked at it
    std::vector<int> queue;
  };
  // The log maps' tables exist only for geodesic distances (about 250 bytes a vertex).
  std::optional<SurfaceGeometry> geometry;
  std::optional<LogMap> base;
  if (options.geodesic) {
    geometry.emplace(mesh);
    base.emplace(*geometry);
  }
  std::vector<Vec3>& centroids = out.centroids;
  if (!options.geodesic) {
    centroids.resize(nf);
    for (int f = 0; f < nf; ++f) {
      const Face& t = mesh.face(f);
      centroids[f] = (mesh.position(t[0]) + mesh.position(t[1]) + mesh.position(t[2])) / 3;
    }
  }
  std::vector<Scratch> scratch;
  scratch.reserve(threads);
  for (int t = 0; t < threads; ++t)
    scratch.push_back({options.geodesic ? std::optional<LogMap>(base->fork()) : std::nullopt,
                       std::vector<int>(options.geodesic ? nv : 0, -1), std::vector<int>(nf, -1), {}});
  std::vector<std::vector<int>> rowFace(kBlock);
  std::vector<std::vector<float>> rowWeight(kBlock);
  out.start.reserve(nf + 1);
  out.faceBlocks.reserve((nf + kBlock - 1) / kBlock);
  if (options.geodesic) out.weightBlocks.reserve((nf + kBlock - 1) / kBlock);
  for (int block = 0; block < nf; block += kBlock) {
    const int count = std::min(kBlock, nf - block);
    ParallelOptions par = options.parallel;
    parallelFor(count, par, progress, "face neighbourhoods", static_cast<double>(block) / nf,
                static_cast<double>(block + count) / nf, [&](int i, int worker) {
      const int f = block + i;
      Scratch& s = scratch[worker];
      std::vector<int>& faces = rowFace[i];
      std::vector<float>& weights = rowWeight[i];
      faces.clear();
      weights.clear();
      faces.push_back(f);
      weights.push_back(1.0f);
      if (options.geodesic) {
        const auto& entries = s.logMap->compute(SurfacePoint::inFace(mesh, f, Vec3::Constant(1.0 / 3.0)), reach);
        for (size_t e = 0; e < entries.size(); ++e) s.slot[entries[e].vertex] = static_cast<int>(e);
        s.faceStamp[f] = f;
        for (const LogMapEntry& entry : entries) {
          mesh.forEachOutgoing(entry.vertex, [&](int h) {
            const int g = Mesh::faceOf(h);
            if (s.faceStamp[g] == f) return;
            s.faceStamp[g] = f;
            Vec2 c = Vec2::Zero();
            for (int w : mesh.face(g)) {
              if (s.slot[w] < 0) return;
              c += entries[s.slot[w]].coords();
            }
            const double d2 = (c / 3).squaredNorm();
            if (d2 > out.radius * out.radius) return;
            faces.push_back(g);
            weights.push_back(static_cast<float>(mean_shift_detail::kernelExp(-d2 * k)));
          });
        }
        for (const LogMapEntry& entry : entries) s.slot[entry.vertex] = -1;
      } else {
        // Faces reached from f across edges while their centroids stay within r of f's (straight
        // distance on the support).
        s.faceStamp[f] = f;
        s.queue.assign(1, f);
        for (size_t q = 0; q < s.queue.size(); ++q) {
          const int a = s.queue[q];
          for (int k3 = 0; k3 < 3; ++k3) {
            const int t = mesh.twin(3 * a + k3);
            if (t < 0) continue;
            const int g = Mesh::faceOf(t);
            if (s.faceStamp[g] == f) continue;
            s.faceStamp[g] = f;
            const double d2 = (centroids[g] - centroids[f]).squaredNorm();
            if (d2 > out.radius * out.radius) continue;
            s.queue.push_back(g);
            faces.push_back(g);
            weights.push_back(0.0f);  // recomputed from the centroids when used
          }
        }
      }
      // A fixed order within the row (the log map's order is deterministic too, but sorting makes the
      // rows independent of it).
      std::vector<int> order(faces.size() - 1);
      for (size_t j = 0; j < order.size(); ++j) order[j] = static_cast<int>(j + 1);
      std::sort(order.begin(), order.end(), [&](int a, int b) { return faces[a] < faces[b]; });
      std::vector<int> sortedFaces{f};
      std::vector<float> sortedWeights{1.0f};
      for (int j : order) {
        sortedFaces.push_back(faces[j]);
        sortedWeights.push_back(weights[j]);
      }
      faces.swap(sortedFaces);
      weights.swap(sortedWeights);
    });
    size_t length = 0;
    for (int i = 0; i < count; ++i) length += rowFace[i].size();
    if (length > static_cast<size_t>(std::numeric_limits<int>::max()))
      throw InputError("face neighbourhoods: more than " + std::to_string(std::numeric_limits<int>::max()) +
                       " entries in a block of " + std::to_string(kBlock) + " faces; use a smaller radius");
    std::vector<int>& faces = out.faceBlocks.emplace_back();
    faces.reserve(length);
    for (int i = 0; i < count; ++i) {
      out.start.push_back(static_cast<int>(faces.size()));
      faces.insert(faces.end(), rowFace[i].begin(), rowFace[i].end());
    }
    if (options.geodesic) {
      std::vector<float>& weights = out.weightBlocks.emplace_back();
      weights.reserve(length);
      for (int i = 0; i < count; ++i) weights.insert(weights.end(), rowWeight[i].begin(), rowWeight[i].end());
    }
  }
  out.start.push_back(out.faceBlocks.empty() ? 0 : static_cast<int>(out.faceBlocks.back().size()));
  return out;
}

namespace {

// The spatial kernel of a straight distance, exactly as stored for geodesic rows: a float.
inline float straightWeight(const std::vector<Vec3>& centroids, int f, int g, double k) {
  return static_cast<float>(mean_shift_detail::kernelExp(-(centroids[g] - centroids[f]).squaredNorm() * k));
}

double spatialExponent(const FaceNeighborhoods& h) { return 0.5 / (h.spatialBandwidth * h.spatialBandwidth); }

}  // namespace

float FaceNeighborhoods::spatialWeight(int f, int j) const {
  const int at = span(f).first + j;
  if (!weightBlocks.empty()) return weightBlocks[f / kBlock][at];
  return straightWeight(centroids, f, faceBlocks[f / kBlock][at], spatialExponent(*this));
}

size_t FaceNeighborhoods::bytes() const {
  size_t n = start.capacity() * sizeof(int) + centroids.capacity() * sizeof(Vec3) +
             (faceBlocks.capacity() + weightBlocks.capacity()) * sizeof(std::vector<int>);
  for (const auto& b : faceBlocks) n += b.capacity() * sizeof(int);
  for (const auto& b : weightBlocks) n += b.capacity() * sizeof(float);
  return n;
}

namespace {

// e^x for the shift's kernel, four at a time, for x in [kMinExponent, 0]: the range reduction of
// mean_shift_detail::kernelExp with a degree-7 polynomial instead of 12 (relative error below 1e-8 on
// |r| <= ln2/2, far below what a weight needs), 2^n built in the exponent bits of the rounding shift
// (its low bits hold n). GCC/Clang vector extensions: two SSE2 halves natively, wasm SIMD in the
// browser; each lane runs the same operations in the same order as one scalar evaluation would, so
// the weights do not depend on the instruction set. No comparison inside (GCC compares vector lanes
// one by one on SSE2): the caller clamps the exponents.
using Double4 = double __attribute__((vector_size(32)));
using Bits4 = std::int64_t __attribute__((vector_size(32)));
constexpr int kLanes = 4;
// e^−708 ≈ 3e-308, still a normal number: a weight no sum notices beside its own face's weight of 1.
constexpr double kMinExponent = -708;

[[gnu::always_inline]] inline Double4 shiftExp(Double4 x) {
  constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
  constexpr double kInvLn2 = 1.44269504088896338700e+00, kShift = 6755399441055744.0;
  const Double4 shifted = x * kInvLn2 + kShift;
  const Double4 n = shifted - kShift;
  const Double4 r = (x - n * kLn2Hi) - n * kLn2Lo;
  const Double4 p =
      1.0 + r * (1.0 + r * (1.0 / 2 + r * (1.0 / 6 + r * (1.0 / 24 + r * (1.0 / 120 + r * (1.0 / 720 + r * (1.0 / 5040)))))));
  const Bits4 scale = (reinterpret_cast<Bits4>(shifted) + 1023) << 52;
  return p * reinterpret_cast<Double4>(scale);
}

// What a neighbour contributes, side by side for the inner loop's memory accesses.
struct FaceNormal {
  Vec3 n;
  double area;
};
// Left uninitialised: the records are first written by a parallel loop (a serial fill and its page
// faults were a share of a 2-thread denoise: docs/denoising.md#speed-and-memory).
using FaceNormals = std::unique_ptr<FaceNormal[]>;

// Face f's record is record(f), filled in parallel (large chunks: each record is cheap).
template <class Record>
FaceNormals faceRecords(int nf, const ParallelOptions& parallel, Record&& record) {
  FaceNormals faces(new FaceNormal[nf]);
  ParallelOptions par = parallel;
  par.chunk = 1024;
  parallelFor(nf, par, Progress{}, "", 0, 1, [&](int f, int) { faces[f] = record(f); });
  return faces;
}

// One shift step of faces [begin, end): each unit normal out[f] from the normals of f's row, with the
// range exponent k and the spatial exponent ks.
struct ShiftRows {
  const FaceNeighborhoods& hoods;
  const FaceNormal* faces;
  double k, ks;
  Vec3* out;
};

[[gnu::always_inline]] inline void shiftRows(const ShiftRows& a, int begin, int end) {
  const FaceNeighborhoods& hoods = a.hoods;
  const FaceNormal* faces = a.faces;
  const double k = a.k, ks = a.ks;
  for (int f = begin; f < end; ++f) {
    const Vec3& nf0 = faces[f].n;
    if (nf0.squaredNorm() == 0) {
      a.out[f] = nf0;
      continue;
    }
    Vec3 sum = Vec3::Zero();
    const auto [rowBegin, rowEnd] = hoods.span(f);
    const int* rows = hoods.faceBlocks[f / FaceNeighborhoods::kBlock].data();
    const float* stored = hoods.weightBlocks.empty() ? nullptr : hoods.weightBlocks[f / FaceNeighborhoods::kBlock].data();
    const Vec3 cf = stored ? Vec3::Zero() : hoods.centroids[f];
    // In batches: the exponents (gathered from the neighbours), their exponentials four at a time,
    // then the weighted sum in row order.
    constexpr int kBatch = 32;
    alignas(32) double e[kBatch];
    for (int j0 = rowBegin; j0 < rowEnd; j0 += kBatch) {
      const int m = std::min(kBatch, rowEnd - j0);
      for (int i = 0; i < m; ++i) {
        const int g = rows[j0 + i];
        const double range = (faces[g].n - nf0).squaredNorm() * k;
        e[i] = std::max(stored ? -range : -range - (hoods.centroids[g] - cf).squaredNorm() * ks, kMinExponent);
      }
      for (int i = m; i % kLanes != 0; ++i) e[i] = 0;
      for (int i = 0; i < m; i += kLanes) {
        Double4 x;
        std::memcpy(&x, e + i, sizeof x);
        x = shiftExp(x);
        std::memcpy(e + i, &x, sizeof x);
      }
      for (int i = 0; i < m; ++i) {
        const FaceNormal& fg = faces[rows[j0 + i]];
        const double w = stored ? stored[j0 + i] * fg.area * e[i] : fg.area * e[i];
        sum += w * fg.n;
      }
    }
    const double len = sum.norm();
    a.out[f] = len > 0 ? Vec3(sum * (1.0 / len)) : nf0;
  }
}

void shiftRowsPortable(const ShiftRows& a, int begin, int end) { shiftRows(a, begin, end); }

// The same operations in the same order with AVX2's registers where the processor has them (x86-64
// natively): the exponentials take half the instructions, and every normal is the same bits, since
// AVX2 brings no fused multiply-add for the compiler to contract into (docs/denoising.md#speed-and-memory).
using ShiftRowsFunction = void (*)(const ShiftRows&, int, int);
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__EMSCRIPTEN__)
[[gnu::target("avx2")]] void shiftRowsAvx2(const ShiftRows& a, int begin, int end) { shiftRows(a, begin, end); }
ShiftRowsFunction shiftRowsHere() {
  static const ShiftRowsFunction here = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") ? shiftRowsAvx2 : shiftRowsPortable;
  }();
  return here;
}
#else
ShiftRowsFunction shiftRowsHere() { return shiftRowsPortable; }
#endif

std::vector<Vec3> shift(const FaceNeighborhoods& hoods, const FaceNormal* faces, double rangeBandwidth,
                        const ParallelOptions& parallel, const Progress& progress) {
  if (!(rangeBandwidth > 0) || !std::isfinite(rangeBandwidth))
    throw InputError("face normal shift: range bandwidth must be > 0 (got " + std::to_string(rangeBandwidth) + ")");
  const int nf = hoods.faceCount();
  std::vector<Vec3> out(nf);
  const ShiftRows rows{hoods, faces, 0.5 / (rangeBandwidth * rangeBandwidth), spatialExponent(hoods), out.data()};
  ParallelOptions par = parallel;
  // Eight faces a call, 32 calls a hand-out.
  constexpr int kGroup = 8;
  par.chunk = 32;
  const ShiftRowsFunction kernel = parallel.portableKernels ? shiftRowsPortable : shiftRowsHere();
  parallelFor((nf + kGroup - 1) / kGroup, par, progress, "face normals", 0, 1,
              [&](int group, int) { kernel(rows, kGroup * group, std::min(nf, kGroup * group + kGroup)); });
  return out;
}

}  // namespace

std::vector<Vec3> shiftFaceNormals(const FaceNeighborhoods& hoods, const std::vector<double>& areas,
                                   const std::vector<Vec3>& normals, double rangeBandwidth,
                                   const ParallelOptions& parallel, const Progress& progress) {
  const int nf = hoods.faceCount();
  if (static_cast<int>(normals.size()) != nf || static_cast<int>(areas.size()) != nf)
    throw InputError("face normal shift: " + std::to_string(normals.size()) + " normals and " +
                     std::to_string(areas.size()) + " areas for " + std::to_string(nf) + " faces");
  const FaceNormals faces = faceRecords(nf, parallel, [&](int f) { return FaceNormal{normals[f], areas[f]}; });
  return shift(hoods, faces.get(), rangeBandwidth, parallel, progress);
}

std::vector<Vec3> shiftFaceNormals(const FaceNeighborhoods& hoods, const Mesh& mesh, double rangeBandwidth,
                                   const ParallelOptions& parallel, const Progress& progress) {
  const int nf = hoods.faceCount();
  if (mesh.faceCount() != nf)
    throw InputError("face normal shift: " + std::to_string(mesh.faceCount()) + " faces for neighbourhoods of " +
                     std::to_string(nf));
  const FaceNormals faces = faceRecords(nf, parallel, [&](int f) {
    // As faceNormals and faceAreas give them: the unit normal (zero for a degenerate face), half the
    // cross product's length.
    const Vec3 c = faceCross(mesh, f);
    const double len = c.norm();
    return FaceNormal{len > 0 ? Vec3(c / len) : Vec3::Zero(), 0.5 * len};
  });
  return shift(hoods, faces.get(), rangeBandwidth, parallel, progress);
}

}  // namespace geoshift
