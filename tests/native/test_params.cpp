// The parameter tables (params.hpp), the denoise request (denoise_request.hpp) and the check
// vocabulary (check.hpp): what every front end shares.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "geoshift/check.hpp"
#include "geoshift/denoise_request.hpp"
#include "geoshift/error.hpp"
#include "geoshift/params.hpp"
#include "geoshift/requests.hpp"

using namespace geoshift;
using Catch::Matchers::Contains;
using Catch::Matchers::Equals;

namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string refusal(const std::string& op, ParamValues values) {
  return errorOf([&] { ParamRequest(paramSpecsOf(op), std::move(values)); });
}

}  // namespace

TEST_CASE("numbers in messages read as given, not as std::to_string prints them", "[params]") {
  CHECK(formatNumber(1e-7) == "1e-07");
  CHECK(formatNumber(0.35) == "0.35");
  CHECK(formatNumber(3) == "3");
  CHECK(formatNumber(-0.53) == "-0.53");
  CHECK(formatNumber(1.7976931348623157e308) == "1.7976931348623157e+308");
  CHECK(formatNumber(9007199254740991.0) == "9007199254740991");
  CHECK(formatNumber(2e6) == "2e+06");  // std::to_chars: the shorter form
  CHECK(formatNumber(std::nan("")) == "nan");
  CHECK(formatNumber(-std::numeric_limits<double>::infinity()) == "-inf");
  // Every digit that matters is kept: the text reads back as the same double.
  for (double x : {0.1, 1.0 / 3, 123456.789, 2.5e-300, 6.02214076e23, 0.1 + 0.2})
    CHECK(std::stod(formatNumber(x)) == x);
}

TEST_CASE("the check vocabulary names what it checks and the value as given", "[params]") {
  CHECK_THAT(errorOf([] { requirePositive("--hr", -1e-7); }), Equals("--hr must be > 0 (got -1e-07)"));
  CHECK_THAT(errorOf([] { requirePositive("h_s", std::nan("")); }), Equals("h_s must be > 0 (got nan)"));
  CHECK_THAT(errorOf([] { requireRange("amount", -1, 0, 100); }), Equals("amount is outside [0, 100] (got -1)"));
  CHECK_THAT(errorOf([] { requireRange("hs", 2e6, 0, 1e6, true); }), Equals("hs is outside (0, 1e+06] (got 2e+06)"));
  CHECK_THAT(errorOf([] { requireRange("k", -1, 0, std::numeric_limits<double>::infinity()); }), Equals("k must be >= 0 (got -1)"));
  CHECK_THAT(errorOf([] { requireAtLeast("passes", 0, 1); }), Equals("passes must be >= 1 (got 0)"));
  CHECK_THAT(errorOf([] { requireFinite("x", std::numeric_limits<double>::infinity()); }), Equals("x must be a finite number (got inf)"));
  CHECK_THAT(errorOf([] { requireIndex("source", 12, 10); }), Equals("source is outside [0, 9] (got 12)"));
  CHECK_THAT(errorOf([] { requireIndex("source", 0, 0); }), Contains("there are none"));
  CHECK(errorOf([] { requireRange("x", 0, 0, 1); }).empty());
  CHECK(errorOf([] { requireIndex("i", 9, 10); }).empty());
  CHECK(positiveProblem(1e-300).empty());
}

TEST_CASE("every table is well formed: conditions refer to earlier enum parameters, defaults obey their ranges",
          "[params]") {
  for (const OpParamSpecs& op : paramSpecs()) {
    INFO(op.op);
    CHECK_FALSE(op.doc.empty());
    std::vector<std::string> seen;
    auto checkCondition = [&](const ParamCondition& c) {
      for (const auto& [name, values] : c) {
        INFO(name);
        REQUIRE(std::find(seen.begin(), seen.end(), name) != seen.end());
        const ParamSpec& ref = paramSpec(op, name);
        CHECK(ref.type == ParamType::Enum);
        for (const std::string& v : values) CHECK(std::find(ref.values.begin(), ref.values.end(), v) != ref.values.end());
      }
    };
    for (const ParamSpec& s : op.params) {
      INFO(s.name);
      CHECK_FALSE(s.doc.empty());
      CHECK(std::find(seen.begin(), seen.end(), s.name) == seen.end());
      for (const ParamCondition& c : s.appliesWhen) checkCondition(c);
      for (const ParamCase& c : s.cases) checkCondition(c.when);
      CHECK((s.type == ParamType::Enum) == !s.values.empty());
      seen.push_back(s.name);
    }
    // With nothing given every default is valid and readable.
    const ParamRequest none(op, {});
    for (const ParamSpec& s : op.params) {
      INFO(s.name);
      const std::optional<ParamValue> d = defaultOf(s, none);
      if (!d) continue;
      ParamValues given = {{s.name, *d}};
      // A parameter that applies only elsewhere is tried where its first condition holds.
      if (!s.appliesWhen.empty())
        for (const auto& [name, values] : s.appliesWhen.front()) given.insert(given.begin(), {name, values.front()});
      CHECK(refusal(op.op, given).empty());
    }
  }
}

