// geoshift terrain: a terrain mesh with per-vertex attributes from LiDAR points (LAS, PLY), a DEM
// GeoTIFF, or the procedural generator, written as glTF (attributes as _NAME accessors).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <set>

#include "commands.hpp"
#include "geoshift/error.hpp"
#include "geoshift/terrain.hpp"

namespace geoshift::cli {
namespace {

// Terrain coordinates are large (UTM northings ~1e7) and glTF positions are float32, so the part
// keeps coordinates relative to a rounded centre and its node carries the offset. The node also
// turns z-up into glTF's y-up, so viewers show the terrain lying flat.
Eigen::Matrix4d placement(const Vec3& origin) {
  Eigen::Matrix4d yUp = Eigen::Matrix4d::Zero();
  yUp(0, 0) = 1;   // x -> x
  yUp(1, 2) = 1;   // z -> y
  yUp(2, 1) = -1;  // y -> -z
  yUp(3, 3) = 1;
  Eigen::Matrix4d shift = Eigen::Matrix4d::Identity();
  shift.block<3, 1>(0, 3) = origin;
  return yUp * shift;
}

void printRange(const Attribute& a) {
  std::cout << "  " << a.name << ":";
  for (int c = 0; c < a.dim; ++c) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int v = 0; v < a.vertexCount(); ++v) lo = std::min(lo, a.row(v)[c]), hi = std::max(hi, a.row(v)[c]);
    std::cout << (c ? ", " : " ") << lo << " .. " << hi;
  }
  if (a.name == "_CLASS") {
    std::set<int> values;
    for (double v : a.values) values.insert(static_cast<int>(v));
    std::cout << " (classes:";
    for (int v : values) std::cout << " " << v;
    std::cout << ")";
  }
  std::cout << "\n";
}

}  // namespace

Command addTerrain(CLI::App& app) {
  struct Args {
    std::string in, out;
    TerrainReadOptions read;
    int procedural = 0;
    TerrainOptions generator;
    bool degrees = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "terrain", "Build a terrain mesh from LiDAR points (.las .ply), a DEM GeoTIFF (.tif), or procedurally");
  sub->add_option("IN", a->in, "input: .las (1.0-1.4), .ply point set, .tif/.tiff DEM");
  sub->add_option("-o,--output", a->out, "output mesh (.glb/.gltf keep the attributes)")->required();
  sub->add_flag("--ground-only", a->read.points.groundOnly, "triangulate only the ground class");
  sub->add_option("--ground-class", a->read.points.groundClass, "class of the ground points (LAS: 2)")->capture_default_str();
  sub->add_flag("--degrees", a->degrees, "geographic DEMs: keep x/y in degrees instead of local metres");
  sub->add_option("--procedural", a->procedural, "generate an N x N procedural terrain instead of reading IN")
      ->check(rangeCheck(2, 18919));  // 6 (N-1)^2 half-edges must fit an int
  sub->add_option("--seed", a->generator.seed, "seed of the procedural terrain")->capture_default_str();
  sub->add_option("--cell-size", a->generator.cellSize, "procedural grid spacing in metres")
      ->capture_default_str()->check(positiveCheck());
  return {sub, [a] {
            if (a->procedural > 0 && !a->in.empty()) throw InputError("terrain: give IN or --procedural N, not both");
            if (a->procedural == 0 && a->in.empty()) throw InputError("terrain: give an input file or --procedural N");
            formatFromPath(a->out);  // a bad output name fails before the work
            a->read.grid.geographicToMeters = !a->degrees;
            const auto t0 = std::chrono::steady_clock::now();
            TerrainMesh mesh;
            if (a->procedural > 0) {
              a->generator.size = a->procedural;
              mesh = proceduralTerrain(a->generator);
            } else {
              mesh = readTerrain(a->in, a->read);
            }
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            for (const std::string& note : mesh.report.notes) std::cerr << "geoshift: note: " << note << "\n";

            Vec3 lo = mesh.positions[0], hi = lo;
            for (const Vec3& p : mesh.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
            const Vec3 origin(std::round(0.5 * (lo.x() + hi.x())), std::round(0.5 * (lo.y() + hi.y())), 0.0);
            Document doc;
            doc.path = a->procedural > 0 ? "procedural terrain" : a->in;
            MeshPart part;
            part.label = "terrain";
            part.positions.reserve(mesh.positions.size());
            for (const Vec3& p : mesh.positions) part.positions.push_back(p - origin);
            part.faces = mesh.faces;
            part.instances = {placement(origin)};
            for (const Attribute& attr : mesh.attributes.all()) {
              if (attr.name == "COLOR_0") {
                part.colors.resize(attr.vertexCount());
                for (int v = 0; v < attr.vertexCount(); ++v)
                  part.colors[v] = Eigen::Vector4d(attr.row(v)[0], attr.row(v)[1], attr.row(v)[2], 1.0);
              } else {
                part.extras.push_back({attr.name, attr.dim, attr.values});
              }
            }
            doc.parts.push_back(std::move(part));
            save(doc, a->out);

            const TerrainReport& r = mesh.report;
            std::cout << "terrain: " << doc.path << "\n"
                      << "  points read: " << r.pointsRead;
            if (r.groundPoints > 0) std::cout << " (ground class " << a->read.points.groundClass << ": " << r.groundPoints << ")";
            if (r.nodataCells > 0) std::cout << " (nodata cells: " << r.nodataCells << ")";
            if (r.duplicatesDropped > 0) std::cout << " (xy duplicates dropped: " << r.duplicatesDropped << ")";
            std::cout << "\n  vertices: " << mesh.positions.size() << ", faces: " << mesh.faces.size() << "\n"
                      << "  x: " << lo.x() << " .. " << hi.x() << ", y: " << lo.y() << " .. " << hi.y()
                      << ", z: " << lo.z() << " .. " << hi.z() << "\n";
            for (const Attribute& attr : mesh.attributes.all()) printRange(attr);
            std::cout << "  built in " << seconds << " s; wrote " << a->out << "\n";
          }};
}

}  // namespace geoshift::cli
