#pragma once
// Procedural meshes for tests, benchmarks and demos. All faces counter-clockwise seen from outside.
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
// The same soup with every face's corners given their own vertex (like a glTF with split seams).
TriangleSoup unwelded(const TriangleSoup& soup);

}  // namespace geoshift::shapes
