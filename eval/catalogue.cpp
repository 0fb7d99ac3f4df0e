#include "catalogue.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <span>
#include <sstream>

#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/io.hpp"
#include "geoshift/shapes.hpp"
#include "geoshift/terrain.hpp"

namespace fs = std::filesystem;

namespace geoshift::eval {

const char* setName(Set s) {
  return s == Set::Tuning ? "tuning" : s == Set::Validation ? "validation" : s == Set::Broad ? "broad" : "holdout";
}

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

namespace {

Mesh fromFile(const fs::path& path) { return buildMesh(worldSoup(readDocument(path.string()))).mesh; }

Mesh fromTerrain(const fs::path& path) { return buildMesh(readTerrain(path.string()).soup()).mesh; }

}  // namespace

std::vector<MeshEntry> cleanMeshes(const fs::path& data) {
  std::vector<MeshEntry> out;
  auto procedural = [&](std::string name, std::string family, std::string category, bool seen,
                        std::function<TriangleSoup()> make) {
    out.push_back({name + " (procedural)", family, category, seen, false, [make] { return buildMesh(make()).mesh; }});
  };
  auto file = [&](std::string name, std::string family, std::string category, bool seen, std::string rel,
                  bool terrain = false) {
    const fs::path p = data / rel;
    if (!fs::exists(p)) {
      std::cerr << "denoise_eval: left out " << name << ": " << p.string() << " not found (../shared/data absent)\n";
      return;
    }
    out.push_back({name, family, category, seen, false, [p, terrain] { return terrain ? fromTerrain(p) : fromFile(p); }});
  };
  const std::string g = "guided_denoising_bldeng/models/", o = "odedstein_meshes/";
  // Seen: the scoreboard that chose the defaults until 2026-11-26 (its 13 clean meshes and 11 pairs).
  procedural("CAD block", "cad block", "CAD", true, [] { return shapes::box(40, 28, 20, Vec3(1.0, 0.7, 0.5)); });
  procedural("Sphere", "sphere", "smooth", true, [] { return shapes::icosphere(5); });
  procedural("Torus", "torus", "smooth", true, [] { return shapes::torus(120, 40); });
  procedural("Double torus", "double torus", "smooth", true, [] { return shapes::doubleTorus(32); });
  file("Fandisk", "fandisk", "CAD", true, g + "Fandisk0.3/Original.obj");
  file("Star", "star", "CAD", true, g + "compareJustin/trim-star_rescaled.obj");
  file("Block", "block", "CAD", true, g + "Block0.4/Original.obj");
  file("SharpSphere", "sharpsphere", "CAD", true, g + "SharpSphere0.3/Original.obj");
  file("Twelve", "twelve", "CAD", true, g + "Twelve0.5Impulsive/Original.obj");
  file("Nicolo", "nicolo", "sculpture", true, g + "Nicolo0.2/Original.obj");
  file("Fertility", "fertility", "sculpture", true, "gcn_denoiser/models/fertility.obj");
  file("Bunny", "bunny", "scan", true, g + "Bunny0.2/Original.obj");
  file("Julius", "julius", "sculpture", true, g + "Julius0.2/Original.obj");
  // The same objects as seen families, other meshes of them: tuning too.
  file("Bunny (3k)", "bunny", "scan", true, o + "bunny/bunny.obj");
  file("Torus (2k)", "torus", "smooth", true, o + "torus/torus.obj");

  // New since 2026-11-26: split by the rule.
  file("Sword", "sword", "CAD", false, o + "sword/sword.obj");
  procedural("Heat sink", "heat sink", "CAD", false, [] { return shapes::heatSink(); });
  procedural("Finned rotor", "finned rotor", "CAD", false, [] { return shapes::finnedRotor(); });
  file("Boot", "boot", "sculpture", false, o + "boot/boot.obj");
  file("Demosthenes", "demosthenes", "sculpture", false, o + "demosthenes/demosthenes-low-res.obj");
  file("Falcon statue", "falconstatue", "sculpture", false, o + "falconstatue/falconstatue.obj");
  file("Goat head", "goathead", "sculpture", false, o + "goathead/goathead.obj");
  file("Lion statue", "lionstatue", "sculpture", false, o + "lionstatue/lionstatue.obj");
  file("Chinese dragon", "chinesedragon", "sculpture", false, "cgal_debian_libcgal_demo/data/meshes/ChineseDragon-10kv.off");
  file("Mushroom", "mushroom", "sculpture", false, o + "mushroom/mushroom.obj");
  file("Pizza", "pizza", "sculpture", false, o + "pizza/pizza.obj");
  file("Stuffed toy", "stuffedtoy", "sculpture", false, o + "stuffedtoy/stuffedtoy.obj");
  file("Armadillo (15k)", "armadillo", "animal", false, o + "armadillo/armadillo.obj");
  file("Armadillo (26k)", "armadillo", "animal", false, "cgal_debian_libcgal_demo/data/meshes/armadillo.off");
  file("Fish", "fish", "animal", false, o + "fish/fish.obj");
  file("Fish (1k)", "fish", "animal", false, o + "fish/fish_low_resolution.obj");
  file("Koala", "koala", "animal", false, o + "koala/koala.obj");
  file("Koala (4k)", "koala", "animal", false, o + "koala/koala_low_resolution.obj");
  file("Penguin", "penguin", "animal", false, o + "penguin/penguin.obj");
  file("Spot", "spot", "animal", false, o + "spot/spot.obj");
  file("Spot (1k)", "spot", "animal", false, o + "spot/spot_low_resolution.obj");
  file("Springer", "springer", "animal", false, o + "springer/springer.obj");
  file("Plane", "plane", "thin sheet", false, o + "plane/plane.obj");
  file("Plane with holes", "plane", "thin sheet", false, o + "plane/plane_holes.obj");
  procedural("Turbine blade", "turbine blade", "thin sheet", false, [] { return shapes::turbineBlade(); });
  procedural("Thin bowl", "thin bowl", "thin sheet", false, [] { return shapes::thinBowl(); });
  procedural("Trefoil knot tube", "trefoil knot", "tube", false, [] { return shapes::torusKnot(2, 3); });
  procedural("(2, 5) knot tube", "2-5 knot", "tube", false, [] { return shapes::torusKnot(2, 5, 0.2); });
  file("Mountain", "mountain", "open or terrain", false, o + "mountain/mountain.obj");
  file("B9 urban terrain", "b9", "open or terrain", false, "cgal_debian_libcgal_demo/data/meshes/b9_mesh.off");
  file("Olinda DEM", "olinda", "open or terrain", false, "dem_debian_r_packages/stars/olinda_dem_utm25s.tif", true);
  file("Elevation DEM (terra)", "terra elev", "open or terrain", false, "dem_debian_r_packages/terra/elev.tif", true);
  procedural("Fractal terrain", "fractal terrain", "open or terrain", false, [] {
    TerrainOptions t;
    t.size = 129;
    t.seed = 7;
    return proceduralTerrain(t).soup();
  });
  procedural("Perforated sheet", "perforated sheet", "open or terrain", false, [] { return shapes::perforatedSheet(); });
  return out;
}

namespace {

// A file of CGAL's demo folder as a set's rule lists it.
struct Listed {
  const char *stem, *family, *category;
};

// The listed files that are in `dir`, a note for each that is not, and none (with a note that says
// how to fetch them) when the folder is absent.
std::vector<std::pair<Listed, fs::path>> listedFiles(const fs::path& dir, const char* set, std::span<const Listed> listed) {
  std::vector<std::pair<Listed, fs::path>> out;
  if (!fs::is_directory(dir)) {
    std::cerr << "denoise_eval: the " << set << " set's meshes are not in " << dir.string()
              << ": fetch them with scripts/eval-data.sh (or give --broad-data DIR)\n";
    return out;
  }
  for (const Listed& l : listed) {
    const fs::path p = dir / (std::string(l.stem) + ".off");
    if (fs::exists(p))
      out.push_back({l, p});
    else
      std::cerr << "denoise_eval: left out " << l.stem << " (CGAL): " << p.string() << " not found\n";
  }
  return out;
}

}  // namespace

std::vector<MeshEntry> broadMeshes(const fs::path& dir) {
  // The rule of docs/denoising.md ("The broad tuning set"): file stem, family, category. Written
  // down from the files' names and sizes before any result on them was looked at.
  static const Listed listed[] = {
      {"ALSTOM_TEST4", "alstom test4", "CAD"},
      {"anchor_dense", "anchor", "CAD"},
      {"couplingdown", "couplingdown", "CAD"},
      {"mech-holes-shark", "mech holes shark", "CAD"},
      {"rotor_small", "rotor small", "CAD"},
      {"turbine", "turbine", "CAD"},
      {"blade", "blade", "thin sheet"},
      {"boeing", "boeing", "thin sheet"},
      {"bear", "bear", "animal"},
      {"bear_bis", "bear", "animal"},
      {"bull", "bull", "animal"},
      {"camel", "camel", "animal"},
      {"cow", "cow", "animal"},
      {"dino", "dino", "animal"},
      {"diplodocus", "diplodocus", "animal"},
      {"elephant", "elephant", "animal"},
      {"elephant-with-holes", "elephant", "animal"},
      {"refined_elephant", "elephant", "animal"},
      {"hand", "hand", "animal"},
      {"homer", "homer", "animal"},
      {"man", "man", "animal"},
      {"triceratops", "triceratops", "animal"},
      {"bones", "bones", "sculpture"},
      {"femur", "femur", "sculpture"},
      {"head", "head", "sculpture"},
      {"mannequin-devil", "mannequin devil", "sculpture"},
      {"blobby", "blobby", "smooth"},
      {"blobby_3cc", "blobby", "smooth"},
      {"cheese", "cheese", "smooth"},
      {"elk", "elk", "smooth"},
      {"ellipe0.003", "ellipe", "smooth"},
      {"handle", "handle", "smooth"},
      {"retinal", "retinal", "smooth"},
      {"knot", "knot", "tube"},
      {"knot1", "knot1", "tube"},
      {"knot2", "knot2", "tube"},
      {"cylinder", "cylinder", "open or terrain"},
      {"cylinder_locally_refined", "cylinder", "open or terrain"},
      {"holes", "holes", "open or terrain"},
      {"horizons", "horizons", "open or terrain"},
      {"mask_cone", "mask cone", "open or terrain"},
      {"polygon_mesh", "polygon mesh", "open or terrain"},
      {"poly2x^2+y^2-0.062500", "poly2x2y2", "open or terrain"},
      {"three_peaks", "three peaks", "open or terrain"},
  };
  std::vector<MeshEntry> out;
  for (const auto& [listedFile, path] : listedFiles(dir, "broad", listed)) {
    // Copies to capture: clang 14 captures no structured binding.
    const Listed l = listedFile;
    const fs::path p = path;
    out.push_back({std::string(l.stem) + " (CGAL)", std::string("cgal ") + l.family, l.category, false, true,
                   [p] { return fromFile(p); }});
  }
  return out;
}

namespace {

// The connectivity of a split in four: the input's vertices, then one vertex per edge (the edge's
// two ends in `edges`, in the order the faces first meet them), four faces per input face.
struct Split {
  std::vector<std::array<int, 2>> edges;
  std::vector<std::vector<int>> opposite;  // per edge: the third corner of each face on it
  std::vector<Face> faces;
};

Split splitConnectivity(const Mesh& mesh) {
  Split s;
  const int n = mesh.vertexCount();
  std::map<std::pair<int, int>, int> index;
  auto edge = [&](int a, int b, int c) {
    auto [it, added] = index.try_emplace({std::min(a, b), std::max(a, b)}, n + static_cast<int>(s.edges.size()));
    if (added) {
      s.edges.push_back({a, b});
      s.opposite.emplace_back();
    }
    s.opposite[it->second - n].push_back(c);
    return it->second;
  };
  s.faces.reserve(4 * mesh.faces().size());
  for (const Face& f : mesh.faces()) {
    const int ab = edge(f[0], f[1], f[2]), bc = edge(f[1], f[2], f[0]), ca = edge(f[2], f[0], f[1]);
    s.faces.push_back({f[0], ab, ca});
    s.faces.push_back({ab, f[1], bc});
    s.faces.push_back({ca, bc, f[2]});
    s.faces.push_back({ab, bc, ca});
  }
  return s;
}

}  // namespace

Mesh splitInFour(const Mesh& mesh) {
  const Split s = splitConnectivity(mesh);
  TriangleSoup soup;
  soup.positions = mesh.positions();
  for (const auto& e : s.edges) soup.positions.push_back(0.5 * (mesh.positions()[e[0]] + mesh.positions()[e[1]]));
  soup.faces = s.faces;
  return buildMesh(soup).mesh;
}

Mesh loopSubdivide(const Mesh& mesh) {
  const Split s = splitConnectivity(mesh);
  const std::vector<Vec3>& p = mesh.positions();
  const int n = mesh.vertexCount();
  // Each vertex's neighbours, and those across a boundary edge (an edge of one face).
  std::vector<std::vector<int>> neighbors(n), boundaryNeighbors(n);
  for (size_t e = 0; e < s.edges.size(); ++e) {
    const auto [a, b] = s.edges[e];
    neighbors[a].push_back(b);
    neighbors[b].push_back(a);
    if (s.opposite[e].size() == 1) {
      boundaryNeighbors[a].push_back(b);
      boundaryNeighbors[b].push_back(a);
    }
  }
  TriangleSoup soup;
  soup.positions.resize(n);
  for (int v = 0; v < n; ++v) {
    const auto& nb = neighbors[v];
    const auto& bn = boundaryNeighbors[v];
    if (bn.size() == 2) {
      soup.positions[v] = 0.75 * p[v] + 0.125 * (p[bn[0]] + p[bn[1]]);
    } else if (!bn.empty() || nb.empty()) {
      soup.positions[v] = p[v];  // a corner of several boundary loops, or a lone vertex: kept
    } else {
      const double k = static_cast<double>(nb.size()), c = 0.375 + 0.25 * std::cos(2 * M_PI / k);
      const double beta = (0.625 - c * c) / k;
      Vec3 sum = Vec3::Zero();
      for (int u : nb) sum += p[u];
      soup.positions[v] = (1 - k * beta) * p[v] + beta * sum;
    }
  }
  for (size_t e = 0; e < s.edges.size(); ++e) {
    const auto [a, b] = s.edges[e];
    const auto& o = s.opposite[e];
    const Vec3 q = o.size() == 2 ? Vec3(0.375 * (p[a] + p[b]) + 0.125 * (p[o[0]] + p[o[1]])) : Vec3(0.5 * (p[a] + p[b]));
    soup.positions.push_back(q);
  }
  soup.faces = s.faces;
  return buildMesh(soup).mesh;
}

std::vector<MeshEntry> holdoutMeshes(const fs::path& dir) {
  // The rule of docs/denoising.md ("The holdout set"): file stem, family, category. Written down
  // from the files' names and sizes before any result on them was looked at.
  static const Listed listed[] = {
      {"cube-meshed", "cube meshed", "CAD"},
      {"pinion", "pinion", "CAD"},
      {"spool", "spool", "CAD"},
      {"pig", "pig", "animal"},
      {"cactus", "cactus", "sculpture"},
      {"helmet", "helmet", "sculpture"},
      {"eight", "eight", "smooth"},
      {"oblong", "oblong", "smooth"},
      {"mesh_with_border", "mesh with border", "open or terrain"},
      {"patch-01", "patch 01", "open or terrain"},
      {"patch-20", "patch 20 30", "open or terrain"},
      {"patch-30", "patch 20 30", "open or terrain"},
      {"plane", "plane grid", "open or terrain"},
  };
  std::vector<MeshEntry> out;
  for (const auto& [listedFile, path] : listedFiles(dir, "holdout", listed)) {
    // Copies to capture: clang 14 captures no structured binding.
    const Listed l = listedFile;
    const fs::path p = path;
    // Split in four: the coarse polyhedron itself. Loop: a smooth surface through the same object,
    // one family with it (added after the split meshes' record: docs/denoising.md, "The holdout set").
    auto refined = [&](const char* how, const std::string& category, Mesh (*refine)(const Mesh&)) {
      MeshEntry m{std::string(l.stem) + " (CGAL, " + how + ")", std::string("cgal ") + l.family, category, false, false,
                  [p, refine] {
                    Mesh mesh = fromFile(p);
                    while (mesh.vertexCount() < holdoutMinVertices) mesh = refine(mesh);
                    return mesh;
                  }};
      m.holdout = true;
      out.push_back(std::move(m));
    };
    refined("split", l.category, splitInFour);
    refined("Loop", "smooth by Loop", loopSubdivide);
  }
  return out;
}

std::vector<std::pair<std::string, Set>> splitFamilies(const std::vector<MeshEntry>& meshes) {
  std::map<std::string, std::vector<std::string>> newByCategory;
  std::vector<std::pair<std::string, Set>> out;
  auto known = [&](const std::string& family) {
    return std::any_of(out.begin(), out.end(), [&](const auto& e) { return e.first == family; });
  };
  for (const MeshEntry& m : meshes) {
    if (known(m.family)) continue;
    if (m.broad) {
      out.push_back({m.family, Set::Broad});
      continue;
    }
    if (m.holdout) {
      out.push_back({m.family, Set::Holdout});
      continue;
    }
    if (m.seen) {
      out.push_back({m.family, Set::Tuning});
      continue;
    }
    auto& list = newByCategory[m.category];
    if (std::find(list.begin(), list.end(), m.family) == list.end()) list.push_back(m.family);
  }
  for (auto& [category, families] : newByCategory) {
    std::sort(families.begin(), families.end(),
              [](const std::string& a, const std::string& b) { return fnv1a(a) < fnv1a(b); });
    for (size_t i = 0; i < families.size(); ++i) out.push_back({families[i], i % 2 == 0 ? Set::Validation : Set::Tuning});
  }
  return out;
}

std::vector<NoiseSpec> noisesFor(const std::string& meshName, std::uint64_t seed) {
  const double levels[] = {0.2, 0.3, 0.5, 0.7};
  auto spec = [seed](NoiseDistribution d, double amount, NoiseDirection dir) {
    NoiseSpec s;
    s.options.distribution = d;
    s.options.amount = amount;
    s.options.direction = dir;
    s.options.seed = seed;
    std::ostringstream label;
    label << (d == NoiseDistribution::Fixed       ? "fixed "
              : d == NoiseDistribution::Uniform   ? "uniform [0, "
              : d == NoiseDistribution::Gaussian  ? "gaussian "
                                                  : "impulsive ")
          << amount << (d == NoiseDistribution::Uniform ? "]" : "") << " AEL"
          << (dir == NoiseDirection::Normal ? " along normals" : " random dir.");
    s.label = label.str();
    return s;
  };
  const std::uint64_t hg = fnv1a(meshName + "/gaussian"), hi = fnv1a(meshName + "/impulsive");
  return {
      spec(NoiseDistribution::Fixed, 0.5, NoiseDirection::Random),
      spec(NoiseDistribution::Uniform, 0.5, NoiseDirection::Random),
      spec(NoiseDistribution::Gaussian, levels[hg % 4], (hg >> 8) % 2 ? NoiseDirection::Normal : NoiseDirection::Random),
      spec(NoiseDistribution::Impulsive, levels[hi % 4], (hi >> 8) % 2 ? NoiseDirection::Normal : NoiseDirection::Random),
  };
}

std::vector<Pair> groundTruthPairs() {
  const std::string g = "guided_denoising_bldeng/models/", n = "gcn_denoiser/models/";
  return {
      {"Fandisk 0.3", "fandisk", g + "Fandisk0.3/Original.obj", g + "Fandisk0.3/Noisy.obj", ""},
      {"Fandisk 0.7", "fandisk", g + "Fandisk0.3/Original.obj", g + "Fandisk0.7/Noisy.obj", ""},
      {"Star (Solomon 2014)", "star", g + "compareJustin/trim-star_rescaled.obj", g + "compareJustin/trim-star_n0.5_rescaled.obj", ""},
      {"Block 0.4", "block", g + "Block0.4/Original.obj", g + "Block0.4/Noisy.obj", ""},
      {"SharpSphere 0.3", "sharpsphere", g + "SharpSphere0.3/Original.obj", g + "SharpSphere0.3/Noisy.obj", ""},
      {"Twelve 0.5 impulsive", "twelve", g + "Twelve0.5Impulsive/Original.obj", g + "Twelve0.5Impulsive/Noisy.obj", ""},
      {"Nicolo 0.2", "nicolo", g + "Nicolo0.2/Original.obj", g + "Nicolo0.2/Noisy.obj", ""},
      {"Bunny 0.2", "bunny", g + "Bunny0.2/Original.obj", g + "Bunny0.2/Noisy.obj", ""},
      {"Julius 0.2", "julius", g + "Julius0.2/Original.obj", g + "Julius0.2/Noisy.obj", ""},
      {"Fandisk (GCN, Gaussian)", "fandisk", n + "fandisk.obj", n + "fandisk_gaus_n6_noisy.obj", n + "fandisk_gaus_n6_denoised.obj"},
      {"Fertility (GCN, Gaussian)", "fertility", n + "fertility.obj", n + "fertility_gaus_n3.obj", n + "fertility_gaus_n3_denoised.obj"},
  };
}

namespace {

// A file of the pair's vertex order mapped onto the clean mesh's welded vertices under `s`.
std::vector<Vec3> mapped(const MeshBuild& b, const Similarity& s, const TriangleSoup& soup) {
  std::vector<Vec3> out = b.mesh.positions();
  std::vector<char> set(b.mesh.vertexCount(), 0);
  for (size_t i = 0; i < soup.positions.size(); ++i) {
    const int v = b.vertexOf[i];
    if (set[v]) continue;  // welded copies: the first caller vertex stands for all
    set[v] = 1;
    out[v] = s.apply(soup.positions[i]);
  }
  return out;
}

}  // namespace

bool loadPair(const fs::path& data, const Pair& p, Case& c) {
  const fs::path cleanPath = data / p.clean, noisyPath = data / p.noisy;
  if (!fs::exists(cleanPath) || !fs::exists(noisyPath)) {
    std::cerr << "denoise_eval: left out pair " << p.name << ": files not found under " << data.string() << "\n";
    return false;
  }
  const TriangleSoup cleanSoup = worldSoup(readDocument(cleanPath.string()));
  const TriangleSoup noisySoup = worldSoup(readDocument(noisyPath.string()));
  if (cleanSoup.positions.size() != noisySoup.positions.size()) {
    std::cerr << "denoise_eval: left out pair " << p.name << ": vertex counts differ\n";
    return false;
  }
  const MeshBuild b = buildMesh(cleanSoup);
  c.mesh = p.name + " (pair)";
  c.noise = "the pair's own noise";
  c.family = p.family;
  c.category = "ground-truth pair";
  c.clean = b.mesh;
  c.noisy = b.mesh;
  const Similarity s = normalizeToUnitCube(c.clean);
  c.noisy.positions() = mapped(b, s, noisySoup);
  c.gcnResult = p.gcnResult;
  return true;
}

std::vector<Vec3> loadResultPositions(const fs::path& data, const Pair& p, const std::string& file) {
  const TriangleSoup cleanSoup = worldSoup(readDocument((data / p.clean).string()));
  const TriangleSoup result = worldSoup(readDocument((data / file).string()));
  if (result.positions.size() != cleanSoup.positions.size()) {
    throw InputError(file + ": " + std::to_string(result.positions.size()) + " vertices, the pair's clean mesh has " +
                     std::to_string(cleanSoup.positions.size()));
  }
  const MeshBuild b = buildMesh(cleanSoup);
  Mesh scaled = b.mesh;
  const Similarity s = normalizeToUnitCube(scaled);
  return mapped(b, s, result);
}

}  // namespace geoshift::eval
