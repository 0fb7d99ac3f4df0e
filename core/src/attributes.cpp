#include "geoshift/attributes.hpp"

#include <algorithm>
#include <cmath>

#include "geoshift/error.hpp"

namespace geoshift {

Attribute& AttributeSet::set(std::string name, int dim, AttributeKind kind,
                             std::vector<double> values) {
  if (name.empty()) throw InputError("attribute name is empty");
  if (dim < 1) {
    throw InputError("attribute '" + name + "': dimension " + std::to_string(dim) +
                     " (must be at least 1)");
  }
  const size_t expected = static_cast<size_t>(vertexCount_) * static_cast<size_t>(dim);
  if (values.size() != expected) {
    throw InputError("attribute '" + name + "': " + std::to_string(values.size()) +
                     " values, expected " + std::to_string(expected) + " (" +
                     std::to_string(vertexCount_) + " vertices x " + std::to_string(dim) + ")");
  }
  if (kind == AttributeKind::UnitVector) {
    // Unit vectors live on the sphere: a zero or non-finite row has no direction, and silently
    // normalising it would put NaN into every later spherical mean.
    for (int v = 0; v < vertexCount_; ++v) {
      double* row = values.data() + static_cast<size_t>(v) * dim;
      double norm2 = 0;
      bool finite = true;
      for (int k = 0; k < dim; ++k) {
        finite = finite && std::isfinite(row[k]);
        norm2 += row[k] * row[k];
      }
      const double norm = std::sqrt(norm2);
      if (!finite || !(norm > 0) || !std::isfinite(norm)) {
        throw InputError("attribute '" + name + "': unit vector at vertex " + std::to_string(v) +
                         (finite ? " is zero" : " is not finite"));
      }
      for (int k = 0; k < dim; ++k) row[k] /= norm;
    }
  }
  Attribute attribute{std::move(name), dim, kind, std::move(values)};
  if (Attribute* existing = find(attribute.name)) {
    *existing = std::move(attribute);
    return *existing;
  }
  attributes_.push_back(std::move(attribute));
  return attributes_.back();
}

const Attribute* AttributeSet::find(const std::string& name) const {
  auto it = std::find_if(attributes_.begin(), attributes_.end(),
                         [&](const Attribute& a) { return a.name == name; });
  return it == attributes_.end() ? nullptr : &*it;
}

Attribute* AttributeSet::find(const std::string& name) {
  return const_cast<Attribute*>(static_cast<const AttributeSet*>(this)->find(name));
}

const Attribute& AttributeSet::get(const std::string& name) const {
  if (const Attribute* a = find(name)) return *a;
  std::string present;
  for (const Attribute& a : attributes_) present += (present.empty() ? "'" : ", '") + a.name + "'";
  throw InputError("no attribute '" + name + "' (present: " +
                   (present.empty() ? std::string("none") : present) + ")");
}

bool AttributeSet::remove(const std::string& name) {
  auto it = std::find_if(attributes_.begin(), attributes_.end(),
                         [&](const Attribute& a) { return a.name == name; });
  if (it == attributes_.end()) return false;
  attributes_.erase(it);
  return true;
}

std::vector<std::string> AttributeSet::names() const {
  std::vector<std::string> out;
  out.reserve(attributes_.size());
  for (const Attribute& a : attributes_) out.push_back(a.name);
  return out;
}

}  // namespace geoshift
