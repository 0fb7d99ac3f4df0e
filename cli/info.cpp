// geoshift info FILE: what a mesh file holds and what the core makes of it.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "geoshift/denoise.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/wavelet.hpp"

namespace geoshift::cli {
namespace {

const char* formatName(FileFormat f) {
  switch (f) {
    case FileFormat::Gltf: return "glTF 2.0 (.gltf)";
    case FileFormat::Glb: return "glTF 2.0 binary (.glb)";
    case FileFormat::Obj: return "Wavefront OBJ";
    case FileFormat::Off: return "OFF";
    case FileFormat::Ply: return "PLY";
    case FileFormat::Stl: return "STL";
  }
  return "?";
}

void printPart(const Document& doc, const MeshPart& part, int levels) {
  const MeshBuild b = buildPart(doc, part);
  const Mesh& m = b.mesh;
  const BuildReport& r = b.report;
  const auto box = boundingBox(part.positions);
  std::printf("%s\n", part.label.c_str());
  std::printf("  vertices            %zu (%d after welding %d coincident)\n", part.positions.size(),
              m.vertexCount() - r.splitVertexCopies, r.weldedVertices);
  std::printf("  faces               %zu (%d kept)\n", part.faces.size(), m.faceCount());
  std::printf("  average edge length %.6g\n", averageEdgeLength(m));
  std::printf("  bounding box        (%.6g, %.6g, %.6g) - (%.6g, %.6g, %.6g), diagonal %.6g\n",
              box.min().x(), box.min().y(), box.min().z(), box.max().x(), box.max().y(), box.max().z(),
              box.diagonal().norm());
  const auto loops = m.boundaryLoops();
  std::printf("  boundary loops      %zu", loops.size());
  if (!loops.empty()) {
    std::printf(" (lengths");
    for (size_t i = 0; i < loops.size() && i < 8; ++i) std::printf(" %zu", loops[i].size());
    if (loops.size() > 8) std::printf(" ...");
    std::printf(")");
  }
  std::printf("\n");
  // docs/denoising.md#small-pieces: the denoiser leaves pieces of fewer vertices than this as they are.
  const int smallPiece = DenoiseOptions{}.minPieceVertices;
  const Pieces parts = pieces(m);
  const auto small = std::ranges::count_if(parts.vertexCount, [&](int n) { return n < smallPiece; });
  std::printf("  pieces              %zu", parts.vertexCount.size());
  if (small > 0) std::printf(" (%td of fewer than %d vertices)", small, smallPiece);
  std::printf("\n");
  std::printf("  degenerate faces    %d (repeated index %d, zero area %d)\n",
              r.repeatedIndexFaces + r.zeroAreaFaces, r.repeatedIndexFaces, r.zeroAreaFaces);
  std::printf("  re-oriented faces   %d\n", r.reorientedFaces);
  std::printf("  non-manifold        %d edges, %d vertices (split into %d extra)\n", r.nonManifoldEdges,
              r.nonManifoldVertices, r.splitVertexCopies);
  std::printf("  isolated vertices   %d\n", r.isolatedVertices);
  std::string attrs = "POSITION";
  if (!part.normals.empty()) attrs += ", NORMAL";
  if (!part.colors.empty()) attrs += ", COLOR_0";
  for (const ExtraAttribute& e : part.extras) attrs += ", " + e.name + " (" + std::to_string(e.dim) + ")";
  std::printf("  attributes          %s\n", attrs.c_str());
  std::printf("  instances           %zu\n", part.instances.size());
  if (levels > 0) {
    WaveletOptions o;
    o.levels = levels;
    const std::vector<int> counts = analyze(m, {}, o).vertexCounts();
    std::printf("  wavelet levels      %zu:", counts.size() - 1);
    for (size_t k = 0; k < counts.size(); ++k) std::printf("%s%d", k ? " -> " : " ", counts[k]);
    std::printf(" vertices\n");
  }
}

}  // namespace

Command addInfo(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  auto levels = std::make_shared<int>(0);
  CLI::App* sub = app.add_subcommand("info", "Counts, average edge length, bounds, boundary loops, defects, attributes");
  sub->add_option("FILE", *file, "mesh file (.gltf .glb .obj .off .ply .stl)")->required();
  sub->add_option("--levels", *levels, "also print the vertex count after each of this many wavelet levels")
      ->check(atLeastCheck(0));
  return {sub, [file, levels] {
            const Document doc = load(*file);
            std::printf("file    %s\nformat  %s\nparts   %zu\n", file->c_str(), formatName(doc.format),
                        doc.parts.size());
            for (const MeshPart& part : doc.parts) printPart(doc, part, *levels);
          }};
}

}  // namespace geoshift::cli
