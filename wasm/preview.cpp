// preview(handle, op, params, maxVertices, onProgress?): a quick look at what an op would do, for
// the web app's live preview while a slider moves. The session's mesh is analysed once into a
// wavelet multiresolution (docs/algorithms.md#wavelets) down to the first level with at most
// `maxVertices` vertices; that analysis is kept with the session and reused for as long as the
// positions and signals it was made from stay the same (a smaller maxVertices later analyses the
// kept coarse mesh further, a larger one uses fewer of the kept stages). Each call runs the op, with its own
// parameters, on the coarse mesh as on any mesh (spatial parameters are then in the coarse mesh's
// edge lengths), and brings its outputs back to every vertex by the wavelet prediction with the
// details left out (alpha = 0): odd vertices take the prediction-weighted mean of their even
// neighbours, labels (segments, classes) the label of the vertex they were collapsed into. The
// session itself never changes.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numeric>
#include <thread>

#include <emscripten/emscripten.h>

#include "adapters.hpp"
#include "convert.hpp"
#include "geoshift/error.hpp"
#include "geoshift/parallel.hpp"
#include "geoshift/wavelet.hpp"
#include "ops.hpp"

namespace geoshift::wasm {

using emscripten::val;

// The analyses made for a session, each of the previous one's coarse mesh (the first of the
// session's own mesh), so that a smaller level extends the chain instead of analysing the whole
// mesh again; a larger one uses a shorter prefix of it.
struct PreviewCache {
  std::uint64_t key = 0;
  std::vector<Multiresolution> stages;
  int used = -1;   // stages the coarse session below was made from
  Session coarse;  // the mesh and signals the op runs on
};

namespace {

// FNV-1a over the 64-bit words of the positions and of every signal (name, dim, values): the
// analysis is reused only for exactly the data it was made from. Word by word, not byte by byte,
// because it runs at every preview call (a 1M-vertex mesh: 4M words, a few milliseconds).
std::uint64_t fingerprint(const Session& s) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](std::uint64_t word) { h = (h ^ word) * 1099511628211ull; };
  auto mixDoubles = [&mix](const double* values, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) {
      std::uint64_t word;  // std::bit_cast is missing from Emscripten 3.1's libc++
      std::memcpy(&word, &values[i], sizeof word);
      mix(word);
    }
  };
  const std::vector<Vec3>& positions = s.build.mesh.positions();
  for (const Vec3& p : positions) mixDoubles(p.data(), 3);
  for (const Attribute& a : s.attributes.all()) {
    for (const char c : a.name) mix(static_cast<unsigned char>(c));
    mix(static_cast<std::uint64_t>(a.dim));
    mixDoubles(a.values.data(), a.values.size());
  }
  return h;
}

// The analysis with the fewest levels whose coarse mesh has at most maxVertices vertices (or the
// coarsest one the mesh allows). Each try estimates the levels still needed from the reduction
// per level seen so far.
Multiresolution analyzeDownTo(const Mesh& mesh, const AttributeSet& signals, int maxVertices, const Progress& progress) {
  const int n = mesh.vertexCount();
  double perLevel = 0.7;  // vertices kept per level; refined from each analysis
  int levels = std::max(1, static_cast<int>(std::ceil(std::log(static_cast<double>(maxVertices) / n) / std::log(perLevel))));
  for (;;) {
    WaveletOptions options;
    options.levels = levels;
    Multiresolution mr = analyze(mesh, signals, options, progress);
    const int count = mr.coarse.vertexCount();
    if (count <= maxVertices || mr.levelCount() < levels) return mr;
    perLevel = std::pow(static_cast<double>(count) / n, 1.0 / mr.levelCount());
    if (!(perLevel < 0.999)) return mr;
    levels += std::max(1, static_cast<int>(std::ceil(std::log(static_cast<double>(maxVertices) / count) / std::log(perLevel))));
  }
}

bool isLabel(const std::string& name) {
  return name == "_SEGMENT" || name.find("CLASS") != std::string::npos || name.find("class") != std::string::npos;
}

// Coarse per-vertex rows -> rows on every vertex of the analysed mesh (see the file comment). The
// odd vertices of one level depend on even ones only, so a level runs in parallel; the reads are
// scattered over the whole mesh, which makes this memory-bound (~0.15 s for 1M vertices, 1 thread).
std::vector<double> prolong(const Multiresolution& mr, const std::vector<double>& coarse, int dim, bool label,
                            int threads, const Progress& progress) {
  std::vector<double> fine(static_cast<std::size_t>(mr.fine.vertexCount()) * dim, 0.0);
  for (std::size_t c = 0; c < mr.coarseToFine.size(); ++c)
    for (int k = 0; k < dim; ++k) fine[mr.coarseToFine[c] * dim + k] = coarse[c * dim + k];
  ParallelOptions parallel;
  parallel.threads = threads;
  parallel.chunk = 4096;
  for (auto level = mr.levels.rbegin(); level != mr.levels.rend(); ++level) {
    const WaveletLevel& l = *level;
    parallelFor(static_cast<int>(l.odd.size()), parallel, progress, "preview: back to every vertex", 0, 1, [&](int i, int) {
      double* out = &fine[static_cast<std::size_t>(l.odd[i]) * dim];
      if (label) {
        const double* from = &fine[static_cast<std::size_t>(l.target[i]) * dim];
        std::copy(from, from + dim, out);
        return;
      }
      for (int e = l.offset[i]; e < l.offset[i + 1]; ++e) {
        const double* from = &fine[static_cast<std::size_t>(l.neighbor[e]) * dim];
        for (int k = 0; k < dim; ++k) out[k] += l.predict[e] * from[k];
      }
    });
  }
  return fine;
}

}  // namespace

