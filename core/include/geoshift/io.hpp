#pragma once
// Reading and writing mesh files: glTF 2.0 (.gltf/.glb) through tinygltf, OBJ through tinyobjloader,
// OFF, PLY (ascii and binary) and STL (ascii and binary). Format chosen by file extension. Writing back into the file's own format keeps everything
// that is not geometry as it was; writes are atomic (temporary file, then rename), so a failure
// never leaves a partial output.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geoshift/mesh.hpp"

namespace geoshift {

enum class FileFormat { Gltf, Glb, Obj, Off, Ply, Stl };

// Throws InputError naming the path when the extension is none of .gltf .glb .obj .off .ply .stl.
FileFormat formatFromPath(const std::string& path);

// A per-vertex channel to write beside the geometry (glTF: accessor "_NAME"; PLY: vertex property
// NAME without the leading '_', read back as "_NAME"; OBJ/OFF/STL: not stored, reported as a warning).
struct ExtraAttribute {
  std::string name;  // e.g. "_CURVATURE"; glTF custom attributes must start with '_'
  int dim = 1;
  std::vector<double> values;  // positions.size() * dim
};

// One triangle mesh of a file, in the file's own vertex order. glTF: all TRIANGLES primitives that
// share one POSITION accessor form one part.
struct MeshPart {
  std::string label;                      // for messages: "mesh 0 'Duck' primitive 0"
  std::vector<Vec3> positions;            // local coordinates
  std::vector<Face> faces;                // triangles (non-indexed input gets 0..n-1)
  std::vector<Vec3> normals;              // empty when the file has none
  std::vector<Eigen::Vector4d> colors;    // RGBA in [0,1] (linear for glTF); empty when none
  std::vector<Eigen::Matrix4d> instances; // world transform of every node that draws it (identity for OBJ/OFF)
  std::vector<ExtraAttribute> extras;     // written on save; read back from glTF "_NAME" float accessors
};

struct DocumentSource;  // the parsed file, kept for writing back (tinygltf model, OBJ text, ...)

struct Document {
  std::string path;
  FileFormat format = FileFormat::Obj;
  std::vector<MeshPart> parts;
  std::vector<std::string> warnings;  // content passed through untouched, and why
  std::shared_ptr<DocumentSource> source;
};

struct ReadOptions {
  // A file declaring more vertices than this (or a glTF accessor without data declaring more
  // elements) is refused before anything is allocated for them. CLI: --max-vertices.
  size_t maxVertices = 50'000'000;
  // OBJ: keep the file's text in the document, for writing back into it (writeDocument rewrites
  // only its v, vn and f lines). When false, only the file's size and a 64-bit hash of its bytes
  // are kept, and writing back reads the file again first: if it changed or is gone by then, the
  // write throws InputError and writes nothing. The CLI sets it false (15 MB less held through the
  // denoise of a 144k-vertex scan; docs/io.md).
  bool keepSourceText = true;
};

// Throws InputError naming the file and what/where (mesh, primitive, accessor, element, line) on
// unreadable or unsupported content: Draco/meshopt compression, non-finite values, indices out of
// range, counts the file cannot hold, more vertices than options.maxVertices.
// Sparse accessors are applied (and written back densely). Points, lines, strips and fans are kept
// untouched and reported in `warnings`. A file with no triangle is an error. See docs/io.md.
Document readDocument(const std::string& path, const ReadOptions& options = {});

// Writes the document; positions, normals, colors and extras of each part replace the file's.
// Same format as read: everything else is kept (materials, textures, nodes, extras, OBJ groups and
// texture coordinates). Another format: geometry, normals, colors (and extras into glTF and PLY)
// only, in world space for OBJ/OFF/PLY/STL, with a warning returned. PLY is written binary little
// endian; STL binary (positions only).
// Throws InputError (nothing written) when a part's array sizes do not match its positions.
std::vector<std::string> writeDocument(const Document& document, const std::string& path);

// All parts of the document in world space (every instance), concatenated into one soup.
TriangleSoup worldSoup(const Document& document);
// One part in its local coordinates.
TriangleSoup partSoup(const MeshPart& part);

}  // namespace geoshift
