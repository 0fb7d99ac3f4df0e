// eval/compare.hpp: the comparison of two denoise_eval runs (docs/denoising.md#comparing-two-runs).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "compare.hpp"
#include "geoshift/error.hpp"

using namespace geoshift;
using namespace geoshift::eval;

namespace {

// W⁺'s mean and variance over every assignment of signs to |d| (each equally likely under the
// null hypothesis), the ranks taken as signedRankTest takes them: a brute-force reference.
std::pair<double, double> exactMoments(const std::vector<double>& magnitudes) {
  const int n = static_cast<int>(magnitudes.size());
  double sum = 0, sumSquares = 0;
  const int count = 1 << n;
  for (int signs = 0; signs < count; ++signs) {
    std::vector<double> d;
    for (int i = 0; i < n; ++i) d.push_back((signs >> i & 1) ? magnitudes[i] : -magnitudes[i]);
    const double w = signedRankTest(d).wPlus;
    sum += w;
    sumSquares += w * w;
  }
  const double mean = sum / count;
  return {mean, sumSquares / count - mean * mean};
}

CaseFigures figures(std::string set, std::string mesh, std::uint64_t seed, double rms, double angle, double bestRms,
                    double bestAngle) {
  return {std::move(set), std::move(mesh), "fixed 0.5 AEL random dir.", seed, rms, angle, bestRms, bestAngle};
}

}  // namespace

TEST_CASE("the signed-rank statistic's null mean and variance match an enumeration of the signs, ties included",
          "[eval][compare]") {
  for (const std::vector<double>& m : {std::vector<double>{0.3, 1.2, 0.7, 2.5, 0.1, 1.9},
                                       std::vector<double>{0.5, 0.5, 0.5, 1.0, 2.0, 2.0, 3.0},
                                       std::vector<double>{1, 1, 1, 1, 1, 1, 1, 1}}) {
    const auto [mean, variance] = exactMoments(m);
    const SignedRank t = signedRankTest(m);
    CHECK(t.mean == Approx(mean).margin(1e-9));
    CHECK(t.variance == Approx(variance).margin(1e-9));
  }
}

TEST_CASE("the signed-rank test: a hand-worked case, a clear shift, a symmetric set and zeros", "[eval][compare]") {
  // d = (1, -2, 3, 4, -5): ranks 1..5, W⁺ = 1 + 3 + 4 = 8, mean 7.5, variance 5·6·11/24 = 13.75.
  const SignedRank a = signedRankTest({1, -2, 3, 4, -5});
  CHECK(a.n == 5);
  CHECK(a.positive == 3);
  CHECK(a.negative == 2);
  CHECK(a.wPlus == 8);
  CHECK(a.variance == Approx(13.75));
  CHECK(a.z == Approx(0.5 / std::sqrt(13.75)));
  CHECK(a.p == Approx(std::erfc(a.z / std::sqrt(2.0))));

  std::vector<double> up;
  for (int i = 1; i <= 20; ++i) up.push_back(0.01 * i);
  const SignedRank b = signedRankTest(up);
  CHECK(b.wPlus == 210);
  CHECK(b.z > 3.9);
  CHECK(b.p < 1e-4);
  for (double& x : up) x = -x;
  CHECK(signedRankTest(up).z == Approx(-b.z));

  const SignedRank c = signedRankTest({-0.2, 0.2, -0.7, 0.7, 0, 0, 0});
  CHECK(c.zeros == 3);
  CHECK(c.n == 4);
  CHECK(c.z == Approx(0).margin(1e-12));
  CHECK(c.p == Approx(1));

  const SignedRank none = signedRankTest({0, 0});
  CHECK(none.n == 0);
  CHECK(none.p == 1);
}

TEST_CASE("the verdict is the scoreboard's: figures compared as printed", "[eval][compare]") {
  // 0.1234 prints as 0.123, at the oracle's 0.1231; 4.004° prints as 4.00.
  CHECK(won(figures("tuning", "A", 1, 0.1234, 4.004, 0.1231, 4.0)));
  CHECK_FALSE(won(figures("tuning", "A", 1, 0.1236, 4.0, 0.1231, 4.0)));
  CHECK_FALSE(won(figures("tuning", "A", 1, 0.1, 4.01, 0.2, 4.0)));
  CHECK(ratio(figures("tuning", "A", 1, 0.2, 4.0, 0.1, 4.0)) == Approx(2.0));
  CHECK(ratio(figures("tuning", "A", 1, 0.1, 6.0, 0.2, 4.0)) == Approx(1.5));
}

