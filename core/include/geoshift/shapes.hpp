#pragma once
// Procedural meshes for tests, benchmarks and demos. All faces counter-clockwise seen from outside.
#include <functional>

#include "geoshift/mesh.hpp"

namespace geoshift::shapes {

TriangleSoup tetrahedron();                    // regular, circumradius 1, centred at the origin
TriangleSoup cube();                           // [-1,1]^3, 8 vertices, 12 faces (welded)
// n x n vertices over [0,1]^2 in the z = 0 plane, jitter (fraction of the spacing) applied to the
// interior vertices with a fixed seed; one boundary loop.
TriangleSoup grid(int n, double jitter = 0.0, unsigned seed = 1);
// Subdivided icosahedron on a sphere of the given radius: 10 * 4^level + 2 vertices.
TriangleSoup icosphere(int level, double radius = 1.0);
// Open prism cylinder around z with `sides` sides and `rings` rings of vertices over [0, height].
TriangleSoup cylinder(int sides, int rings, double radius = 1.0, double height = 1.0);
// Torus around z: major radius R, minor radius r.
TriangleSoup torus(int majorSegments, int minorSegments, double R = 1.0, double r = 0.35);
// Closed box [-size/2, size/2] with nx x ny x nz quads (each split into two triangles) along its
// sides: flat sides meeting at sharp 90° edges, a CAD-like block for feature-preserving filters.
TriangleSoup box(int nx, int ny, int nz, const Vec3& size = Vec3(1, 1, 1));
// Closed genus-2 surface: two tori (major radius 1, minor radius 0.4, centres 2.4 apart on x)
// blended smoothly where they meet. `resolution` grid cells span its length, in [16, 1024]; the
// vertex count grows with its square (32: about 4.6k, 64: about 18k). Marched tetrahedra, then
// relaxed along the surface for even triangles.
TriangleSoup doubleTorus(int resolution = 32);
// The zero set of `field` (negative inside) within the box [lo, hi], marched on tetrahedra of a grid
// of cell size h, then `relaxPasses` times every vertex moved to the mean of its neighbours and back
// onto the surface (Newton steps along the field's gradient) to even out the marching's slivers.
// The field must be negative inside and positive on the box's faces; faces point outward.
using ImplicitField = std::function<double(const Vec3&)>;
TriangleSoup implicitSurface(const ImplicitField& field, const Vec3& lo, const Vec3& hi, double h, int relaxPasses = 8);

// Parts with the features that trouble surface filters (docs/denoising.md#the-evaluation), all closed
// unless said otherwise; `detail` scales their vertex count (1: a few thousand).
// A tube of radius `tube` around the (p, q) torus knot on a torus of radii 2 and 1 (p = 2, q = 3:
// the trefoil), swept with a rotation-minimising frame: a thin tube, 16 edges around at detail 1.
TriangleSoup torusKnot(int p, int q, double tube = 0.25, double detail = 1);
// A turbine blade: a plate 1 long, 0.4 wide and 0.05 thick with rounded long edges, twisted 60°
// along its length: a thin sheet whose two sides lie about two edge lengths apart.
TriangleSoup turbineBlade(double detail = 1);
// A bowl: a spherical shell of radius 0.5 and thickness 0.04 cut by a plane: thin sheet with a rim.
TriangleSoup thinBowl(double detail = 1);
// A hub (radius 0.25) with six thin radial fins (0.036 thick): thin fins on a solid body.
TriangleSoup finnedRotor(double detail = 1);
// A base plate with seven thin parallel fins (0.03 thick) standing on it: concave creases at their feet.
TriangleSoup heatSink(double detail = 1);
// An open sheet: a jittered n x n grid bent over a cylinder section, with three round holes cut
// out along the faces' centroids (ragged boundaries, as a scan's holes have). Unused vertices are dropped.
TriangleSoup perforatedSheet(int n = 70, unsigned seed = 1);

// The same soup with every face's corners given their own vertex (like a glTF with split seams).
TriangleSoup unwelded(const TriangleSoup& soup);

}  // namespace geoshift::shapes
