#pragma once
// Named per-vertex signal channels: what the filters read and write.
#include <string>
#include <vector>

namespace geoshift {

enum class AttributeKind {
  Euclidean,   // colors, scalars (curvature, height), class indices: compared with |a - b|
  UnitVector,  // normals: points on the sphere S^{dim-1}, compared on the sphere
};

struct Attribute {
  std::string name;
  int dim = 1;
  AttributeKind kind = AttributeKind::Euclidean;
  std::vector<double> values;  // vertexCount * dim, row per vertex

  int vertexCount() const { return dim > 0 ? static_cast<int>(values.size()) / dim : 0; }
  const double* row(int v) const { return values.data() + static_cast<size_t>(v) * dim; }
  double* row(int v) { return values.data() + static_cast<size_t>(v) * dim; }
};

// A set of attributes over the same vertices. Names are unique.
class AttributeSet {
 public:
  AttributeSet() = default;
  explicit AttributeSet(int vertexCount) : vertexCount_(vertexCount) {}

  int vertexCount() const { return vertexCount_; }
  int size() const { return static_cast<int>(attributes_.size()); }

  // Adds or replaces. Throws InputError when the value count is not vertexCount * dim, dim < 1,
  // the name is empty, or a UnitVector row is not finite and non-zero (naming the vertex); UnitVector
  // rows are normalised.
  Attribute& set(std::string name, int dim, AttributeKind kind, std::vector<double> values);
  bool contains(const std::string& name) const { return find(name) != nullptr; }
  const Attribute* find(const std::string& name) const;
  Attribute* find(const std::string& name);
  // Throws InputError naming the missing attribute and the ones present.
  const Attribute& get(const std::string& name) const;
  bool remove(const std::string& name);
  std::vector<std::string> names() const;
  const std::vector<Attribute>& all() const { return attributes_; }

 private:
  int vertexCount_ = 0;
  std::vector<Attribute> attributes_;
};

}  // namespace geoshift