TEST_CASE("results written and read back are the same figures, to the last bit", "[eval][compare]") {
  const std::vector<CaseFigures> cases = {figures("tuning", "(2, 5) knot tube (procedural)", 1, 0.1 / 3, 1.0 / 7, 0.05, 2.5),
                                          figures("validation", "Boot", 8, 0.115, 14.34, 0.118, 14.23)};
  std::stringstream file;
  writeResults(file, cases);
  const std::vector<CaseFigures> back = readResults(file, "r.tsv");
  REQUIRE(back.size() == 2);
  for (size_t i = 0; i < 2; ++i) {
    CHECK(back[i].set == cases[i].set);
    CHECK(back[i].mesh == cases[i].mesh);
    CHECK(back[i].noise == cases[i].noise);
    CHECK(back[i].seed == cases[i].seed);
    CHECK(back[i].rms == cases[i].rms);
    CHECK(back[i].angle == cases[i].angle);
    CHECK(back[i].bestRms == cases[i].bestRms);
    CHECK(back[i].bestAngle == cases[i].bestAngle);
  }
}

TEST_CASE("a bad results file is refused with its name and line", "[eval][compare]") {
  auto refuses = [](const std::string& text, const std::string& message) {
    std::stringstream in(text);
    try {
      readResults(in, "r.tsv");
      FAIL("accepted: " << text);
    } catch (const InputError& e) {
      CHECK_THAT(e.what(), Catch::Contains(message));
    }
  };
  const std::string head = "# denoise_eval results 1\nset\tmesh\tnoise\tseed\trms\tangle\tbest_rms\tbest_angle\n";
  refuses("", "r.tsv: no header");
  refuses("| case | noise |\n", "not a results file of denoise_eval --results");
  refuses("# denoise_eval results 1\n", "r.tsv: no header");
  refuses("# denoise_eval results 1\nset\tmesh\n", "r.tsv line 2: expected the header");
  refuses(head + "tuning\tA\tn\t1\t0.1\t2\t0.1\n", "r.tsv line 3: expected 8 tab-separated fields, found 7");
  refuses(head + "tuning\tA\tn\t1\t0.1x\t2\t0.1\t2\n", "r.tsv line 3: '0.1x' in column rms is not a finite number");
  refuses(head + "tuning\tA\tn\t1\t0.1\tnan\t0.1\t2\n", "'nan' in column angle");
  refuses(head + "tuning\tA\tn\t1.5\t0.1\t2\t0.1\t2\n", "r.tsv line 3: the seed '1.5' is not a whole number");
  refuses(head + "tuning\tA\tn\t1\t0.1\t2\t0.1\t2\n\ntuning\tA\tn\t1\t0.2\t2\t0.1\t2\n", "r.tsv line 5: A, n at seed 1 appears twice");
}

TEST_CASE("two runs compared: verdicts that changed, counts per seed and the direction of the changes",
          "[eval][compare]") {
  std::vector<CaseFigures> before, after;
  // Twelve tuning cases at seeds 1 and 2: after lowers both numbers by 1-12% on each, and so wins
  // A (tied with its oracle) where before lost it; B goes the other way at seed 1 only.
  for (int i = 0; i < 12; ++i) {
    const std::string mesh = i == 0 ? "A" : i == 1 ? "B" : "M" + std::to_string(i);
    for (std::uint64_t seed : {1, 2}) {
      const double shrink = 1 - 0.01 * (i + 1);
      if (i == 0) {
        before.push_back(figures("tuning", mesh, seed, 0.110, 5.0, 0.100, 5.0));
        after.push_back(figures("tuning", mesh, seed, 0.100, 4.5, 0.100, 5.0));
      } else if (i == 1) {
        before.push_back(figures("tuning", mesh, seed, 0.090, 4.0, 0.100, 5.0));
        after.push_back(figures("tuning", mesh, seed, seed == 1 ? 0.101 : 0.089, 3.9, 0.100, 5.0));
      } else {
        before.push_back(figures("tuning", mesh, seed, 0.2, 6.0, 0.1, 5.0));
        after.push_back(figures("tuning", mesh, seed, 0.2 * shrink, 6.0 * shrink, 0.1, 5.0));
      }
    }
  }
  // A validation case in one run only.
  before.push_back(figures("validation", "Lonely", 1, 0.1, 4.0, 0.1, 4.0));
  const std::string report = compareResults(before, after);
  INFO(report);
  CHECK_THAT(report, Catch::Contains("## tuning: 12 cases in both runs"));
  CHECK_THAT(report, Catch::Contains("| won at probe seed 1 | 1 | 1 |"));
  CHECK_THAT(report, Catch::Contains("| won at probe seed 2 | 1 | 2 |"));
  CHECK_THAT(report, Catch::Contains("Won before and lost after (seed 1): B, fixed 0.5 AEL random dir. (ratio 0.90 → 1.01)."));
  CHECK_THAT(report, Catch::Contains("Lost before and won after (seed 1): A, fixed 0.5 AEL random dir. (ratio 1.10 → 1.00)."));
  CHECK_THAT(report, Catch::Contains("averaged over the 2 shared probe seeds"));
  // Normal error is lower after on all twelve; RMS on eleven (B's mean change over its seeds is up).
  CHECK_THAT(report, Catch::Contains("| normal error | 12 | 0 | 0 | -3.06 | 0.002 |"));
  CHECK_THAT(report, Catch::Contains("| RMS | 11 | 1 | 0 |"));
  CHECK_THAT(report, Catch::Contains("## validation: 0 cases in both runs"));
  CHECK_THAT(report, Catch::Contains("Lonely, fixed 0.5 AEL random dir. (before)"));
  CHECK_THAT(report, Catch::Contains("No case at a probe seed both runs share."));
}