TEST_CASE("a request is checked in table order: the same values in any order give the same message", "[params]") {
  const std::string a = refusal("denoise", {{"hs", -1.0}, {"method", std::string("taubin")}, {"kmax", 2.5}});
  const std::string b = refusal("denoise", {{"kmax", 2.5}, {"method", std::string("taubin")}, {"hs", -1.0}});
  CHECK_THAT(a, Equals(b));
  CHECK_THAT(a, Equals("denoise: parameter hs belongs to method \"meanshift\"; hs does not apply to method \"taubin\""));
}

TEST_CASE("a request refuses what does not apply, naming what it belongs to", "[params]") {
  CHECK_THAT(refusal("denoise", {{"kmax", 20.0}}),
             Equals("denoise: parameter kmax belongs to preset \"paper\"; kmax does not apply to preset \"default\""));
  CHECK_THAT(refusal("denoise", {{"preset", std::string("paper")}, {"strength", 2.0}}),
             Equals("denoise: parameter strength belongs to preset \"default\"; strength does not apply to preset \"paper\""));
  CHECK_THAT(refusal("denoise", {{"method", std::string("taubin")}, {"vertexIterations", 3.0}}),
             Equals("denoise: parameter vertexIterations belongs to method \"meanshift\" or \"bilateral\"; vertexIterations does not "
                    "apply to method \"taubin\""));
  CHECK_THAT(refusal("denoise", {{"method", std::string("taubin")}, {"fixedBoundary", true}}),
             Equals("denoise: parameter fixedBoundary belongs to method \"meanshift\" with preset \"paper\" or to method "
                    "\"bilateral\"; fixedBoundary does not apply to method \"taubin\""));
  CHECK_THAT(refusal("denoise", {{"method", std::string("bilateral")}, {"preset", std::string("paper")}}),
             Contains("parameter preset belongs to method \"meanshift\""));
  CHECK_THAT(refusal("denoise", {{"sigma", 1.0}}), Contains("denoise: unknown parameter \"sigma\" (accepted: method, preset"));
}

TEST_CASE("a request refuses wrong types, fractions, choices and ranges with the vocabulary's words", "[params]") {
  CHECK_THAT(refusal("denoise", {{"radius", std::string("far")}}), Equals("denoise: parameter radius must be a number"));
  CHECK_THAT(refusal("denoise", {{"passes", 1.5}}), Equals("denoise: parameter passes must be a whole number (got 1.5)"));
  CHECK_THAT(refusal("denoise", {{"method", std::string("median")}}),
             Equals("denoise: parameter method = \"median\" is not one of meanshift, bilateral, taubin"));
  CHECK_THAT(refusal("denoise", {{"hs", -1e-7}}), Equals("denoise: parameter hs is outside (0, 1e+06] (got -1e-07)"));
  CHECK_THAT(refusal("denoise", {{"vertexIterations", 0.0}}),
             Equals("denoise: parameter vertexIterations is outside [1, 10000] (got 0)"));
  CHECK_THAT(refusal("denoise", {{"alpha", Unsupported{}}}), Equals("denoise: parameter alpha must be a number or a list of numbers"));
  CHECK_THAT(refusal("denoise", {{"presmoothing", std::vector<double>{3, -1}}}),
             Equals("denoise: parameter presmoothing is outside [0, 10000] (got -1)"));
  CHECK_THAT(refusal("filter", {{"segments", std::string("yes")}}), Equals("filter: parameter segments must be true or false"));
  // A case changes the range: passes 0 lets SURE choose in the default preset, the paper's needs one.
  CHECK(refusal("denoise", {{"passes", 0.0}}).empty());
  CHECK_THAT(refusal("denoise", {{"preset", std::string("paper")}, {"passes", 0.0}}),
             Equals("denoise: parameter passes is outside [1, 10000] (got 0)"));
  CHECK(refusal("denoise", {{"method", std::string("bilateral")}, {"vertexIterations", 0.0}}).empty());
}

