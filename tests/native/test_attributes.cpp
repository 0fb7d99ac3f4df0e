// Named per-vertex attribute channels.
#include <catch2/catch.hpp>

#include <cmath>

#include "geoshift/attributes.hpp"
#include "geoshift/error.hpp"

using namespace geoshift;

TEST_CASE("set, find, get, replace and remove", "[attributes]") {
  AttributeSet set(3);
  CHECK(set.vertexCount() == 3);
  Attribute& h = set.set("height", 1, AttributeKind::Euclidean, {1, 2, 3});
  CHECK(h.vertexCount() == 3);
  CHECK(h.row(2)[0] == 3);
  set.set("color", 3, AttributeKind::Euclidean, std::vector<double>(9, 0.5));
  CHECK(set.size() == 2);
  CHECK(set.contains("height"));
  CHECK_FALSE(set.contains("Height"));
  CHECK(set.find("missing") == nullptr);
  CHECK(set.get("color").dim == 3);
  CHECK(set.names() == std::vector<std::string>{"height", "color"});

  set.set("height", 1, AttributeKind::Euclidean, {7, 8, 9});  // replaces in place, keeps order
  CHECK(set.size() == 2);
  CHECK(set.get("height").values == std::vector<double>{7, 8, 9});
  set.find("height")->values[0] = -1;
  CHECK(set.get("height").values[0] == -1);

  CHECK(set.remove("height"));
  CHECK_FALSE(set.remove("height"));
  CHECK(set.names() == std::vector<std::string>{"color"});
}

TEST_CASE("get names the missing attribute and the ones present", "[attributes]") {
  AttributeSet set(1);
  set.set("normal", 3, AttributeKind::UnitVector, {0, 0, 2});
  CHECK_THROWS_AS(set.get("curvature"), InputError);
  CHECK_THROWS_WITH(set.get("curvature"),
                    Catch::Contains("curvature") && Catch::Contains("normal"));
}

TEST_CASE("size checks throw with messages naming the attribute", "[attributes]") {
  AttributeSet set(4);
  CHECK_THROWS_WITH(set.set("color", 3, AttributeKind::Euclidean, std::vector<double>(11)),
                    Catch::Contains("color") && Catch::Contains("11") && Catch::Contains("12"));
  CHECK_THROWS_AS(set.set("x", 0, AttributeKind::Euclidean, {}), InputError);
  CHECK_THROWS_WITH(set.set("x", 0, AttributeKind::Euclidean, {}), Catch::Contains("'x'"));
  CHECK_THROWS_AS(set.set("", 1, AttributeKind::Euclidean, std::vector<double>(4)), InputError);
  CHECK(set.size() == 0);  // nothing half-added
}

TEST_CASE("unit vectors are normalised; zero or non-finite rows are rejected", "[attributes]") {
  AttributeSet set(2);
  const Attribute& n = set.set("normal", 3, AttributeKind::UnitVector, {3, 0, 4, 0, -2, 0});
  CHECK(n.values[0] == Approx(0.6));
  CHECK(n.values[2] == Approx(0.8));
  CHECK(n.values[4] == -1.0);
  CHECK_THROWS_WITH(set.set("bad", 3, AttributeKind::UnitVector, {1, 0, 0, 0, 0, 0}),
                    Catch::Contains("bad") && Catch::Contains("vertex 1"));
  CHECK_THROWS_WITH(set.set("bad", 3, AttributeKind::UnitVector, {NAN, 0, 0, 1, 0, 0}),
                    Catch::Contains("vertex 0"));
  CHECK_FALSE(set.contains("bad"));
  // Euclidean rows are stored as given.
  set.set("offset", 3, AttributeKind::Euclidean, {3, 0, 4, 0, 0, 0});
  CHECK(set.get("offset").values[0] == 3);
}
