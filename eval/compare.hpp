// Two runs of denoise_eval compared case by case (docs/denoising.md#comparing-two-runs): which cases
// changed verdict, how the ratios moved, and whether the figures moved one way more than chance
// would (a paired signed-rank test over the cases), so that a change is judged on more than a count
// of cases won.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace geoshift::eval {

// One case at one probe seed, as denoise_eval --results writes it: the default's figures and the
// better oracle's in each number (RMS ×10², mean normal error in degrees).
struct CaseFigures {
  std::string set, mesh, noise;
  std::uint64_t seed = 1;
  double rms = 0, angle = 0;          // ours
  double bestRms = 0, bestAngle = 0;  // the better of tuned Taubin and the tuned bilateral filter, each number
};

// The verdict as the scoreboard gives it, the one place it is written: figures compared as printed
// (RMS to 3 decimals, angles to 2), won when both are at or below the better oracle's; each
// number's ratio is ours / it, and the case's ratio the larger of the two.
double printed(double x, int digits);
struct Verdict {
  bool win = false;
  double ratio = 0, rmsRatio = 0, angleRatio = 0;
};
Verdict verdictOf(const CaseFigures& c);
inline bool won(const CaseFigures& c) { return verdictOf(c).win; }
inline double ratio(const CaseFigures& c) { return verdictOf(c).ratio; }

// The noise label of a case at another realization of the synthetic noises (denoise_eval
// --noise-seed): "<label> (noise seed N)", so that cases of several realizations stay apart in one
// run and in --compare; the scoreboard's realization, 1, keeps its label, so that its results compare
// with those of runs before the suffix. noiseSeedOf reads it back (1 without the suffix).
std::string withNoiseSeed(const std::string& label, std::uint64_t noiseSeed);
std::uint64_t noiseSeedOf(const std::string& label);

// Tab-separated, one case and seed a line, after a header; numbers with 17 significant digits.
void writeResults(std::ostream& out, const std::vector<CaseFigures>& cases);
// Reads what writeResults wrote; `name` (the file's) goes into the InputError a bad line raises,
// with its line number.
std::vector<CaseFigures> readResults(std::istream& in, const std::string& name);

// Wilcoxon's signed-rank test of paired differences: zeros dropped (|d| ≤ 1e-12), the rest ranked by
// |d| with ties given their mean rank, W⁺ the sum of the positive ranks. z is W⁺'s distance from its
// mean n(n + 1)/4 over its standard deviation under the null hypothesis of a symmetric distribution
// about zero (variance n(n + 1)(2n + 1)/24 less Σ(t³ − t)/48 over groups of t tied ranks), p the
// two-sided normal probability of a |z| at least as large; fine from n ≈ 10 on.
struct SignedRank {
  int n = 0, positive = 0, negative = 0, zeros = 0;
  double wPlus = 0, mean = 0, variance = 0, z = 0, p = 1;
};
SignedRank signedRankTest(const std::vector<double>& differences);

// One mean per group: values[i] belongs to groups[i] (the same length); the means in the groups'
// sorted order. Cases of one mesh share its shape, so a test over cases counts a mesh that moves
// with every noise four times; over mesh means, once.
std::vector<double> groupMeans(const std::vector<std::string>& groups, const std::vector<double>& values);

// How far a share of cases won could move with the meshes in the set: a percentile bootstrap over
// groups (families), each resample drawing as many groups as there are, with replacement, and
// counting the cases of the drawn groups (docs/denoising.md#the-evaluation). Cases of one family share
// a shape and move together, so resampling cases alone would read the share as more precise than
// it is. `resamples` draws from a fixed seed (splitmix64): the same interval on every machine.
struct ShareInterval {
  double share = 0, low = 0, high = 0;  // the share won, and the central 95% of the resampled shares
  int groups = 0;
};
ShareInterval groupBootstrapShare(const std::vector<std::string>& groups, const std::vector<bool>& won,
                                  int resamples = 10000, std::uint64_t seed = 1);

// The comparison of `after` against `before`, per set, over the (set, mesh, noise) cases both hold,
// as Markdown: cases won at each seed the two share (and, where the cases hold more than one noise
// realization, at each noise seed), the cases whose verdict changed at the first,
// the geometric mean ratios, and for RMS and normal error the cases that moved each way with the
// signed-rank test of log(after / before), each case's change averaged over the shared seeds; then
// the same test over each mesh's mean change (groupMeans).
std::string compareResults(const std::vector<CaseFigures>& before, const std::vector<CaseFigures>& after);

}  // namespace geoshift::eval
