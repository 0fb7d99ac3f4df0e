// PLY point sets (ascii, binary little/big endian): the vertex element's position, color and
// class. Other elements are skipped (lists included), so a PLY mesh reads as its vertices. The
// container is parsed by ply_format.cpp, the same parser as PLY meshes.
#include <algorithm>
#include <cmath>

#include "geoshift/terrain.hpp"
#include "io_detail.hpp"
#include "ply_format.hpp"

namespace geoshift {

TerrainPoints readPlyPoints(const std::string& path) {
  using namespace io::ply;
  const std::string b = io::readWholeFile(path);
  const Header h = parseHeader(path, b);
  if (h.findElement("vertex") < 0) io::fail(path, "the PLY file has no vertex element");

  TerrainPoints pts;
  Records rec(path, b, h);
  for (const Element& e : h.elements) {
    if (e.name != "vertex") {
      if (e.props.empty()) continue;
      for (size_t i = 0; i < e.count; ++i) {
        rec.begin(e, i);
        for (const Property& p : e.props) rec.skip(p);
        rec.end();
      }
      continue;
    }
    int ix = -1, iy = -1, iz = -1, ir = -1, ig = -1, ib = -1, ic = -1;
    for (size_t k = 0; k < e.props.size(); ++k) {
      const std::string& nm = e.props[k].name;
      const int kk = static_cast<int>(k);
      if (nm == "x") ix = kk;
      else if (nm == "y") iy = kk;
      else if (nm == "z") iz = kk;
      else if (nm == "red" || nm == "r" || nm == "diffuse_red") ir = kk;
      else if (nm == "green" || nm == "g" || nm == "diffuse_green") ig = kk;
      else if (nm == "blue" || nm == "b" || nm == "diffuse_blue") ib = kk;
      else if (nm == "classification" || nm == "class" || nm == "label" || nm == "scalar_Classification") ic = kk;
    }
    if (ix < 0 || iy < 0 || iz < 0) io::fail(path, "the vertex element has no x, y and z properties");
    if (e.props[ix].list || e.props[iy].list || e.props[iz].list) io::fail(path, "vertex x/y/z are lists");
    // parseHeader has checked the count against the file's size.
    const bool color = ir >= 0 && ig >= 0 && ib >= 0;
    const double colorScale = !color ? 1.0 : e.props[ir].type == Type::U8 ? 1.0 / 255 : e.props[ir].type == Type::U16 ? 1.0 / 65535 : 1.0;
    pts.positions.resize(e.count);
    if (ic >= 0) pts.classes.resize(e.count);
    if (color) pts.colors.resize(e.count);
    std::vector<double> row(e.props.size());
    for (size_t i = 0; i < e.count; ++i) {
      rec.begin(e, i);
      for (size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        if (p.list) rec.skip(p);
        else row[k] = rec.scalar(p);
      }
      rec.end();
      pts.positions[i] = Vec3(row[ix], row[iy], row[iz]);
      if (!pts.positions[i].allFinite()) rec.fail("NaN or infinite coordinate");
      if (ic >= 0) {
        // A float class property may hold anything; converting it unchecked would be undefined.
        if (!(row[ic] >= -2147483648.0 && row[ic] <= 2147483647.0) || row[ic] != std::floor(row[ic]))
          rec.fail("class '" + io::formatNumber(row[ic]) + "' is not an integer");
        pts.classes[i] = static_cast<int>(row[ic]);
      }
      if (color) pts.colors[i] = (Eigen::Vector3d(row[ir], row[ig], row[ib]) * colorScale).cwiseMax(0.0).cwiseMin(1.0);
    }
    if (ic >= 0) pts.notes.push_back("classes from the PLY property '" + e.props[ic].name + "'");
    return pts;
  }
  io::fail(path, "the PLY file has no vertex element");
}

}  // namespace geoshift
