#pragma once
// Meshes held by the module between calls, addressed by integer handles. A handle keeps the welded
// mesh (built once, on load) and the per-vertex signals set on it, so a parameter change only
// costs the filter, not another weld. Positions and signals are updated when an op succeeds; a
// failed or cancelled op leaves them as they were.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geoshift/attributes.hpp"
#include "geoshift/mesh.hpp"

namespace geoshift::wasm {

struct PreviewCache;  // preview.cpp

struct Session {
  MeshBuild build;         // the welded mesh; build.vertexOf maps caller vertices onto it
  AttributeSet attributes; // signals in the welded (mesh) layout
  // The coarse level the live preview works on, made at the first preview (preview.cpp).
  std::shared_ptr<PreviewCache> preview;
  int callerVertexCount() const { return static_cast<int>(build.vertexOf.size()); }
};

// Normals are compared on the sphere; every other signal (colors, curvature, height, class) with
// |a - b|. The name decides, so that setAttribute keeps the three-argument shape of the JS API.
AttributeKind kindForName(const std::string& name);

// Adds a caller-layout signal (dim numbers per caller vertex) to the session, averaging caller
// vertices welded together. Throws InputError on a wrong length, dim outside 1..16 or bad values.
void setCallerAttribute(Session& session, const std::string& name, int dim, const std::vector<double>& callerValues);

class Sessions {
 public:
  int add(Session session);
  // Throws InputError naming the handle when it is unknown or was freed.
  Session& get(int handle);
  bool remove(int handle);

 private:
  int next_ = 1;
  std::map<int, Session> sessions_;
};

Sessions& sessions();

}  // namespace geoshift::wasm
