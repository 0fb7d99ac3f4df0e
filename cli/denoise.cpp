// geoshift denoise: remove noise from vertex positions, keeping sharp features. Methods are listed
// in one table so that further denoisers plug in with a row.
#include <chrono>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

#include "commands.hpp"
#include "geoshift/bilateral_normal.hpp"
#include "geoshift/denoise.hpp"
#include "geoshift/error.hpp"
#include "geoshift/smoothing.hpp"

namespace geoshift::cli {
namespace {

struct DenoiseArgs {
  std::string in, out;
  std::string method = "meanshift";
  DenoiseOptions meanShift;
  std::string preset = "default";
  std::string rangeUpdate, faceRule;
  // Options both presets have, each with its own default: applied to the preset chosen.
  std::optional<double> hs, hr, radius;
  std::optional<int> passes;
  int threads = 0;
  // Options of one preset only: refused with the other.
  std::vector<std::pair<std::string, CLI::Option*>> paperOnly, defaultOnly;
  BilateralNormalOptions bilateral;
  std::string neighborhood = "vertex";
  std::string flipGuard = "input";
  int vertexIterations = -1;  // < 0: the method's own default
  bool fixedBoundary = false;
  TaubinOptions taubin;
};

struct Method {
  std::string name;
  std::string help;
  std::function<void(Mesh&, const DenoiseArgs&)> run;
};

VertexUpdateOptions vertexUpdateOf(const DenoiseArgs& a, VertexUpdateOptions o) {
  if (a.vertexIterations >= 0) o.iterations = a.vertexIterations;
  o.fixedBoundary = a.fixedBoundary;
  o.flipGuard = a.flipGuard == "input-or-target" ? FlipGuard::InputOrTarget : FlipGuard::Input;
  return o;
}

const std::vector<Method>& methods() {
  static const std::vector<Method> table = {
      {"meanshift", "Riemannian mean shift of the vertex normals (the paper's 4.1), then the vertex update",
       [](Mesh& mesh, const DenoiseArgs& a) {
         DenoiseOptions o = a.meanShift;
         o.threads = a.threads;
         if (a.preset == "paper") {
           o.preset = DenoisePreset::Paper;
           PaperDenoiseOptions& p = o.paper;
           MeanShiftOptions& ms = p.meanShift;
           if (a.hs) ms.spatialBandwidth = *a.hs;
           if (a.hr) ms.rangeBandwidth = *a.hr;
           if (a.radius) ms.radius = *a.radius;
           if (a.passes) p.passes = *a.passes;
           ms.parallel.threads = a.threads;
           if (a.rangeUpdate == "sampled") ms.rangeUpdate = RangeUpdate::Sampled;
           if (a.rangeUpdate == "joint") ms.rangeUpdate = RangeUpdate::Joint;
           if (a.faceRule == "mean") p.faceNormals = FaceNormalRule::Mean;
           p.vertexUpdate = vertexUpdateOf(a, p.vertexUpdate);
           const DenoiseResult r = denoise(mesh, o);
           std::cerr << "geoshift: mean shift (paper preset) " << p.passes << " passes, iterations mean " << r.meanIterations
                     << ", converged " << 100 * r.convergedFraction << "%, " << r.threads << " threads\n";
           return;
         }
         if (a.hs) o.neighborhood.spatialBandwidth = *a.hs;
         if (a.hr) o.rangeBandwidths = {*a.hr};
         if (a.radius) o.neighborhood.radius = *a.radius;
         if (a.passes) o.fixedPasses = *a.passes;
         if (a.vertexIterations >= 0) o.vertexIterations = a.vertexIterations;
         const DenoiseResult r = denoise(mesh, o);
         std::ostringstream line;
         line.precision(3);
         line << "geoshift: noise level " << r.noiseLevel << " AEL"
              << (r.noiseEstimated ? " (estimated from the mesh" : " (given")
              << (o.strength != 1 ? ", times strength " : "");
         if (o.strength != 1) line << o.strength;
         line << "); ";
         if (!(r.noiseLevel > 0)) {
           line << "nothing to remove";
         } else if (o.fixedPasses > 0) {
           line << "Taubin " << r.presmoothingSteps << " steps + " << r.passes << " mean shift passes (fixed)";
         } else {
           line << "Taubin " << r.presmoothingSteps << " steps + " << r.passes
                << " mean shift passes chosen by SURE (estimated error ";
           // The unbiased estimate can come out below zero when the result is much closer to the
           // truth than the noise; that is below what one probe resolves (docs/denoising.md).
           if (r.estimatedError > 0)
             line << r.estimatedError << " AEL";
           else
             line << "too small to resolve";
           line << ", " << r.passesRun << " passes computed)";
         }
         line << ", " << r.threads << " threads";
         std::cerr << line.str() << "\n";
       }},
      {"bilateral", "bilateral normal filtering (Zheng et al. 2011), then the vertex update",
       [](Mesh& mesh, const DenoiseArgs& a) {
         BilateralNormalOptions o = a.bilateral;
         o.neighborhood = a.neighborhood == "edge" ? FaceNeighborhood::Edge : FaceNeighborhood::Vertex;
         o.vertexUpdate = vertexUpdateOf(a, o.vertexUpdate);
         bilateralNormalDenoise(mesh, o);
       }},
      {"taubin", "Taubin lambda|mu smoothing (not feature-preserving; a baseline)",
       [](Mesh& mesh, const DenoiseArgs& a) { taubinSmooth(mesh, a.taubin); }},
  };
  return table;
}

const Method& methodNamed(const std::string& name) {
  for (const Method& m : methods())
    if (m.name == name) return m;
  throw InputError("denoise: unknown method '" + name + "'");
}

}  // namespace

Command addDenoise(CLI::App& app) {
  auto a = std::make_shared<DenoiseArgs>();
  CLI::App* sub = app.add_subcommand("denoise", "Remove noise from vertex positions, keeping sharp features");
  sub->add_option("IN", a->in, "input mesh (.gltf .glb .obj .off)")->required();
  sub->add_option("-o,--output", a->out, "output mesh; format from its extension")->required();
  std::vector<std::string> names;
  std::ostringstream help;
  help << "denoising method:";
  for (const Method& m : methods()) {
    names.push_back(m.name);
    help << "\n  " << m.name << ": " << m.help;
  }
  sub->add_option("--method", a->method, help.str())->check(CLI::IsMember(names))->capture_default_str();

  DenoiseOptions& d = a->meanShift;
  MeanShiftOptions& ms = d.paper.meanShift;
  sub->add_option("--preset", a->preset,
                  "meanshift: default (face-normal mean shift, amount of smoothing chosen by SURE from the estimated "
                  "noise) or paper (the paper's 4.1 pipeline)")
      ->check(CLI::IsMember({"default", "paper"}))->capture_default_str();
  sub->add_option("--passes", a->passes,
                  "meanshift: passes of normal filtering and vertex update (default preset: fixes the count instead of "
                  "SURE; paper: 3)")->check(CLI::PositiveNumber);
  sub->add_option("--hs", a->hs, "meanshift: spatial bandwidth h_s in average edge lengths (default 0.6; paper 3)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--hr", a->hr, "meanshift: range bandwidth h_r between unit normals; smaller keeps more edges (default 0.35; paper 0.45)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--radius", a->radius, "meanshift: neighbourhood radius in average edge lengths (default 1.75; paper 4)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--threads", a->threads, "meanshift: worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  sub->add_option("--levels", d.levels,
                  "meanshift: wavelet levels; denoise the coarse mesh and restore the details times --alpha")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  sub->add_option("--alpha", d.alpha, "meanshift: detail gain per level (finest first) or one for all")->delimiter(',');
  auto defaultOnly = [&](CLI::Option* o) { a->defaultOnly.emplace_back(o->get_name(), o); };
  defaultOnly(sub->add_option("--noise", d.noiseLevel,
                              "meanshift default: noise level in average edge lengths (0 = estimate it from the mesh)")
                  ->capture_default_str()->check(CLI::NonNegativeNumber));
  defaultOnly(sub->add_option("--strength", d.strength, "meanshift default: times the noise level; > 1 smooths more")
                  ->capture_default_str()->check(CLI::PositiveNumber));
  defaultOnly(sub->add_option("--presmoothing", d.presmoothing,
                              "meanshift default: candidate Taubin step counts before the passes, SURE picks one")
                  ->delimiter(',')->check(CLI::NonNegativeNumber));
  defaultOnly(sub->add_option("--max-passes", d.maxPasses, "meanshift default: most passes SURE considers")
                  ->capture_default_str()->check(CLI::PositiveNumber));
  defaultOnly(sub->add_option("--patience", d.patience, "meanshift default: stop after this many passes without a lower risk")
                  ->capture_default_str()->check(CLI::PositiveNumber));
  defaultOnly(sub->add_option("--seed", d.seed, "meanshift default: seed of the risk estimate's probe")->capture_default_str());
  auto paperOnly = [&](CLI::Option* o) { a->paperOnly.emplace_back(o->get_name(), o); };
  paperOnly(sub->add_option("--kmax", ms.maxIterations, "meanshift paper: most iterations per vertex and pass")->capture_default_str());
  paperOnly(sub->add_option("--eps", ms.epsilon, "meanshift paper: stop when a step is shorter than this, in AEL")->capture_default_str());
  paperOnly(sub->add_option("--range-update", a->rangeUpdate, "meanshift paper: sampled (the paper, default) or joint")
                ->check(CLI::IsMember({"sampled", "joint"})));
  paperOnly(sub->add_option("--face-normals", a->faceRule,
                            "meanshift paper: consensus (default: corners that disagree with the face drop out) or mean (the paper)")
                ->check(CLI::IsMember({"consensus", "mean"})));
  paperOnly(sub->add_flag("--exact-charts", ms.tuning.exactCharts, "meanshift paper: a fresh log map at every iteration (slower reference)"));
  paperOnly(sub->add_flag("--double-weights", [options = &ms](std::int64_t) { options->tuning.singlePrecisionKernel = false; },
                          "meanshift paper: kernel weights in double precision (slower reference)"));
  paperOnly(sub->add_option("--support-iterations", d.paper.support.iterations,
                            "meanshift paper: Taubin steps of the smoothed copy that carries the log and exp maps")
                ->capture_default_str()->check(CLI::NonNegativeNumber));
  sub->add_option("--normal-iterations", a->bilateral.normalIterations, "bilateral: normal filtering iterations")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  sub->add_option("--sigma-c", a->bilateral.sigmaSpatial,
                  "bilateral: spatial sigma in average edge lengths; 0 = mean distance of adjacent face centroids")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  sub->add_option("--sigma-s", a->bilateral.sigmaRange, "bilateral: range sigma on normal differences, > 0")
      ->capture_default_str()->check(CLI::PositiveNumber);
  sub->add_option("--neighbors", a->neighborhood, "bilateral: faces sharing a vertex or an edge")
      ->check(CLI::IsMember({"vertex", "edge"}))->capture_default_str();
  sub->add_option("--vertex-iterations", a->vertexIterations, "vertex update iterations (default: the method's, 10 for bilateral)")
      ->check(CLI::NonNegativeNumber);
  sub->add_flag("--fixed-boundary", a->fixedBoundary, "keep boundary vertices in place");
  sub->add_option("--flip-guard", a->flipGuard,
                  "input: no face ends up flipped relative to the input; input-or-target: faces the noise folded may unfold")
      ->check(CLI::IsMember({"input", "input-or-target"}))->capture_default_str();

  sub->add_option("--taubin-iterations", a->taubin.iterations, "taubin: lambda|mu step pairs")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  sub->add_option("--lambda", a->taubin.lambda, "taubin: shrinking step, > 0")->capture_default_str();
  sub->add_option("--mu", a->taubin.mu, "taubin: inflating step, < -lambda")->capture_default_str();

  return {sub, [a] {
            const Method& method = methodNamed(a->method);
            const auto& refused = a->preset == "paper" ? a->defaultOnly : a->paperOnly;
            for (const auto& [name, option] : refused)
              if (option->count() > 0)
                throw InputError("denoise: " + name + " does not apply to --preset " + a->preset);
            const auto start = std::chrono::steady_clock::now();
            Document doc = load(a->in);
            long vertices = 0;
            double filterSeconds = 0;
            for (MeshPart& part : doc.parts) {
              MeshBuild b = buildPart(doc, part);
              const auto t0 = std::chrono::steady_clock::now();
              method.run(b.mesh, *a);
              filterSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
              vertices += b.mesh.vertexCount();
              writeBack(part, b);
            }
            save(doc, a->out);
            const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::cerr << "geoshift: denoise " << method.name << ": " << vertices << " vertices in " << doc.parts.size()
                      << (doc.parts.size() == 1 ? " part" : " parts") << ", filter " << static_cast<long>(filterSeconds * 1000 + 0.5)
                      << " ms, total " << static_cast<long>(total * 1000 + 0.5) << " ms -> " << a->out << "\n";
          }};
}

}  // namespace geoshift::cli