val preview(int handle, const std::string& op, const val& params, int maxVertices, const val& onProgress) {
  return guarded([&] {
    Session& session = sessions().get(handle);
    if (maxVertices < 100) throw InputError("preview: maxVertices must be at least 100, not " + std::to_string(maxVertices));
    const OpEntry& entry = findOp(op);
    const ParamRequest request(paramSpecsOf(entry.name), paramValuesOf(entry.name, params));

    JsProgress js(onProgress);
    const Progress& progress = js.progress;

    const double start = emscripten_get_now();
    const std::uint64_t key = fingerprint(session);
    if (!session.preview || session.preview->key != key) {
      session.preview = std::make_shared<PreviewCache>();
      session.preview->key = key;
    }
    PreviewCache& cache = *session.preview;
    auto countAfter = [&](std::size_t stages) {
      return stages == 0 ? session.build.mesh.vertexCount() : cache.stages[stages - 1].coarse.vertexCount();
    };
    // The shortest prefix of the chain that is small enough; else the chain grows by one stage.
    std::size_t used = 0;
    while (used < cache.stages.size() && countAfter(used) > maxVertices) ++used;
    double analysisMs = 0;
    bool reused = true;
    if (countAfter(used) > maxVertices) {
      reused = false;
      const Mesh& from = used == 0 ? session.build.mesh : cache.stages.back().coarse;
      const AttributeSet& signals = used == 0 ? session.attributes : cache.stages.back().coarseAttributes;
      Multiresolution next = analyzeDownTo(from, signals, maxVertices, progress);
      if (next.levelCount() > 0) {
        cache.stages.push_back(std::move(next));
        ++used;
      }
      analysisMs = emscripten_get_now() - start;
    }
    if (static_cast<int>(used) != cache.used) {
      cache.coarse.build.mesh = used == 0 ? session.build.mesh : cache.stages[used - 1].coarse;
      cache.coarse.build.vertexOf.resize(cache.coarse.build.mesh.vertexCount());
      std::iota(cache.coarse.build.vertexOf.begin(), cache.coarse.build.vertexOf.end(), 0);
      cache.coarse.attributes = used == 0 ? session.attributes : cache.stages[used - 1].coarseAttributes;
      cache.used = static_cast<int>(used);
    }
    int levels = 0;
    for (std::size_t k = 0; k < used; ++k) levels += cache.stages[k].levelCount();

    const OpContext context{cache.coarse, request, progress};
    const double opStart = emscripten_get_now();
    OpOutput output = entry.run(context);
    const double opMs = emscripten_get_now() - opStart;
    progress.step(1, "preview: back to every vertex");

    const std::vector<int>& vertexOf = session.build.vertexOf;
    const int threads = context.threads(0);
    auto toCaller = [&](const std::vector<double>& values, int dim, bool label) {
      std::vector<double> fine = values;
      for (std::size_t k = used; k-- > 0;) fine = prolong(cache.stages[k], fine, dim, label, threads, progress);
      return floatsOut(toCallerLayout(fine, dim, vertexOf));
    };
    const double backStart = emscripten_get_now();
    val result = val::object();
    result.set("ok", true);
    if (output.positions) {
      std::vector<double> flat;
      flat.reserve(3 * output.positions->size());
      for (const Vec3& p : *output.positions) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
      result.set("positions", toCaller(flat, 3, false));
    }
    if (output.colors) result.set("colors", toCaller(*output.colors, 3, false));
    val scalars = val::object();
    for (const auto& [name, values] : output.scalars) scalars.set(name, toCaller(values, 1, isLabel(name)));
    result.set("scalars", scalars);
    val stats = output.stats;
    stats.set("op", op);
    stats.set("timeMs", emscripten_get_now() - start);
    stats.set("analysisMs", analysisMs);
    stats.set("coarseOpMs", opMs);
    stats.set("backToEveryVertexMs", emscripten_get_now() - backStart);
    stats.set("analysisReused", reused);
    stats.set("levels", levels);
    stats.set("stages", static_cast<int>(used));
    stats.set("previewVertices", cache.coarse.build.mesh.vertexCount());
    stats.set("vertices", session.callerVertexCount());
    stats.set("weldedVertices", session.build.mesh.vertexCount());
    stats.set("threadsAvailable", context.threads(0));
    result.set("stats", stats);
    return result;
  });
}

val previewWithoutProgress(int handle, const std::string& op, const val& params, int maxVertices) {
  return preview(handle, op, params, maxVertices, val::undefined());
}

}  // namespace geoshift::wasm