TEST_CASE("a denoise request becomes the options of its method, with the options structs' own defaults", "[params]") {
  const DenoiseSettings none = denoiseSettings(ParamValues{});
  CHECK(none.method == DenoiseMethod::MeanShift);
  CHECK(none.meanShift.preset == DenoisePreset::Default);
  const DenoiseOptions d;
  CHECK(none.meanShift.neighborhood.spatialBandwidth == d.neighborhood.spatialBandwidth);
  CHECK(none.meanShift.vertexIterations == d.vertexIterations);

  const ParamRequest defaults(paramSpecsOf("denoise"), {});
  CHECK(defaults.number("hs") == d.neighborhood.spatialBandwidth);
  CHECK(defaults.numbers("hr") == d.rangeBandwidths);
  REQUIRE(d.rangeBandwidths.size() > 1);
  // hr 0 is "Auto" (the app's slider): the default candidates, as if hr were not given; a list is
  // taken as given; the paper preset takes one positive h_r.
  CHECK(denoiseSettings(ParamValues{{"hr", 0.0}}).meanShift.rangeBandwidths == d.rangeBandwidths);
  CHECK(denoiseSettings(ParamValues{{"hr", std::vector<double>{0.2, 0.6}}}).meanShift.rangeBandwidths ==
        std::vector<double>{0.2, 0.6});
  CHECK_THROWS_WITH(denoiseSettings(ParamValues{{"preset", std::string("paper")}, {"hr", 0.0}}),
                    Catch::Contains("hr must be > 0"));
  CHECK_THROWS_WITH(denoiseSettings(ParamValues{{"preset", std::string("paper")}, {"hr", std::vector<double>{0.3, 0.4}}}),
                    Catch::Contains("takes one value"));
  // taubinOnly 0 (alone) offers none; a list is taken as given (a 0 among others is the denoiser's
  // to refuse); impulse on/off force the outlier correction or turn it off, auto keeps the trigger.
  CHECK(defaults.numbers("taubinOnly") == std::vector<double>(d.taubinOnlySteps.begin(), d.taubinOnlySteps.end()));
  CHECK(none.meanShift.taubinOnlySteps == d.taubinOnlySteps);
  CHECK(denoiseSettings(ParamValues{{"taubinOnly", 0.0}}).meanShift.taubinOnlySteps.empty());
  CHECK(denoiseSettings(ParamValues{{"taubinOnly", std::vector<double>{10, 30}}}).meanShift.taubinOnlySteps ==
        std::vector<int>{10, 30});
  CHECK(denoiseSettings(ParamValues{{"taubinOnly", std::vector<double>{0, 5}}}).meanShift.taubinOnlySteps ==
        std::vector<int>{0, 5});
  // lightStart: the steps of the light start (docs/denoising.md#a-light-start), 0 turns it off.
  CHECK(defaults.integer("lightStart") == d.lightStart);
  CHECK(none.meanShift.lightStart == d.lightStart);
  CHECK(denoiseSettings(ParamValues{{"lightStart", 0.0}}).meanShift.lightStart == 0);
  CHECK(denoiseSettings(ParamValues{{"lightStart", 2.0}}).meanShift.lightStart == 2);
  CHECK_THAT(refusal("denoise", {{"lightStart", 1.5}}), Contains("lightStart"));
  CHECK_THAT(refusal("denoise", {{"preset", std::string("paper")}, {"lightStart", 0.0}}), Contains("lightStart"));
  CHECK(defaults.text("impulse") == "auto");
  for (const char* rule : {"auto", "on", "off"}) {
    const DenoiseOptions i = denoiseSettings(ParamValues{{"impulse", std::string(rule)}}).meanShift;
    INFO(rule);
    CHECK(i.impulseShrink == (std::string(rule) == "off" ? 0.0 : d.impulseShrink));
    CHECK(i.impulseKurtosis == (std::string(rule) == "on" ? 0.0 : d.impulseKurtosis));
  }
  CHECK_THAT(refusal("denoise", {{"impulse", std::string("always")}}),
             Equals("denoise: parameter impulse = \"always\" is not one of auto, on, off"));
  CHECK_THAT(refusal("denoise", {{"preset", std::string("paper")}, {"impulse", std::string("off")}}),
             Contains("impulse"));
  const ParamRequest paper(paramSpecsOf("denoise"), {{"preset", std::string("paper")}});
  CHECK(paper.number("hs") == d.paper.meanShift.spatialBandwidth);
  CHECK(paper.integer("passes") == d.paper.passes);
  CHECK(paper.integer("vertexIterations") == d.paper.vertexUpdate.iterations);

  const DenoiseSettings s = denoiseSettings(ParamValues{{"hs", 0.8},
                                                        {"hr", 0.3},
                                                        {"passes", 2.0},
                                                        {"presmoothing", std::vector<double>{1, 4}},
                                                        {"seed", 7.0},
                                                        {"levels", 2.0},
                                                        {"alpha", std::vector<double>{0.5, 0}}});
  CHECK(s.meanShift.neighborhood.spatialBandwidth == 0.8);
  CHECK(s.meanShift.rangeBandwidths == std::vector<double>{0.3});
  CHECK(s.meanShift.fixedPasses == 2);
  CHECK(s.meanShift.presmoothing == std::vector<int>{1, 4});
  CHECK(s.meanShift.seed == 7);
  CHECK(s.meanShift.levels == 2);
  CHECK(s.meanShift.alpha == std::vector<double>{0.5, 0});

  const DenoiseSettings p = denoiseSettings(ParamValues{{"preset", std::string("paper")},
                                                        {"hs", 2.0},
                                                        {"kmax", 20.0},
                                                        {"rangeUpdate", std::string("joint")},
                                                        {"faceNormals", std::string("mean")},
                                                        {"doubleWeights", true},
                                                        {"vertexIterations", 8.0},
                                                        {"flipGuard", std::string("input-or-target")}});
  CHECK(p.meanShift.preset == DenoisePreset::Paper);
  CHECK(p.meanShift.paper.meanShift.spatialBandwidth == 2);
  CHECK(p.meanShift.paper.meanShift.maxIterations == 20);
  CHECK(p.meanShift.paper.meanShift.rangeUpdate == RangeUpdate::Joint);
  CHECK(p.meanShift.paper.faceNormals == FaceNormalRule::Mean);
  CHECK_FALSE(p.meanShift.paper.meanShift.tuning.singlePrecisionKernel);
  CHECK(p.meanShift.paper.vertexUpdate.iterations == 8);
  CHECK(p.meanShift.paper.vertexUpdate.flipGuard == FlipGuard::InputOrTarget);

  const DenoiseSettings b = denoiseSettings(
      ParamValues{{"method", std::string("bilateral")}, {"sigmaS", 0.3}, {"neighbors", std::string("edge")}, {"vertexIterations", 5.0}});
  CHECK(b.method == DenoiseMethod::Bilateral);
  CHECK(b.bilateral.sigmaRange == 0.3);
  CHECK(b.bilateral.neighborhood == FaceNeighborhood::Edge);
  CHECK(b.bilateral.vertexUpdate.iterations == 5);

  const DenoiseSettings t = denoiseSettings(ParamValues{{"method", std::string("taubin")}, {"iterations", 4.0}, {"mu", -0.6}});
  CHECK(t.method == DenoiseMethod::Taubin);
  CHECK(t.taubin.iterations == 4);
  CHECK(t.taubin.mu == -0.6);
  CHECK(t.taubin.parallel.threads == 0);
  const DenoiseSettings t1 = denoiseSettings(ParamValues{{"method", std::string("taubin")}, {"threads", 1.0}});
  CHECK(t1.taubin.parallel.threads == 1);
  // The bilateral filter runs on one thread: a thread count is refused there, naming the methods it applies to.
  CHECK_THAT(refusal("denoise", {{"method", std::string("bilateral")}, {"threads", 2.0}}),
             Equals("denoise: parameter threads belongs to method \"meanshift\" or \"taubin\"; threads does not apply to "
                    "method \"bilateral\""));
}

