// Commands that change a mesh file: noise, smooth, curvature. Each part of the file is welded,
// processed, and written back into the file's own vertex layout. Their options are the parameters
// of the wasm ops of the same names, checked and read as the ops read them (requests.hpp).
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "geoshift/requests.hpp"

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
  CLI::App* sub = app.add_subcommand("noise", "Displace vertices by seeded random noise (for demos and benchmarks)");
  struct Args : InOut {
    std::optional<TableOptions> options;  // the op's parameters, checked as the wasm op checks them
  };
  auto a = std::make_shared<Args>();
  addInOut(sub, *a);
  a->options.emplace(sub, "noise");
  return {sub, [a] {
            const NoiseOptions noise = noiseOptions(a->options->request());
            movePositions(*a, [&](Mesh& mesh) { addNoise(mesh, noise); });
            std::cerr << "geoshift: noise amount " << noise.amount << " AEL, seed " << noise.seed << " -> " << a->out << "\n";
          }};
}

Command addSmooth(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("smooth", "Smooth vertex positions (Taubin lambda|mu)");
  struct Args : InOut {
    std::string method = "taubin";
    std::optional<TableOptions> options;  // the op's parameters, checked as the wasm op checks them
  };
  auto a = std::make_shared<Args>();
  addInOut(sub, *a);
  a->options.emplace(sub, "smooth");
  sub->add_option("--method", a->method, "smoothing method")->check(CLI::IsMember({"taubin"}))->capture_default_str();
  return {sub, [a] {
            const TaubinOptions taubin = smoothOptions(a->options->request());
            movePositions(*a, [&](Mesh& mesh) { taubinSmooth(mesh, taubin); });
          }};
}

Command addCurvature(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "curvature", "Discrete curvature as a color-mapped COLOR_0 and the scalar attribute _CURVATURE");
  struct Args : InOut {
    std::optional<TableOptions> options;  // the op's parameters, checked as the wasm op checks them
  };
  auto a = std::make_shared<Args>();
  addInOut(sub, *a);
  a->options.emplace(sub, "curvature");
  return {sub, [a] {
            const CurvatureKind kind = curvatureKind(a->options->request());
            Document doc = load(a->in);
            for (MeshPart& part : doc.parts) {
              const MeshBuild b = buildPart(doc, part);
              const std::vector<double> values = toCallerLayout(curvatures(b.mesh).get(kind), 1, b.vertexOf);
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