TEST_CASE("cases of several noise realizations keep apart, and compare counts each realization", "[eval][compare]") {
  const std::string label = "fixed 0.5 AEL random dir.";
  CHECK(withNoiseSeed(label, 1) == label);  // the scoreboard's realization: labels as before
  CHECK(withNoiseSeed(label, 3) == "fixed 0.5 AEL random dir. (noise seed 3)");
  for (std::uint64_t seed : {1, 2, 3, 17, 1000})
    CHECK(noiseSeedOf(withNoiseSeed(label, seed)) == seed);
  CHECK(noiseSeedOf("uniform [0, 0.5] AEL random dir.") == 1);
  CHECK(noiseSeedOf("(noise seed )") == 1);
  CHECK(noiseSeedOf("odd (noise seed x2)") == 1);
  // One mesh at noise seeds 1 and 2, and a pair (its own noise, so noise seed 1): after wins the
  // mesh's noise seed 2 case only.
  const std::vector<CaseFigures> before = {
      {"tuning", "M", label, 1, 0.11, 5.0, 0.10, 5.0},
      {"tuning", "M", withNoiseSeed(label, 2), 1, 0.11, 5.0, 0.10, 5.0},
      {"tuning", "Pair", "its own", 1, 0.09, 4.0, 0.10, 5.0}};
  std::vector<CaseFigures> after = before;
  after[1].rms = 0.10;
  const std::string report = compareResults(before, after);
  INFO(report);
  CHECK_THAT(report, Catch::Contains("## tuning: 3 cases in both runs"));
  CHECK_THAT(report, Catch::Contains("| won at probe seed 1 | 1 | 2 |"));
  CHECK_THAT(report, Catch::Contains("| won at noise seed 1 (of 2, probe seed 1) | 1 | 1 |"));
  CHECK_THAT(report, Catch::Contains("| won at noise seed 2 (of 1, probe seed 1) | 0 | 1 |"));
  // One realization alone: no rows per noise seed.
  CHECK_THAT(compareResults({before[0]}, {after[0]}), !Catch::Contains("noise seed"));
}

TEST_CASE("group means: one per group, in the groups' order", "[eval][compare]") {
  const std::vector<double> m = groupMeans({"b", "a", "b", "c", "a", "b"}, {1, 2, 3, 4, 6, 5});
  REQUIRE(m.size() == 3);
  CHECK(m[0] == Approx(4.0));  // a: 2, 6
  CHECK(m[1] == Approx(3.0));  // b: 1, 3, 5
  CHECK(m[2] == Approx(4.0));  // c
  CHECK(groupMeans({}, {}).empty());
  CHECK_THROWS_AS(groupMeans({"a"}, {1, 2}), std::invalid_argument);
}

TEST_CASE("one mesh that moves with every noise counts once in the test over meshes", "[eval][compare]") {
  // Mesh Big has eight noises, each 10% lower after; six other meshes one noise each, 1% higher.
  // Over the 14 cases the eight large drops dominate (W⁺ = 6 × 3.5 = 21 against a mean of 52.5:
  // z −2.04); over the 7 meshes Big is one drop against six rises (W⁺ = 21 against 14: z +1.26).
  std::vector<CaseFigures> before, after;
  for (int i = 0; i < 8; ++i) {
    const std::string noise = "noise " + std::to_string(i);
    before.push_back({"tuning", "Big", noise, 1, 0.2, 6.0, 0.1, 5.0});
    after.push_back({"tuning", "Big", noise, 1, 0.2 * 0.9, 6.0 * 0.9, 0.1, 5.0});
  }
  for (int i = 0; i < 6; ++i) {
    const std::string mesh = "Small " + std::to_string(i);
    before.push_back(figures("tuning", mesh, 1, 0.2, 6.0, 0.1, 5.0));
    after.push_back(figures("tuning", mesh, 1, 0.2 * 1.01, 6.0 * 1.01, 0.1, 5.0));
  }
  const std::string report = compareResults(before, after);
  INFO(report);
  CHECK_THAT(report, Catch::Contains("| RMS | 8 | 6 | 0 | -2.04 | 0.042 |"));
  CHECK_THAT(report, Catch::Contains("The same test over the 7 meshes"));
  CHECK_THAT(report, Catch::Contains("| RMS | 1 | 6 | 0 | 1.26 | 0.206 |"));
  CHECK_THAT(report, Catch::Contains("| normal error | 1 | 6 | 0 | 1.26 | 0.206 |"));
}

