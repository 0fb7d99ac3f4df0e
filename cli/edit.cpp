// Commands that change a mesh file: noise, smooth, curvature. Each part of the file is welded,
// processed, and written back into the file's own vertex layout.
#include <iostream>
#include <map>
#include <memory>

#include "commands.hpp"
#include "geoshift/curvature.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/smoothing.hpp"

namespace geoshift::cli {
namespace {

struct InOut {
  std::string in, out;
};

void addInOut(CLI::App* sub, InOut& io) {
  sub->add_option("IN", io.in, "input mesh (.gltf .glb .obj .off .ply .stl)")->required();
  sub->add_option("-o,--output", io.out, "output mesh; format from its extension")->required();
}

// Reads IN, moves the vertices of every part's welded mesh with `move`, writes OUT.
template <class Move>
void movePositions(const InOut& io, Move move) {
  Document doc = load(io.in);
  for (MeshPart& part : doc.parts) {
    MeshBuild b = buildPart(doc, part);
    move(b.mesh);
    writeBack(part, b);
  }
  save(doc, io.out);
}

}  // namespace

Command addNoise(CLI::App& app) {
  struct Args : InOut {
    NoiseOptions noise;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("noise", "Displace vertices by seeded random noise (for demos and benchmarks)");
  addInOut(sub, *a);
  sub->add_option("--amount", a->noise.amount, "magnitude in multiples of the average edge length")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  const std::map<std::string, NoiseDistribution> dists = {
      {"fixed", NoiseDistribution::Fixed}, {"uniform", NoiseDistribution::Uniform}, {"gaussian", NoiseDistribution::Gaussian},
      {"impulsive", NoiseDistribution::Impulsive}};
  sub->add_option("--dist", a->noise.distribution,
                  "fixed: |d| = amount*AEL; uniform: |d| in [0, amount*AEL]; gaussian: sigma = amount*AEL; "
                  "impulsive: a tenth of the vertices, sigma = amount*AEL")
      ->transform(CLI::CheckedTransformer(dists, CLI::ignore_case));
  const std::map<std::string, NoiseDirection> dirs = {{"random", NoiseDirection::Random}, {"normal", NoiseDirection::Normal}};
  sub->add_option("--direction", a->noise.direction, "random: uniformly random direction; normal: along the vertex normal")
      ->transform(CLI::CheckedTransformer(dirs, CLI::ignore_case));
  sub->add_option("--seed", a->noise.seed, "random seed (same seed, same noise, natively and in wasm)")->capture_default_str();
  return {sub, [a] {
            movePositions(*a, [&](Mesh& mesh) { addNoise(mesh, a->noise); });
            std::cerr << "geoshift: noise amount " << a->noise.amount << " AEL, seed " << a->noise.seed
                      << " -> " << a->out << "\n";
          }};
}

Command addSmooth(CLI::App& app) {
  struct Args : InOut {
    std::string method = "taubin";
    TaubinOptions taubin;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand("smooth", "Smooth vertex positions (Taubin lambda|mu)");
  addInOut(sub, *a);
  sub->add_option("--method", a->method, "smoothing method")->check(CLI::IsMember({"taubin"}))->capture_default_str();
  sub->add_option("--iterations", a->taubin.iterations, "lambda|mu step pairs")->capture_default_str()->check(CLI::NonNegativeNumber);
  sub->add_option("--lambda", a->taubin.lambda, "shrinking step, > 0")->capture_default_str();
  sub->add_option("--mu", a->taubin.mu, "inflating step, < -lambda")->capture_default_str();
  const std::map<std::string, LaplacianWeights> weights = {
      {"uniform", LaplacianWeights::Uniform}, {"fujiwara", LaplacianWeights::Fujiwara}, {"cotangent", LaplacianWeights::Cotangent}};
  sub->add_option("--weights", a->taubin.weights, "Laplacian weights: uniform, fujiwara (1/length), cotangent")
      ->transform(CLI::CheckedTransformer(weights, CLI::ignore_case));
  return {sub, [a] { movePositions(*a, [&](Mesh& mesh) { taubinSmooth(mesh, a->taubin); }); }};
}

Command addCurvature(CLI::App& app) {
  struct Args : InOut {
    CurvatureKind kind = CurvatureKind::Absolute;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "curvature", "Discrete curvature as a color-mapped COLOR_0 and the scalar attribute _CURVATURE");
  addInOut(sub, *a);
  const std::map<std::string, CurvatureKind> kinds = {{"abs", CurvatureKind::Absolute}, {"mean", CurvatureKind::Mean},
                                                      {"gauss", CurvatureKind::Gaussian}, {"rms", CurvatureKind::Rms}};
  sub->add_option("--kind", a->kind, "abs = |k1|+|k2| (MeshLab), mean H, gauss K, rms")
      ->transform(CLI::CheckedTransformer(kinds, CLI::ignore_case));
  return {sub, [a] {
            Document doc = load(a->in);
            for (MeshPart& part : doc.parts) {
              const MeshBuild b = buildPart(doc, part);
              const std::vector<double> values = toCallerLayout(curvatures(b.mesh).get(a->kind), 1, b.vertexOf);
              const std::vector<double> rgb = colorMap(values);
              part.colors.resize(values.size());
              for (size_t i = 0; i < values.size(); ++i) part.colors[i] = {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 1.0};
              std::erase_if(part.extras, [](const ExtraAttribute& e) { return e.name == "_CURVATURE"; });
              part.extras.push_back({"_CURVATURE", 1, values});
            }
            save(doc, a->out);
          }};
}

}  // namespace geoshift::cli
