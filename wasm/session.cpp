#include "session.hpp"

#include <cmath>

#include "geoshift/error.hpp"

namespace geoshift::wasm {

AttributeKind kindForName(const std::string& name) {
  return name == "normal" || name == "NORMAL" ? AttributeKind::UnitVector : AttributeKind::Euclidean;
}

void setCallerAttribute(Session& session, const std::string& name, int dim, const std::vector<double>& callerValues) {
  if (name.empty()) throw InputError("setAttribute: the attribute name is empty");
  if (dim < 1 || dim > 16) {
    throw InputError("setAttribute \"" + name + "\": dim must be 1 to 16, not " + std::to_string(dim));
  }
  const auto expected = static_cast<std::size_t>(session.callerVertexCount()) * static_cast<std::size_t>(dim);
  if (callerValues.size() != expected) {
    throw InputError("setAttribute \"" + name + "\": " + std::to_string(callerValues.size()) + " numbers for " +
                     std::to_string(session.callerVertexCount()) + " vertices of " + std::to_string(dim) +
                     " (expected " + std::to_string(expected) + ")");
  }
  for (std::size_t i = 0; i < callerValues.size(); ++i) {
    if (!std::isfinite(callerValues[i])) {
      throw InputError("setAttribute \"" + name + "\": vertex " + std::to_string(i / dim) + " has a value that is not a finite number");
    }
  }
  const AttributeKind kind = kindForName(name);
  std::vector<double> meshValues =
      toMeshLayout(callerValues, dim, session.build.vertexOf, session.build.mesh, kind == AttributeKind::UnitVector);
  session.attributes.set(name, dim, kind, std::move(meshValues));
}

int Sessions::add(Session session) {
  const int handle = next_++;
  sessions_.emplace(handle, std::move(session));
  return handle;
}

Session& Sessions::get(int handle) {
  const auto it = sessions_.find(handle);
  if (it == sessions_.end()) {
    throw InputError("mesh handle " + std::to_string(handle) + " is unknown (never loaded, or freed)");
  }
  return it->second;
}

bool Sessions::remove(int handle) { return sessions_.erase(handle) > 0; }

Sessions& sessions() {
  static Sessions all;
  return all;
}

}  // namespace geoshift::wasm