TEST_CASE("the bootstrap over families: a share whose wins sit in whole families is less certain", "[eval][compare]") {
  // Ten families of four cases, half the cases won either way: in whole families (five won, five
  // lost) the share moves with which families are drawn; spread evenly (two of four in each) it
  // cannot move at all.
  std::vector<std::string> groups;
  std::vector<bool> whole, even;
  for (int f = 0; f < 10; ++f)
    for (int c = 0; c < 4; ++c) {
      groups.push_back("family " + std::to_string(f));
      whole.push_back(f < 5);
      even.push_back(c < 2);
    }
  const ShareInterval a = groupBootstrapShare(groups, whole), b = groupBootstrapShare(groups, even);
  CHECK(a.groups == 10);
  CHECK(a.share == 0.5);
  CHECK(a.low < 0.25);
  CHECK(a.high > 0.75);
  CHECK(b.share == 0.5);
  CHECK(b.low == 0.5);
  CHECK(b.high == 0.5);
  // All won: nothing to move.
  const ShareInterval all = groupBootstrapShare(groups, std::vector<bool>(groups.size(), true));
  CHECK(all.low == 1.0);
  CHECK(all.high == 1.0);
  // The same seed, the same interval; another seed, nearly the same.
  const ShareInterval again = groupBootstrapShare(groups, whole);
  CHECK(again.low == a.low);
  CHECK(again.high == a.high);
  CHECK(groupBootstrapShare({}, {}).groups == 0);
  CHECK_THROWS_AS(groupBootstrapShare({"a"}, {true, false}), std::invalid_argument);
  CHECK_THROWS_AS(groupBootstrapShare({"a"}, {true}, 0), std::invalid_argument);
}

TEST_CASE("the bootstrap over families matches the exact distribution of every draw", "[eval][compare]") {
  // Four families (cases, won): (3, 3), (2, 0), (4, 1), (1, 1). Every one of the 4^4 ordered draws is
  // equally likely; the share of each is the brute-force reference for the resampled shares.
  const std::vector<std::pair<int, int>> family = {{3, 3}, {2, 0}, {4, 1}, {1, 1}};
  std::vector<std::string> groups;
  std::vector<bool> won;
  for (size_t f = 0; f < family.size(); ++f)
    for (int c = 0; c < family[f].first; ++c) {
      groups.push_back(std::string(1, static_cast<char>('a' + f)));
      won.push_back(c < family[f].second);
    }
  std::vector<double> exact;
  for (int d = 0; d < 256; ++d) {
    int cases = 0, w = 0;
    for (int k = 0; k < 4; ++k) {
      const auto& [c, gw] = family[(d >> (2 * k)) & 3];
      cases += c;
      w += gw;
    }
    exact.push_back(static_cast<double>(w) / cases);
  }
  std::sort(exact.begin(), exact.end());
  // The exact quantiles: the smallest share whose probability of a share at or below it reaches q.
  auto quantile = [&](double q) {
    for (size_t i = 0; i < exact.size(); ++i) {
      const size_t last = std::upper_bound(exact.begin(), exact.end(), exact[i]) - exact.begin();
      const double cdf = static_cast<double>(last) / exact.size();
      if (cdf >= q) {
        // Far enough from the jump that 200,000 resamples cannot land on its other side.
        REQUIRE(std::abs(cdf - q) > 0.003);
        REQUIRE(std::abs(static_cast<double>(i) / exact.size() - q) > 0.003);
        return exact[i];
      }
    }
    return exact.back();
  };
  const ShareInterval r = groupBootstrapShare(groups, won, 200000, 7);
  CHECK(r.share == Approx(5.0 / 10));
  CHECK(r.low == Approx(quantile(0.025)));
  CHECK(r.high == Approx(quantile(0.975)));
}
