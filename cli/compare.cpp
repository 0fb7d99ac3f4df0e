// geoshift compare RESULT REFERENCE: distances and normal errors between two meshes, in world space
// (node transforms applied), both directions.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "geoshift/metrics.hpp"

namespace geoshift::cli {
namespace {

nlohmann::json toJson(const DistanceStats& s) {
  return {{"samples", s.samples}, {"dropped", s.dropped}, {"min", s.min}, {"max", s.max}, {"mean", s.mean},
          {"rms", s.rms}, {"diagonal", s.diagonal}};
}

void printRow(const char* name, const DistanceStats& s) {
  const double d = s.diagonal > 0 ? s.diagonal : 1.0;
  std::printf("%-22s %12.6g %12.6g %12.6g %12.6g %10.6g %8d\n", name, s.rms, s.mean, s.max, s.rms / d,
              s.max / d, s.dropped);
}

}  // namespace

Command addCompare(CLI::App& app) {
  struct Args {
    std::string result, reference;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "compare", "Point-to-surface RMS and maximum (like MeshLab's Hausdorff filter) both ways, per-vertex RMS and "
                 "normal angle error when the meshes correspond");
  sub->add_option("RESULT", a->result, "the mesh to evaluate")->required();
  sub->add_option("REFERENCE", a->reference, "the ground truth")->required();
  sub->add_flag("--json", a->json, "print one JSON object instead of a table");
  return {sub, [a] {
            const Document res = load(a->result), ref = load(a->reference);
            const TriangleSoup rs = worldSoup(res), gs = worldSoup(ref);
            const MeshBuild rm = buildMesh(rs), gm = buildMesh(gs);
            const DistanceStats forward = pointToSurface(rs.positions, gm.mesh);
            const DistanceStats backward = pointToSurface(gs.positions, rm.mesh);
            // Per-vertex figures need the same vertices and faces in the same order (a clean/noisy pair).
            const bool corresponding = rs.positions.size() == gs.positions.size() && rs.faces == gs.faces;
            std::optional<double> vertexRms, normalError;
            if (corresponding) {
              vertexRms = perVertexRms(rs.positions, gs.positions);
              const MeshBuild ru = buildMesh(rs, MeshBuildOptions::withoutWelding()), gu = buildMesh(gs, MeshBuildOptions::withoutWelding());
              if (ru.mesh.faceCount() == gu.mesh.faceCount()) normalError = meanNormalAngleError(ru.mesh, gu.mesh);
            }
            const double hausdorff = std::max(forward.max, backward.max);
            if (a->json) {
              nlohmann::json j = {{"result", a->result},
                                  {"reference", a->reference},
                                  {"resultToReference", toJson(forward)},
                                  {"referenceToResult", toJson(backward)},
                                  {"hausdorff", hausdorff},
                                  {"perVertexRms", vertexRms ? nlohmann::json(*vertexRms) : nlohmann::json()},
                                  {"meanNormalAngleDeg", normalError ? nlohmann::json(*normalError) : nlohmann::json()}};
              std::printf("%s\n", j.dump(2).c_str());
              return;
            }
            std::printf("%-22s %12s %12s %12s %12s %10s %8s\n", "direction", "rms", "mean", "max", "rms/diag",
                        "max/diag", "dropped");
            printRow("result -> reference", forward);
            printRow("reference -> result", backward);
            std::printf("hausdorff (max both)   %.6g\n", hausdorff);
            if (vertexRms) std::printf("per-vertex rms         %.6g\n", *vertexRms);
            else std::printf("per-vertex rms         n/a (vertex counts or faces differ)\n");
            if (normalError) std::printf("mean normal error      %.4f deg\n", *normalError);
            else std::printf("mean normal error      n/a (faces differ)\n");
          }};
}

}  // namespace geoshift::cli