TEST_CASE("a smooth request becomes TaubinOptions with their own defaults, threads included", "[params]") {
  const TaubinOptions d;
  const TaubinOptions o = smoothOptions(ParamRequest(paramSpecsOf("smooth"), {}));
  CHECK(o.iterations == d.iterations);
  CHECK(o.lambda == d.lambda);
  CHECK(o.mu == d.mu);
  CHECK(o.parallel.threads == d.parallel.threads);
  const TaubinOptions one = smoothOptions(ParamRequest(paramSpecsOf("smooth"), {{"threads", 1.0}, {"iterations", 3.0}}));
  CHECK(one.parallel.threads == 1);
  CHECK(one.iterations == 3);
  CHECK_THAT(refusal("smooth", {{"threads", -1.0}}), Equals("smooth: parameter threads is outside [0, 1024] (got -1)"));
}

TEST_CASE("the CLI spells a parameter in kebab-case unless the table says otherwise", "[params]") {
  const OpParamSpecs& d = paramSpecsOf("denoise");
  CHECK(cliOptionName(paramSpec(d, "vertexIterations")) == "--vertex-iterations");
  CHECK(cliOptionName(paramSpec(d, "hs")) == "--hs");
  CHECK(cliOptionName(paramSpec(d, "iterations")) == "--taubin-iterations");
  CHECK_THAT(errorOf([] { paramSpecsOf("sharpen"); }), Contains("unknown op \"sharpen\" (known: noise, smooth"));
}
