// OBJ written back without its text kept (ReadOptions::keepSourceText = false, as the CLI reads):
// the file is read again when written and must be the one that was read (docs/io.md, OBJ).
#include <catch2/catch.hpp>

#include <filesystem>
#include <functional>
#include <string>

#include "geoshift/error.hpp"
#include "geoshift/io.hpp"
#include "support.hpp"

using namespace geoshift;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace geoshift::test;

namespace {

// Comments, a material library, groups, texture coordinates, normals, vertex colors, CRLF line
// ends, blanks before keywords and a last line without a terminator.
const std::string kText =
    "# two quads\r\nmtllib none.mtl\r\no thing\r\ng left\r\nv 0 0 0 1 0 0\r\nv 1 0 0 0 1 0\r\n  v 1 1 0 0 0 1\r\n"
    "v 0 1 0 0.5 0.5 0.5\r\nv 2 0 0 1 1 1\r\nv 3 0 0 0.25 0.25 0.25\r\nv 3 1 0 0 0 0\r\nv 2 1 0 1 1 1\r\n"
    "vt 0 0\r\nvt 1 0\r\nvt 1 1\r\nvn 0 0 1\r\n\tvn 0 0 1\r\nusemtl red\r\n# the left quad\r\n"
    "f 1/1/1 2/2/1 3/3/1 4/1/1\r\ng right\r\ns 1\r\nf 5/1/2 6/2/2 7/3/2\r\nf 5/1/2 7/3/2 8/2/2";

ReadOptions withoutText() {
  ReadOptions o;
  o.keepSourceText = false;
  return o;
}

// Moves two vertices, recolors one and changes the normals: `consistent` keeps one normal per vn
// line (rewritten in place), otherwise the two vertices of vn line 1 differ (the vn lines go and
// the faces lose their normal references).
void edit(Document& doc, bool consistent) {
  MeshPart& part = doc.parts.at(0);
  part.positions[1] = Vec3(1, 0, 0.25);
  part.positions[5] = Vec3(3, 0.5, -0.125);
  part.colors[2] = Eigen::Vector4d(0.125, 0.5, 1, 1);
  for (size_t v = 0; v < 4; ++v) part.normals[v] = Vec3(0, 0.6, 0.8);
  if (!consistent) part.normals[3] = Vec3(0, 0.8, 0.6);
}

}  // namespace

TEST_CASE("OBJ without its text kept writes the same bytes as with it", "[io][obj]") {
  const fs::path dir = tempDir("io-obj-source");
  spit(dir / "a.obj", kText);
  for (const bool consistent : {true, false}) {
    INFO("one new normal per vn line: " << consistent);
    Document kept = readDocument((dir / "a.obj").string());
    Document reread = readDocument((dir / "a.obj").string(), withoutText());
    REQUIRE(reread.parts.at(0).positions == kept.parts.at(0).positions);
    REQUIRE(reread.parts.at(0).normals.size() == 8);
    REQUIRE(reread.parts.at(0).colors.size() == 8);

    // Unchanged: the file itself, both ways.
    writeDocument(reread, (dir / "same.obj").string());
    CHECK(slurp(dir / "same.obj") == kText);

    edit(kept, consistent);
    edit(reread, consistent);
    const auto keptWarnings = writeDocument(kept, (dir / "kept.obj").string());
    const auto rereadWarnings = writeDocument(reread, (dir / "reread.obj").string());
    CHECK(rereadWarnings.size() == keptWarnings.size());
    CHECK(anyContains(rereadWarnings, "vn lines are left out") == !consistent);
    const std::string out = slurp(dir / "reread.obj");
    CHECK(out == slurp(dir / "kept.obj"));
    // What changed, and only that.
    std::string expected = kText;
    expected.replace(expected.find("v 1 0 0 0 1 0"), 13, "v 1 0 0.25 0 1 0");
    expected.replace(expected.find("v 1 1 0 0 0 1"), 13, "v 1 1 0 0.125 0.5 1");
    expected.replace(expected.find("v 3 0 0 0.25 0.25 0.25"), 22, "v 3 0.5 -0.125 0.25 0.25 0.25");
    if (consistent) {
      expected.replace(expected.find("vn 0 0 1"), 8, "vn 0 0.6 0.8");
    } else {
      expected.replace(expected.find("vn 0 0 1\r\n"), 10, "");
      expected.replace(expected.find("vn 0 0 1\r\n"), 10, "");
      expected.replace(expected.find("f 1/1/1 2/2/1 3/3/1 4/1/1"), 25, "f 1/1 2/2 3/3 4/1");
      expected.replace(expected.find("f 5/1/2 6/2/2 7/3/2"), 19, "f 5/1 6/2 7/3");
      expected.replace(expected.find("f 5/1/2 7/3/2 8/2/2"), 19, "f 5/1 7/3 8/2");
    }
    CHECK(out == expected);
  }
}

TEST_CASE("OBJ without its text kept: a source changed or gone since it was read writes nothing", "[io][obj]") {
  const fs::path dir = tempDir("io-obj-source-changed");
  const std::string a = (dir / "a.obj").string(), out = (dir / "out.obj").string();
  const auto check = [&](const std::string& why, const std::function<void()>& change) {
    INFO(why);
    spit(a, kText);
    Document doc = readDocument(a, withoutText());
    doc.parts[0].positions[0] = Vec3(0.5, 0.5, 0.5);
    change();
    const std::string message = errorOf([&] { writeDocument(doc, out); });
    CHECK_THAT(message, Contains(a + ": ") && Contains("since it was read") && Contains("nothing written to " + out));
    CHECK(!fs::exists(out));
    // Not even a temporary beside it.
    for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().filename() == "a.obj");
  };
  check("same size, one digit changed", [&] {
    std::string t = kText;
    t[t.find("v 2 0 0") + 2] = '4';
    spit(a, t);
  });
  check("a line added", [&] { spit(a, kText + "\r\n# more\r\n"); });
  check("emptied", [&] { spit(a, ""); });
  check("deleted", [&] { fs::remove(a); });
  check("replaced by a directory", [&] {
    fs::remove(a);
    fs::create_directory(a);
  });
  fs::remove_all(a);
  // The text kept: the source is not read again, so a change to it does not matter.
  spit(a, kText);
  Document kept = readDocument(a);
  fs::remove(a);
  writeDocument(kept, out);
  CHECK(slurp(out) == kText);
}

TEST_CASE("OBJ without its text kept writes back in place", "[io][obj]") {
  const fs::path dir = tempDir("io-obj-source-in-place");
  const std::string a = (dir / "a.obj").string();
  spit(a, kText);
  Document kept = readDocument(a);
  edit(kept, true);
  writeDocument(kept, (dir / "expected.obj").string());

  Document doc = readDocument(a, withoutText());
  edit(doc, true);
  writeDocument(doc, a);
  CHECK(slurp(a) == slurp(dir / "expected.obj"));
  CHECK(slurp(a) != kText);
  // The document now describes a file that has changed: a second write refuses.
  CHECK_THAT(errorOf([&] { writeDocument(doc, a); }), Contains("changed since it was read"));
  CHECK(slurp(a) == slurp(dir / "expected.obj"));
}
