// denoise_eval: the denoising evaluation (docs/denoising.md#the-evaluation). Every clean mesh of the
// catalogue (eval/catalogue.cpp) gets four noises; the ground-truth pairs are evaluated as they are.
// Each case is scored for the noisy input, Taubin smoothing and the bilateral normal filter (both
// tuned per case against the truth: oracles), the default denoiser, and, on its pairs, GCN-Denoiser's
// published result. Cases are split into a tuning set and a validation set by family; the report
// gives each set on its own.
//   denoise_eval [--set tuning|validation|all] [--mesh SUBSTRING] [--seeds LIST] [--markdown FILE] ...
//   denoise_eval --compare BEFORE AFTER   (two files written by --results)
#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "catalogue.hpp"
#include "compare.hpp"
#include "geoshift/bilateral_normal.hpp"
#include "geoshift/denoise.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/io.hpp"
#include "geoshift/metrics.hpp"
#include "geoshift/noise.hpp"
#include "geoshift/shapes.hpp"
#include "geoshift/smoothing.hpp"

namespace fs = std::filesystem;
using namespace geoshift;
using namespace geoshift::eval;

namespace {

// One candidate the race computed, scored against the truth (--trace).
struct CandidateScore {
  int steps = 0, passes = 0;
  double rms = NAN, angle = NAN;
};

// One method's figures on one case.
struct Score {
  double rms = NAN, angle = NAN, ms = -1;  // RMS ×10², mean face-normal angle (°), wall clock
  std::string note;
  std::vector<CandidateScore> candidates;  // --trace: every candidate computed, before the impulse correction
  bool present() const { return std::isfinite(rms); }
};

Score scoreOf(const Case& c, std::vector<Vec3> positions, std::string note, double ms) {
  Mesh result = c.noisy;
  result.positions() = std::move(positions);
  return {100 * pointToSurface(result.positions(), c.clean).rms, meanNormalAngleError(result, c.clean), ms,
          std::move(note), {}};
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// --- the oracles: tuned against the truth per case ----------------------------------------------

// Taubin (MeshLab's λ = 0.5, μ = −0.53), one λ|μ pair at a time, keeping the step count of least RMS.
Score taubinTuned(const Case& c) {
  Mesh m = c.noisy;
  TaubinOptions one;
  one.iterations = 1;
  one.parallel.threads = 1;  // each method on one thread (--jobs runs cases side by side)
  int best = 0;
  double bestRms = pointToSurface(m.positions(), c.clean).rms;
  for (int step = 1; step <= 200; ++step) {
    taubinSmooth(m, one);
    const double rms = pointToSurface(m.positions(), c.clean).rms;
    if (rms < bestRms) {
      bestRms = rms;
      best = step;
    }
  }
  m = c.noisy;
  TaubinOptions o;
  o.iterations = best;
  o.parallel.threads = 1;
  const auto t0 = std::chrono::steady_clock::now();
  taubinSmooth(m, o);
  return scoreOf(c, m.positions(), "best of 0..200: " + std::to_string(best) + " steps", msSince(t0));
}

// The bilateral normal filter (Zheng et al. 2011), best RMS of σ_r × normal iterations.
Score bilateralTuned(const Case& c) {
  Score best;
  double bestRms = std::numeric_limits<double>::infinity();
  for (double sigma : {0.2, 0.35, 0.5}) {
    for (int iterations : {5, 10, 20, 40}) {
      Mesh m = c.noisy;
      BilateralNormalOptions o;
      o.sigmaRange = sigma;
      o.normalIterations = iterations;
      o.vertexUpdate.parallel.threads = 1;
      const auto t0 = std::chrono::steady_clock::now();
      bilateralNormalDenoise(m, o);
      const double ms = msSince(t0);
      const double rms = pointToSurface(m.positions(), c.clean).rms;
      if (rms < bestRms) {
        bestRms = rms;
        std::ostringstream note;
        note << "best of 12: σ_r " << sigma << ", " << iterations << " iterations";
        best = scoreOf(c, m.positions(), note.str(), ms);
      }
    }
  }
  return best;
}

// The oracles do not change with the denoiser: their scores are kept in a cache keyed by the case's
// bits and the oracle's name, so that re-running the evaluation costs only the denoiser.
struct OracleCache {
  fs::path dir;  // empty: no cache

  static std::string key(const Case& c, const std::string& method) {
    std::uint64_t h = fnv1a(method + "/v1");
    auto mix = [&](const void* p, size_t n) {
      const auto* b = static_cast<const unsigned char*>(p);
      for (size_t i = 0; i < n; ++i) {
        h ^= b[i];
        h *= 1099511628211ull;
      }
    };
    for (const Mesh* m : {&c.clean, &c.noisy}) {
      mix(m->positions().data(), m->positions().size() * sizeof(Vec3));
      mix(m->faces().data(), m->faces().size() * sizeof(Face));
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
  }

  Score get(const Case& c, const std::string& method, const std::function<Score(const Case&)>& run) const {
    const fs::path file = dir.empty() ? fs::path() : dir / (key(c, method) + ".txt");
    if (!file.empty() && fs::exists(file)) {
      std::ifstream in(file);
      Score s;
      in >> s.rms >> s.angle >> s.ms;
      std::getline(in >> std::ws, s.note);
      if (in || in.eof()) return s;
    }
    Score s = run(c);
    if (!file.empty()) {
      fs::create_directories(dir);
      const fs::path tmp = file.string() + ".tmp";
      std::ofstream(tmp) << std::setprecision(17) << s.rms << " " << s.angle << " " << s.ms << " " << s.note << "\n";
      fs::rename(tmp, file);
    }
    return s;
  }
};

// --- the denoiser under test ---------------------------------------------------------------------

// --strength, --presmoothing, ...: what-ifs of the default denoiser's options.
struct WhatIf {
  std::optional<double> strength, detailBoundRatio, levelLean, blendSpread, gradientRiskWeight, impulseSpectrumKurtosis, spectrumVeto, radius, spatialBandwidth, impulseShrink, impulseKurtosis, tieMargin, tieStandardErrors,
      taubinOnlyMargin, taubinOnlyMu, planarLevelShare, planarKeep, lightStartTurn;
  std::optional<std::vector<int>> taubinOnlySteps;
  std::optional<int> maxPasses, vertexIterations, patience, highMinSamples, impulseSpectrumMinSamples, fixedPasses, riskNormalSmoothing, probeSpacing, supportSteps,
      tieProbes, minPieceVertices, lightStart;
  std::optional<bool> refineNoise, highFrequencyLevel, halving, boundedDivergence, tieByNormals, inputCandidate,
      spatialOrder;
  bool trace = false, trueNoise = false;
  std::vector<double> range;
  std::vector<int> presmoothing;
  bool paper = false;

  void apply(DenoiseOptions& o) const {
    if (strength) o.strength = *strength;
    if (detailBoundRatio) o.detailBoundRatio = *detailBoundRatio;
    if (levelLean) o.levelLean = *levelLean;
    if (blendSpread) o.blendSpread = *blendSpread;
    if (minPieceVertices) o.minPieceVertices = *minPieceVertices;
    if (gradientRiskWeight) o.gradientRiskWeight = *gradientRiskWeight;
    if (impulseSpectrumKurtosis) o.impulseSpectrumKurtosis = *impulseSpectrumKurtosis;
    if (highFrequencyLevel) o.highFrequencyLevel = *highFrequencyLevel;
    if (impulseShrink) o.impulseShrink = *impulseShrink;
    if (impulseKurtosis) o.impulseKurtosis = *impulseKurtosis;
    if (taubinOnlySteps) o.taubinOnlySteps = *taubinOnlySteps;
    if (taubinOnlyMargin) o.taubinOnlyMargin = *taubinOnlyMargin;
    if (lightStart) o.lightStart = *lightStart;
    if (lightStartTurn) o.lightStartTurn = *lightStartTurn;
    if (taubinOnlyMu) o.candidateTaubin.mu = *taubinOnlyMu;
    if (radius) o.neighborhood.radius = *radius;
    if (spatialBandwidth) o.neighborhood.spatialBandwidth = *spatialBandwidth;
    if (maxPasses) o.maxPasses = *maxPasses;
    if (vertexIterations) o.vertexIterations = *vertexIterations;
    if (patience) o.patience = *patience;
    if (highMinSamples) o.highFrequencyMinSamples = *highMinSamples;
    if (impulseSpectrumMinSamples) o.impulseSpectrumMinSamples = *impulseSpectrumMinSamples;
    if (planarLevelShare) o.planarLevelShare = *planarLevelShare;
    if (planarKeep) o.planarKeep = *planarKeep;
    if (spectrumVeto) o.impulseSpectrumVeto = *spectrumVeto;
    if (fixedPasses) o.fixedPasses = *fixedPasses;
    if (riskNormalSmoothing) o.riskNormalSmoothing = *riskNormalSmoothing;
    if (!range.empty()) o.rangeBandwidths = range;
    if (!presmoothing.empty()) o.presmoothing = presmoothing;
    if (probeSpacing) o.probeSpacing = *probeSpacing;
    if (tieProbes) o.tieProbes = *tieProbes;
    if (tieMargin) o.tieMargin = *tieMargin;
    if (tieStandardErrors) o.tieStandardErrors = *tieStandardErrors;
    if (tieByNormals) o.tieByNormals = *tieByNormals;
    if (inputCandidate) o.inputCandidate = *inputCandidate;
    if (spatialOrder) o.spatialOrder = *spatialOrder;
    if (supportSteps) o.supportSmoothing.iterations = *supportSteps;
    if (refineNoise) o.refineNoise = *refineNoise;
    if (halving) o.halvingRace = *halving;
    if (boundedDivergence) o.boundedDivergence = *boundedDivergence;
  }
};

// The noise along the clean mesh's vertex normals, RMS in the noisy mesh's average edge lengths: what
// estimateNoise estimates.
double trueNoiseLevel(const Case& c) {
  const std::vector<Vec3> n = vertexNormals(c.clean);
  double sum = 0;
  int count = 0;
  for (int v = 0; v < c.clean.vertexCount(); ++v) {
    if (n[v].squaredNorm() == 0) continue;
    const double d = (c.noisy.position(v) - c.clean.position(v)).dot(n[v]);
    sum += d * d;
    ++count;
  }
  return std::sqrt(sum / std::max(1, count)) / averageEdgeLength(c.noisy);
}

std::string fixed(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}
std::string fixed3(double x) { return fixed(x, 3); }

// A candidate blended in (DenoiseResult::Blend), for the scoreboard's note; empty when none.
std::string blended(const std::string& lead, const DenoiseResult::Blend& b) {
  if (b.weight <= 0) return "";
  return lead + fixed3(b.weight) + " with " +
         (b.taubinOnly ? "Taubin only " + std::to_string(b.presmoothingSteps)
                       : "Taubin " + std::to_string(b.presmoothingSteps) + " + " + std::to_string(b.passes));
}

Score ours(const Case& c, const WhatIf& w, std::uint64_t seed, bool paper) {
  Mesh m = c.noisy;
  DenoiseOptions o;
  o.threads = 1;
  o.seed = seed;
  if (paper) {
    o.preset = DenoisePreset::Paper;
  } else {
    w.apply(o);
    if (w.trueNoise) o.noiseLevel = trueNoiseLevel(c);
  }
  std::ostringstream trace;
  std::vector<CandidateScore> candidates;
  if (w.trace && !paper) {
    // Every candidate's risks against the truth (slow: two distance queries per candidate).
    trace.precision(4);
    // The directions the risk is measured along, as the denoiser finds them (6 Taubin steps).
    Mesh smoothed = c.noisy;
    TaubinOptions six;
    six.iterations = o.riskNormalSmoothing;
    six.parallel.threads = 1;
    taubinSmooth(smoothed, six);
    const std::vector<Vec3> N = vertexNormals(smoothed);
    o.onCandidate = [&, N](int steps, int passes, const std::vector<Vec3>& x, double positionRisk) {
      const Score s = scoreOf(c, x, "", -1);
      candidates.push_back({steps, passes, s.rms, s.angle});
      const double ael = averageEdgeLength(c.noisy);
      double along = 0;
      for (size_t v = 0; v < x.size(); ++v) along += std::pow((x[v] - c.clean.position(v)).dot(N[v]), 2);
      along = std::sqrt(along / x.size()) / ael;
      trace << "  trace " << c.mesh << " | " << c.noise << " | k " << steps << " t " << passes << " | SURE "
            << positionRisk / (ael * ael) << " AEL² | true along N " << fixed3(along) << " AEL | true " << fixed3(s.rms) << " / " << fixed3(s.angle) << " | turn "
            << fixed3(meanNormalTurn(c.noisy, x)) << "\n";
    };
  }
  const auto t0 = std::chrono::steady_clock::now();
  const DenoiseResult r = denoise(m, o);
  const double ms = msSince(t0);
  if (w.trace) std::cerr << trace.str();
  std::ostringstream note;
  note.precision(3);
  if (paper) {
    note << o.paper.passes << " passes";
  } else {
    note << "σ " << r.noiseLevel << " AEL" << (r.planarLevel ? " from planes" : "") << "; ";
    if (r.keptInput)
      note << "the input kept as it was";
    else if (r.taubinOnly)
      note << "Taubin only, " << r.presmoothingSteps << " steps";
    else
      note << "Taubin " << r.presmoothingSteps << " + " << r.passes << " passes"
           << (o.rangeBandwidths.size() > 1 ? " at h_r " + fixed3(r.rangeBandwidth) : "");
    note
         << (o.fixedPasses > 0 ? " (fixed)" : "")
         << blended(", blended ", r.blend) << blended(", then ", r.startBlend)
         << (r.impulseGarrote ? ", impulse garrote (kurtosis " + fixed(r.displacementKurtosis, 1) + ", spectrum " + fixed(r.spectrumKurtosis, 1) + ")" : "")
         << (r.planarKept > 0 ? ", " + std::to_string(r.planarKept) + " kept on planes" : "")
         << (r.lightStartRaced ? (r.lightStartTurnedDown ? ", light start turned down" : ", light start raced") : "")
         << (r.tieProbes > 0 ? ", tie: " + std::to_string(r.tieProbes) + (r.tieProbes > 1 ? " more probes" : " more probe") +
                                   (r.tieByNormals ? ", by normals" : "")
                             : "")
         << " (" << r.passesRun << " computed)";
  }
  Score score = scoreOf(c, m.positions(), note.str(), ms);
  score.candidates = std::move(candidates);
  return score;
}

// --- verdicts -------------------------------------------------------------------------------------

// Ours and, in each number, the better oracle's figure, as the verdict reads them (the lesser of two
// figures printed is the lesser figure printed, so the better oracle's raw figure is kept).
CaseFigures figuresOf(const Score& ours, const Score& taubin, const Score& bilateral) {
  CaseFigures f;
  f.rms = ours.rms;
  f.angle = ours.angle;
  f.bestRms = std::min(taubin.rms, bilateral.rms);
  f.bestAngle = std::min(taubin.angle, bilateral.angle);
  return f;
}

// The scoreboard's verdict (compare.hpp: figures compared as printed, a tie at that precision a tie).
Verdict verdict(const Score& ours, const Score& taubin, const Score& bilateral) {
  return verdictOf(figuresOf(ours, taubin, bilateral));
}

struct Result {
  const Case* c = nullptr;
  Score noisy, taubin, bilateral, gcn, paper;
  std::vector<Score> ours;  // one per seed
};

std::string pairOf(const Score& s) { return s.present() ? fixed(s.rms, 3) + " / " + fixed(s.angle, 2) : "–"; }

// With --trace: whether what is lost is lost to the choice or for want of a candidate. A case is
// within reach when some candidate the race computed (at the first probe seed, scored before the
// impulse correction) or the default's own result wins it.
std::string ceiling(const std::vector<const Result*>& rows) {
  if (rows.empty() || rows.front()->ours.front().candidates.empty()) return "";
  int reachable = 0;
  std::vector<std::string> toChoice, toFamily;
  for (const Result* r : rows) {
    const Score& o = r->ours.front();
    const CandidateScore* best = nullptr;
    for (const CandidateScore& k : o.candidates) {
      Score as;
      as.rms = k.rms;
      as.angle = k.angle;
      if (verdict(as, r->taubin, r->bilateral).win && (!best || k.rms < best->rms)) best = &k;
    }
    const bool won = verdict(o, r->taubin, r->bilateral).win;
    reachable += won || best;
    if (won) continue;
    const std::string name = r->c->mesh + ", " + r->c->noise;
    if (best)
      toChoice.push_back(name + " (" + std::to_string(best->steps) + " steps + " + std::to_string(best->passes) +
                         " passes: " + fixed(best->rms, 3) + " / " + fixed(best->angle, 2) + ")");
    else
      toFamily.push_back(name);
  }
  std::ostringstream s;
  s << "\nWith a perfect choice among the candidates computed (`--trace`; scored before the impulse correction, the "
       "default's own result counted): "
    << reachable << " of " << rows.size() << " within reach.\n\nLost to the choice:";
  for (size_t i = 0; i < toChoice.size(); ++i) s << (i ? "; " : " ") << toChoice[i];
  s << (toChoice.empty() ? " none" : "") << ".\n\nNo candidate wins:";
  for (size_t i = 0; i < toFamily.size(); ++i) s << (i ? "; " : " ") << toFamily[i];
  s << (toFamily.empty() ? " none" : "") << ".\n";
  return s.str();
}

std::string lower(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

std::vector<std::uint64_t> parseSeeds(const std::string& text, const std::string& option) {
  std::vector<std::uint64_t> out;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) {
    const size_t dash = item.find('-');
    if (dash == std::string::npos) {
      out.push_back(std::stoull(item));
    } else {
      const std::uint64_t a = std::stoull(item.substr(0, dash)), b = std::stoull(item.substr(dash + 1));
      if (b < a || b - a > 1000) throw InputError(option + ": bad range " + item);
      for (std::uint64_t s = a; s <= b; ++s) out.push_back(s);
    }
  }
  if (out.empty()) throw InputError(option + " needs at least one seed");
  return out;
}

// Geometric means of ours / the better oracle, RMS and normal error apart: how far ahead or behind
// a set is on the whole, which a count of cases won does not tell (a loss by 1% counts as one by
// 100%). Logs are summed, so a case twice better offsets one twice worse.
struct RatioMean {
  double logRms = 0, logAngle = 0;
  int n = 0;
  void add(const Verdict& v) {
    logRms += std::log(std::max(v.rmsRatio, 1e-6));
    logAngle += std::log(std::max(v.angleRatio, 1e-6));
    ++n;
  }
  double rms() const { return n ? std::exp(logRms / n) : 1.0; }
  double angle() const { return n ? std::exp(logAngle / n) : 1.0; }
};

// The tables of one set: every case, then what the set adds up to.
std::string report(Set set, const std::vector<Result>& results, const std::vector<std::uint64_t>& seeds, bool paper) {
  std::ostringstream s;
  std::vector<const Result*> rows;
  for (const Result& r : results)
    if (r.c->set == set) rows.push_back(&r);
  s << "## "
    << (set == Set::Tuning       ? "Tuning set"
        : set == Set::Validation ? "Validation set"
        : set == Set::Broad      ? "Broad tuning set"
                                 : "Holdout set")
    << " ("
    << rows.size() << " cases)\n\n";
  if (rows.empty()) return s.str();
  s << "RMS ×10² / mean normal error (°); oracles tuned per case on the truth; geoshift with its defaults, probe seed "
    << seeds.front() << ". ✓: both numbers at or below both oracles; ratio: the worse of ours / the better oracle.\n\n"
    << "| case | noise | vertices | noisy | Taubin, tuned | bilateral, tuned | **geoshift** | ✓ | ratio |"
    << (paper ? " paper preset |" : "") << " GCN-Denoiser | note |\n|---|---|---|---|---|---|---|---|---|"
    << (paper ? "---|" : "") << "---|---|\n";
  struct Category {
    int won = 0, cases = 0;
    RatioMean ratios;
  };
  std::map<std::string, Category> byCategory;
  std::vector<int> wonPerSeed(seeds.size(), 0);
  std::map<std::uint64_t, std::pair<int, int>> perNoiseSeed;  // cases won at the first probe seed, cases
  std::vector<RatioMean> ratiosPerSeed(seeds.size());
  int within = 0;
  double worst = 0;
  std::string worstCase;
  std::vector<std::string> misses, unstable;
  std::vector<std::string> families;  // the cases' families and verdicts at the first seed, for the interval
  std::vector<bool> wonFirst;
  for (const Result* r : rows) {
    const Verdict v = verdict(r->ours.front(), r->taubin, r->bilateral);
    std::pair<int, int>& atNoise = perNoiseSeed[noiseSeedOf(r->c->noise)];
    atNoise.first += v.win;
    ++atNoise.second;
    families.push_back(r->c->family);
    wonFirst.push_back(v.win);
    std::string wonAt;
    int wins = 0;
    for (size_t k = 0; k < seeds.size(); ++k) {
      const Verdict vk = verdict(r->ours[k], r->taubin, r->bilateral);
      wonPerSeed[k] += vk.win;
      ratiosPerSeed[k].add(vk);
      if (!vk.win) continue;
      if (wins++ > 0) wonAt += ", ";
      wonAt += std::to_string(seeds[k]);
    }
    // The cases the seed decides: what the spread is made of.
    if (wins > 0 && wins < static_cast<int>(seeds.size())) {
      std::string line = r->c->mesh;
      line += ", ";
      line += r->c->noise;
      line += wins > 1 ? " (won at seeds " : " (won at seed ";
      line += wonAt;
      line += ")";
      unstable.push_back(std::move(line));
    }
    Category& cat = byCategory[r->c->category];
    cat.won += v.win;
    ++cat.cases;
    cat.ratios.add(v);
    within += v.ratio <= 1.25;
    if (v.ratio > worst) {
      worst = v.ratio;
      worstCase = r->c->mesh + ", " + r->c->noise;
    }
    if (!v.win) misses.push_back(r->c->mesh + ", " + r->c->noise);
    s << "| " << r->c->mesh << " | " << r->c->noise << " | " << r->c->clean.vertexCount() << " | " << pairOf(r->noisy)
      << " | " << pairOf(r->taubin) << " | " << pairOf(r->bilateral) << " | **" << pairOf(r->ours.front()) << "** | "
      << (v.win ? "✓" : "✗") << " | " << fixed(v.ratio, 2) << " |" << (paper ? " " + pairOf(r->paper) + " |" : "")
      << " " << pairOf(r->gcn) << " | " << r->ours.front().note << " |\n";
  }
  s << "\n| category | cases | won | RMS ratio | normal ratio |\n|---|---|---|---|---|\n";
  for (const auto& [category, c] : byCategory)
    s << "| " << category << " | " << c.cases << " | " << c.won << " | " << fixed(c.ratios.rms(), 3) << " | "
      << fixed(c.ratios.angle(), 3) << " |\n";
  s << "\nRMS and normal ratio: geometric means over the cases of ours / the better oracle (below 1: ahead).\n";
  const ShareInterval interval = groupBootstrapShare(families, wonFirst);
  s << "\n**" << setName(set) << ": won " << wonPerSeed.front() << " of " << rows.size() << "** ("
    << fixed(100.0 * wonPerSeed.front() / rows.size(), 1) << "%; 95% interval " << fixed(100.0 * interval.low, 0) << "–"
    << fixed(100.0 * interval.high, 0) << "% over the set's " << interval.groups
    << " families, resampled); within 1.25× of the better oracle in both numbers: "
    << within << " of " << rows.size() << "; worst ratio " << fixed(worst, 2) << " (" << worstCase
    << "); geometric mean ratio RMS " << fixed(ratiosPerSeed.front().rms(), 3) << ", normal error "
    << fixed(ratiosPerSeed.front().angle(), 3) << ".\n";
  if (perNoiseSeed.size() > 1) {
    s << "\nCases won per noise seed (probe seed " << seeds.front() << "; the pairs with noise seed 1):";
    for (auto it = perNoiseSeed.begin(); it != perNoiseSeed.end(); ++it)
      s << (it == perNoiseSeed.begin() ? " " : ", ") << it->first << ": " << it->second.first << " of " << it->second.second;
    s << ".\n";
  }
  if (seeds.size() > 1) {
    s << "\nCases won per probe seed:";
    for (size_t k = 0; k < seeds.size(); ++k) s << " " << seeds[k] << ": " << wonPerSeed[k] << (k + 1 < seeds.size() ? "," : "");
    const auto [lo, hi] = std::minmax_element(wonPerSeed.begin(), wonPerSeed.end());
    s << " (spread " << (*hi - *lo) << ").\n\nGeometric mean ratios per probe seed (RMS / normal error):";
    for (size_t k = 0; k < seeds.size(); ++k)
      s << " " << seeds[k] << ": " << fixed(ratiosPerSeed[k].rms(), 3) << " / " << fixed(ratiosPerSeed[k].angle(), 3)
        << (k + 1 < seeds.size() ? "," : "");
    s << ".\n\nCases won at some probe seeds and not at others: ";
    if (unstable.empty()) s << "none";
    for (size_t i = 0; i < unstable.size(); ++i) s << (i ? "; " : "") << unstable[i];
    s << ".\n";
  }
  if (!misses.empty()) {
    s << "\nNot won:";
    for (size_t i = 0; i < misses.size(); ++i) s << (i ? "; " : " ") << misses[i];
    s << ".\n";
  }
  s << ceiling(rows);
  for (const Result* r : rows) {
    if (!r->gcn.present()) continue;
    const Score& o = r->ours.front();
    s << "\nAgainst GCN-Denoiser on " << r->c->mesh << ": ours " << pairOf(o) << ", GCN-Denoiser " << pairOf(r->gcn)
      << (verdict(o, r->gcn, r->gcn).win ? " (both at or below)" : " (not both at or below)")
      << ".\n";
  }
  return s.str() + "\n";
}

int usage(const char* error) {
  if (error) std::cerr << "denoise_eval: " << error << "\n";
  std::cerr
      << "usage: denoise_eval [options]\n"
         "  --set tuning|validation|broad|holdout|all   which cases (default all: tuning and validation); choose\n"
         "                     defaults on tuning (and broad, more tuning cases: CGAL's demo meshes, scripts/eval-data.sh)\n"
         "                     alone; holdout (CGAL's small demo meshes, split in four and by Loop) is a record, never a choice\n"
         "  --mesh SUBSTRING   only cases whose mesh name contains SUBSTRING (case-insensitive)\n"
         "  --pairs            only the ground-truth pairs\n"
         "  --quick            one pair and two small procedural meshes, as a smoke test\n"
         "  --seeds LIST       probe seeds of the denoiser, e.g. 1-8 or 1,3 (default 1); the report counts wins per seed\n"
         "  --noise-seed LIST  realizations of the synthetic noises, e.g. 2 or 1-3 (default 1, the scoreboard's; same kinds and\n"
         "                     levels; the pairs keep their own noise): how much of a result is the noise's luck; the\n"
         "                     tuning run for a choice is --set tuning --noise-seed 1-3 (docs/denoising.md#the-evaluation)\n"
         "  --jobs N           cases evaluated at once (default 2; each method runs on one thread)\n"
         "  --paper            also the paper preset\n"
         "  --split            print the families of each set and exit\n"
         "  --oracles-only     only fill the oracles' cache (no denoiser, no report)\n"
         "  --noise-estimate   only the estimated against the true noise level of each case (est: the quadric\n"
         "                     estimate; high: highFrequencyNoiseLevel, what the default ranks with; kurtosis: of\n"
         "                     the same frequencies, the second impulse trigger)\n"
         "  --strength, --detail-bound-ratio, --max-passes, --hr (list), --presmoothing (list), --vertex-iterations,\n"
         "  --radius, --hs, --patience, --fixed-passes, --risk-normal-smoothing, --probe-spacing, --refine-noise on|off,\n"
         "  --halving on|off, --support-steps (supportSmoothing.iterations), --tie-probes, --tie-margin,\n"
         "  --tie-standard-errors, --tie-normals on|off, --input-candidate on|off, --spatial-order on|off,\n"
         "  --impulse-shrink, --impulse-kurtosis, --bounded-divergence on|off, --taubin-only (list, or none),\n"
         "  --taubin-only-margin, --taubin-only-mu (candidateTaubin.mu), --high-frequency-level on|off, --level-lean,\n"
         "  --gradient-risk-weight, --impulse-spectrum-kurtosis, --min-piece (minPieceVertices), --blend-spread,\n"
         "  --high-min-samples (highFrequencyMinSamples), --impulse-spectrum-veto,\n"
         "  --impulse-spectrum-min-samples (impulseSpectrumMinSamples), --planar-level-share (planarLevelShare),\n"
         "  --planar-keep (planarKeep), --light-start (lightStart), --light-start-turn (lightStartTurn)\n"
         "                     the default denoiser's options of those names (what-ifs)\n"
         "  --trace            every candidate's risk estimates against its true errors and its normals' mean turn,\n"
         "                     and how many cases a perfect choice among the candidates would win (slow)\n"
         "  --true-noise       the denoiser is given the true noise level (an oracle experiment)\n"
         "  --cache DIR        the oracles' score cache (default build/eval-cache); --no-cache to recompute\n"
         "  --markdown FILE    also write the report to FILE\n"
         "  --results FILE     also write every case's figures at every probe seed to FILE, for --compare\n"
         "  --compare BEFORE AFTER   no evaluation: compare two --results files case by case (verdicts that\n"
         "                     changed, ratios, and a signed-rank test of the changes in RMS and normal error,\n"
         "                     over the cases and over the meshes)\n"
         "  --data DIR         the shared data folder (default ../shared/data of the repository)\n"
         "  --broad-data DIR   the broad and holdout sets' meshes (default build/eval-data/cgal-demo/meshes of the repository)\n";
  return error ? 2 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string filter, markdownPath, resultsPath, setFilter = "all";
  std::vector<std::string> compare;
  bool quick = false, pairsOnly = false, paper = false, splitOnly = false, noiseOnly = false, oraclesOnly = false;
  int jobs = 2;
  std::vector<std::uint64_t> seeds = {1};
  std::vector<std::uint64_t> noiseSeeds = {1};  // the synthetic noises' realizations
  WhatIf whatIf;
  OracleCache cache{"build/eval-cache"};
  const char* env = std::getenv("GEOSHIFT_SHARED_DATA");
  fs::path data = env && *env ? env : GEOSHIFT_SHARED_DATA;
  const char* broadEnv = std::getenv("GEOSHIFT_BROAD_DATA");
  fs::path broadData = broadEnv && *broadEnv ? broadEnv : GEOSHIFT_BROAD_DATA;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InputError(a + " needs a value");
      return argv[++i];
    };
    auto list = [&](auto parse) {
      std::stringstream text(value());
      std::vector<decltype(parse(std::string()))> out;
      for (std::string item; std::getline(text, item, ',');) out.push_back(parse(item));
      return out;
    };
    try {
      if (a == "--mesh") filter = lower(value());
      else if (a == "--set") setFilter = lower(value());
      else if (a == "--quick") quick = true;
      else if (a == "--pairs") pairsOnly = true;
      else if (a == "--paper") paper = true;
      else if (a == "--split") splitOnly = true;
      else if (a == "--oracles-only") oraclesOnly = true;
      else if (a == "--noise-estimate") noiseOnly = true;
      else if (a == "--seeds") seeds = parseSeeds(value(), a);
      else if (a == "--noise-seed") {
        noiseSeeds = parseSeeds(value(), a);  // each realization once, in order
        std::sort(noiseSeeds.begin(), noiseSeeds.end());
        noiseSeeds.erase(std::unique(noiseSeeds.begin(), noiseSeeds.end()), noiseSeeds.end());
      }
      else if (a == "--jobs") jobs = std::max(1, std::stoi(value()));
      else if (a == "--strength") whatIf.strength = std::stod(value());
      else if (a == "--detail-bound-ratio") whatIf.detailBoundRatio = std::stod(value());
      else if (a == "--level-lean") whatIf.levelLean = std::stod(value());
      else if (a == "--blend-spread") whatIf.blendSpread = std::stod(value());
      else if (a == "--gradient-risk-weight") whatIf.gradientRiskWeight = std::stod(value());
      else if (a == "--min-piece") whatIf.minPieceVertices = std::stoi(value());
      else if (a == "--impulse-spectrum-kurtosis") whatIf.impulseSpectrumKurtosis = std::stod(value());
      else if (a == "--high-frequency-level") whatIf.highFrequencyLevel = value() != "off";
      else if (a == "--impulse-shrink") whatIf.impulseShrink = std::stod(value());
      else if (a == "--impulse-kurtosis") whatIf.impulseKurtosis = std::stod(value());
      else if (a == "--taubin-only") {
        const std::string v = value();
        whatIf.taubinOnlySteps = std::vector<int>();
        if (v != "none") {
          std::stringstream text(v);
          for (std::string item; std::getline(text, item, ',');) whatIf.taubinOnlySteps->push_back(std::stoi(item));
        }
      }
      else if (a == "--taubin-only-margin") whatIf.taubinOnlyMargin = std::stod(value());
      else if (a == "--light-start") whatIf.lightStart = std::stoi(value());
      else if (a == "--light-start-turn") whatIf.lightStartTurn = std::stod(value());
      else if (a == "--taubin-only-mu") whatIf.taubinOnlyMu = std::stod(value());
      else if (a == "--max-passes") whatIf.maxPasses = std::stoi(value());
      else if (a == "--presmoothing") whatIf.presmoothing = list([](const std::string& s) { return std::stoi(s); });
      else if (a == "--hr") whatIf.range = list([](const std::string& s) { return std::stod(s); });
      else if (a == "--vertex-iterations") whatIf.vertexIterations = std::stoi(value());
      else if (a == "--radius") whatIf.radius = std::stod(value());
      else if (a == "--hs") whatIf.spatialBandwidth = std::stod(value());
      else if (a == "--patience") whatIf.patience = std::stoi(value());
      else if (a == "--high-min-samples") whatIf.highMinSamples = std::stoi(value());
      else if (a == "--impulse-spectrum-veto") whatIf.spectrumVeto = std::stod(value());
      else if (a == "--impulse-spectrum-min-samples") whatIf.impulseSpectrumMinSamples = std::stoi(value());
      else if (a == "--planar-level-share") whatIf.planarLevelShare = std::stod(value());
      else if (a == "--planar-keep") whatIf.planarKeep = std::stod(value());
      else if (a == "--fixed-passes") whatIf.fixedPasses = std::stoi(value());
      else if (a == "--risk-normal-smoothing") whatIf.riskNormalSmoothing = std::stoi(value());
      else if (a == "--probe-spacing") whatIf.probeSpacing = std::stoi(value());
      else if (a == "--tie-probes") whatIf.tieProbes = std::stoi(value());
      else if (a == "--tie-margin") whatIf.tieMargin = std::stod(value());
      else if (a == "--tie-standard-errors") whatIf.tieStandardErrors = std::stod(value());
      else if (a == "--tie-normals") whatIf.tieByNormals = value() != "off";
      else if (a == "--input-candidate") whatIf.inputCandidate = value() != "off";
      else if (a == "--spatial-order") whatIf.spatialOrder = value() != "off";
      else if (a == "--support-steps") whatIf.supportSteps = std::stoi(value());
      else if (a == "--trace") whatIf.trace = true;
      else if (a == "--true-noise") whatIf.trueNoise = true;
      else if (a == "--refine-noise") whatIf.refineNoise = value() != "off";
      else if (a == "--halving") whatIf.halving = value() != "off";
      else if (a == "--bounded-divergence") whatIf.boundedDivergence = value() != "off";
      else if (a == "--cache") cache.dir = value();
      else if (a == "--no-cache") cache.dir.clear();
      else if (a == "--markdown") markdownPath = value();
      else if (a == "--results") resultsPath = value();
      else if (a == "--compare") {
        compare.push_back(value());
        compare.push_back(value());
      }
      else if (a == "--data") data = value();
      else if (a == "--broad-data") broadData = value();
      else if (a == "-h" || a == "--help") return usage(nullptr);
      else return usage(("unknown argument '" + a + "'").c_str());
    } catch (const std::exception& e) {
      return usage(e.what());
    }
  }
  if (setFilter != "all" && setFilter != "tuning" && setFilter != "validation" && setFilter != "broad" &&
      setFilter != "holdout")
    return usage("--set takes tuning, validation, broad, holdout or all");
  if (!compare.empty()) {
    try {
      std::vector<CaseFigures> runs[2];
      for (int k = 0; k < 2; ++k) {
        std::ifstream in(compare[k]);
        if (!in) throw InputError(compare[k] + ": cannot open");
        runs[k] = readResults(in, compare[k]);
      }
      std::cout << "# " << compare[1] << " against " << compare[0] << "\n\n" << compareResults(runs[0], runs[1]);
      return 0;
    } catch (const std::exception& e) {
      std::cerr << "denoise_eval: error: " << e.what() << "\n";
      return 1;
    }
  }

  // The catalogue and its split.
  std::vector<MeshEntry> meshes = cleanMeshes(data);
  // The broad set only where it is asked for: --set all stays the tuning and validation sets.
  if (setFilter == "broad" || splitOnly)
    for (MeshEntry& m : broadMeshes(broadData)) meshes.push_back(std::move(m));
  // The holdout set likewise (docs/denoising.md, "The holdout set").
  if (setFilter == "holdout" || splitOnly)
    for (MeshEntry& m : holdoutMeshes(broadData)) meshes.push_back(std::move(m));
  const auto split = splitFamilies(meshes);
  auto setOf = [&](const std::string& family) {
    for (const auto& [f, s] : split)
      if (f == family) return s;
    return Set::Tuning;
  };
  if (splitOnly) {
    for (Set set : {Set::Tuning, Set::Validation, Set::Broad, Set::Holdout}) {
      std::cout << setName(set) << ":\n";
      for (const MeshEntry& m : meshes)
        if (setOf(m.family) == set) std::cout << "  " << m.name << " [" << m.family << "; " << m.category << (m.seen ? "; seen" : "") << "]\n";
    }
    return 0;
  }
  auto wantedSet = [&](Set s) {
    return (setFilter == "all" && (s == Set::Tuning || s == Set::Validation)) || setFilter == setName(s);
  };
  auto wanted = [&](const std::string& name) { return filter.empty() || lower(name).find(filter) != std::string::npos; };

  // Tasks: one per (clean mesh, noise) and one per pair; each builds its case when it runs.
  std::vector<std::function<std::optional<Case>()>> tasks;
  if (quick) {
    meshes.erase(std::remove_if(meshes.begin(), meshes.end(),
                                [](const MeshEntry& m) { return m.family != "sphere" && m.family != "cad block"; }),
                 meshes.end());
  }
  if (!pairsOnly) {
    for (const MeshEntry& m : meshes) {
      if (!wanted(m.name) || !wantedSet(setOf(m.family))) continue;
      for (std::uint64_t noiseSeed : noiseSeeds) {
        std::vector<NoiseSpec> noises = noisesFor(m.name, noiseSeed);
        if (quick) noises.resize(1);
        for (const NoiseSpec& n : noises) {
          tasks.push_back([&m, n, noiseSeed, set = setOf(m.family), quick]() -> std::optional<Case> {
            Mesh clean = quick ? buildMesh(m.family == "sphere" ? shapes::icosphere(3) : shapes::box(20, 14, 10, Vec3(1.0, 0.7, 0.5))).mesh
                               : m.load();
            normalizeToUnitCube(clean);
            Case c{m.name, withNoiseSeed(n.label, noiseSeed), m.family, m.category, set, clean, clean, ""};
            addNoise(c.noisy, n.options);
            return c;
          });
        }
      }
    }
  }
  std::vector<Pair> pairs = groundTruthPairs();
  if (quick) pairs.resize(1);
  for (const Pair& p : pairs) {
    if (!wanted(p.name) || !wantedSet(setOf(p.family))) continue;
    tasks.push_back([&p, &data, set = setOf(p.family)]() -> std::optional<Case> {
      Case c;
      if (!loadPair(data, p, c)) return std::nullopt;
      c.set = set;
      return c;
    });
  }

  std::vector<std::optional<Case>> cases(tasks.size());
  std::vector<Result> results(tasks.size());
  std::atomic<size_t> next{0};
  std::mutex log;
  std::exception_ptr failure;
  auto worker = [&] {
    for (size_t t; (t = next++) < tasks.size();) {
      try {
        cases[t] = tasks[t]();
        if (!cases[t]) continue;
        const Case& c = *cases[t];
        if (noiseOnly) {
          // Experimental estimators beside the default: the mean of all quadric residual variances,
          // and the mean over vertices whose two-ring on a smoothed support still misfits by less
          // than tau of the noisy misfit (creases survive the smoothing, noise does not).
          const std::vector<int> at = noiseSampleVertices(c.noisy);
          const std::vector<double> v = quadricResidualVariances(c.noisy, at);
          Mesh support = c.noisy;
          taubinSmooth(support, TaubinOptions{});
          const std::vector<double> w = quadricResidualVariances(support, at);
          const double ael = averageEdgeLength(c.noisy);
          auto level = [&](double tau, double* kept) {
            double sum = 0;
            int count = 0, all = 0;
            for (size_t i = 0; i < v.size(); ++i) {
              if (v[i] < 0 || w[i] < 0) continue;
              ++all;
              if (tau > 0 && w[i] > tau * v[i]) continue;
              sum += v[i];
              ++count;
            }
            if (kept) *kept = all ? double(count) / all : 0;
            return count ? std::sqrt(sum / count) / ael : 0.0;
          };
          double k1, k2, k3;
          const double a = level(0, nullptr), b = level(0.1, &k1), d = level(0.2, &k2), e = level(0.4, &k3);
          std::lock_guard lock(log);
          ParallelOptions one;
          one.threads = 1;
          const HighFrequencyNoise high = highFrequencyNoise(c.noisy, one);
          const PlanarNoise planar = planarNoise(c.noisy), planarClean = planarNoise(c.clean);
          std::printf("noise | %-28s | %-36s | true %.3f | est %.3f | high %.3f | kurtosis %.2f | samples %d of %d | mean %.3f | t.1 %.3f (%.2f) | t.2 %.3f (%.2f) | t.4 %.3f (%.2f) | planar %.3f share %.2f read %d | clean share %.2f\n",
                      c.mesh.c_str(), c.noise.c_str(), trueNoiseLevel(c), estimateNoise(c.noisy).level, high.level,
                      high.kurtosis, high.samples, c.noisy.vertexCount(), a, b, k1, d, k2, e, k3, planar.level,
                      planar.confirmedShare, planar.samples, planarClean.confirmedShare);
          continue;
        }
        Result& r = results[t];
        r.c = &c;
        r.noisy = scoreOf(c, c.noisy.positions(), "", -1);
        r.taubin = cache.get(c, "taubin-tuned", taubinTuned);
        r.bilateral = cache.get(c, "bilateral-tuned", bilateralTuned);
        if (oraclesOnly) {
          r.c = nullptr;
          continue;
        }
        for (std::uint64_t seed : seeds) r.ours.push_back(ours(c, whatIf, seed, false));
        if (paper) r.paper = ours(c, whatIf, 1, true);
        if (!c.gcnResult.empty()) {
          for (const Pair& p : pairs)
            if (p.gcnResult == c.gcnResult) r.gcn = scoreOf(c, loadResultPositions(data, p, c.gcnResult), "published", -1);
        }
        const Verdict v = verdict(r.ours.front(), r.taubin, r.bilateral);
        std::lock_guard lock(log);
        std::cerr << "denoise_eval: [" << setName(c.set) << "] " << c.mesh << ", " << c.noise << ": ours " << pairOf(r.ours.front())
                  << " (" << r.ours.front().note << ", " << fixed(r.ours.front().ms / 1000, 1) << " s), Taubin "
                  << pairOf(r.taubin) << ", bilateral " << pairOf(r.bilateral) << (v.win ? "  won" : "  NOT WON") << "\n";
      } catch (...) {
        std::lock_guard lock(log);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int k = 0; k < std::min<int>(jobs, std::max<size_t>(1, tasks.size())); ++k) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  if (failure) {
    try {
      std::rethrow_exception(failure);
    } catch (const std::exception& e) {
      std::cerr << "denoise_eval: error: " << e.what() << "\n";
      return 1;
    }
  }
  if (noiseOnly || oraclesOnly) return 0;
  results.erase(std::remove_if(results.begin(), results.end(), [](const Result& r) { return r.c == nullptr; }), results.end());

  std::ostringstream md;
  md << "# Denoising evaluation\n\nRMS: one-sided point-to-surface distance from the result's vertices to the clean surface "
        "(as MeshLab's Hausdorff filter), meshes scaled to the unit cube, ×10². Normal error: mean angle between "
        "corresponding face normals. The split and the noises: docs/denoising.md#the-evaluation.\n\n";
  if (noiseSeeds != std::vector<std::uint64_t>{1}) {
    md << "Synthetic noises of seed" << (noiseSeeds.size() > 1 ? "s" : "");
    for (size_t k = 0; k < noiseSeeds.size(); ++k) md << (k ? ", " : " ") << noiseSeeds[k];
    md << " (the scoreboard's: 1; the pairs keep their own noise, counted with noise seed 1).\n\n";
  }
  for (Set set : {Set::Validation, Set::Tuning, Set::Broad, Set::Holdout})
    if (wantedSet(set)) md << report(set, results, seeds, paper);
  std::cout << md.str();
  if (!markdownPath.empty()) {
    const fs::path tmp = markdownPath + ".tmp";
    std::ofstream(tmp) << md.str();
    fs::rename(tmp, markdownPath);
    std::cerr << "denoise_eval: report written to " << markdownPath << "\n";
  }
  if (!resultsPath.empty()) {
    std::vector<CaseFigures> figures;
    for (const Result& r : results) {
      for (size_t k = 0; k < seeds.size(); ++k) {
        CaseFigures f = figuresOf(r.ours[k], r.taubin, r.bilateral);
        f.set = setName(r.c->set);
        f.mesh = r.c->mesh;
        f.noise = r.c->noise;
        f.seed = seeds[k];
        figures.push_back(std::move(f));
      }
    }
    const fs::path tmp = resultsPath + ".tmp";
    {
      std::ofstream out(tmp);
      writeResults(out, figures);
      if (!out) {
        std::cerr << "denoise_eval: error: cannot write " << tmp.string() << "\n";
        return 1;
      }
    }
    fs::rename(tmp, resultsPath);
    std::cerr << "denoise_eval: results written to " << resultsPath << "\n";
  }
  return 0;
}
