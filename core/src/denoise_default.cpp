// The default denoiser (denoise.hpp; docs/denoising.md#the-default-pipeline).
//
// Candidates x(k, t): k Taubin steps, then t passes of [blurring mean shift of the face normals →
// vertex update]. Each is scored by the risk estimate (denoise_risk.hpp) from itself and its copy
// computed from a probed input, so every pass is computed twice. The candidates race
// (CandidateRace below) and the one of least risk is returned.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <string>

#include "denoise_detail.hpp"
#include "denoise_risk.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geodesic.hpp"
#include "geoshift/geometry.hpp"
#include "geoshift/noise.hpp"

namespace geoshift::denoise_detail {

namespace {

void validate(const DenoiseOptions& o) {
  auto bad = [](const std::string& what) { throw InputError("denoise: " + what); };
  if (!(o.noiseLevel >= 0) || !std::isfinite(o.noiseLevel))
    bad("noise level must be >= 0 (0: estimate it; got " + std::to_string(o.noiseLevel) + ")");
  if (!(o.strength > 0) || !std::isfinite(o.strength)) bad("strength must be > 0 (got " + std::to_string(o.strength) + ")");
  if (!(o.detailBoundRatio >= 0 && o.detailBoundRatio <= 1))
    bad("detail bound ratio must be within [0, 1] (got " + std::to_string(o.detailBoundRatio) + ")");
  if (!(o.gradientRiskWeight >= 0 && o.gradientRiskWeight <= 10))
    bad("gradient risk weight must be within [0, 10] (got " + std::to_string(o.gradientRiskWeight) + ")");
  if (!(o.impulseSpectrumKurtosis >= 0) || !std::isfinite(o.impulseSpectrumKurtosis))
    bad("impulse spectrum kurtosis must be >= 0 (0: not used; got " + std::to_string(o.impulseSpectrumKurtosis) + ")");
  if (!(o.blendSpread >= 0 && o.blendSpread <= 1000)) bad("blend spread must be within [0, 1000] (got " + std::to_string(o.blendSpread) + ")");
  if (!(o.levelLean > 0 && o.levelLean <= 10)) bad("level lean must be within (0, 10] (got " + std::to_string(o.levelLean) + ")");
  if (o.rangeBandwidths.empty()) bad("range bandwidths need at least one candidate h_r");
  for (double hr : o.rangeBandwidths)
    if (!(hr > 0) || !std::isfinite(hr)) bad("range bandwidth h_r must be > 0 (got " + std::to_string(hr) + ")");
  if (o.presmoothing.empty()) bad("presmoothing needs at least one candidate step count");
  for (int k : o.presmoothing)
    if (k < 0 || k > 10000) bad("presmoothing steps must be in [0, 10000] (got " + std::to_string(k) + ")");
  for (size_t i = 0; i < o.taubinOnlySteps.size(); ++i)
    if (o.taubinOnlySteps[i] < 1 || o.taubinOnlySteps[i] > 10000 || (i > 0 && o.taubinOnlySteps[i] <= o.taubinOnlySteps[i - 1]))
      bad("Taubin-only step counts must ascend within [1, 10000] (got " + std::to_string(o.taubinOnlySteps[i]) + " at " +
          std::to_string(i) + ")");
  if (!(o.candidateTaubin.lambda > 0) || !(o.candidateTaubin.mu < -o.candidateTaubin.lambda))
    bad("Taubin-only candidates need lambda > 0 and mu < -lambda (got " + std::to_string(o.candidateTaubin.lambda) + ", " +
        std::to_string(o.candidateTaubin.mu) + ")");
  if (o.lightStart < 0 || o.lightStart > 10000) bad("light start steps must be in [0, 10000] (got " + std::to_string(o.lightStart) + ")");
  if (!(o.lightStartTurn > 0) || !std::isfinite(o.lightStartTurn))
    bad("light start turn must be > 0 (got " + std::to_string(o.lightStartTurn) + ")");
  if (!(o.taubinOnlyMargin >= 0) || !std::isfinite(o.taubinOnlyMargin))
    bad("Taubin-only margin must be >= 0 (got " + std::to_string(o.taubinOnlyMargin) + ")");
  if (o.maxPasses < 1 || o.maxPasses > 10000) bad("maximum passes must be in [1, 10000] (got " + std::to_string(o.maxPasses) + ")");
  if (o.patience < 1) bad("patience must be at least 1 (got " + std::to_string(o.patience) + ")");
  if (!(o.planarKeep >= 0 && o.planarKeep <= 1))
    bad("planar keep must be in [0, 1] (got " + std::to_string(o.planarKeep) + ")");
  if (!(o.planarLevelShare >= 0 && o.planarLevelShare <= 1))
    bad("planar level share must be in [0, 1] (got " + std::to_string(o.planarLevelShare) + ")");
  if (o.highFrequencyMinSamples < 0)
    bad("high-frequency minimum samples must be >= 0 (got " + std::to_string(o.highFrequencyMinSamples) + ")");
  if (o.impulseSpectrumMinSamples < 0)
    bad("impulse spectrum minimum samples must be >= 0 (got " + std::to_string(o.impulseSpectrumMinSamples) + ")");
  if (!(o.impulseSpectrumVeto >= 0) || !std::isfinite(o.impulseSpectrumVeto))
    bad("impulse spectrum veto must be >= 0 (got " + std::to_string(o.impulseSpectrumVeto) + ")");
  if (o.fixedPasses < 0 || o.fixedPasses > 10000) bad("fixed passes must be in [0, 10000] (got " + std::to_string(o.fixedPasses) + ")");
  if (o.riskNormalSmoothing < 0 || o.riskNormalSmoothing > 10000)
    bad("risk normal smoothing must be in [0, 10000] steps (got " + std::to_string(o.riskNormalSmoothing) + ")");
  if (o.vertexIterations < 1 || o.vertexIterations > 10000)
    bad("vertex iterations must be in [1, 10000] (got " + std::to_string(o.vertexIterations) + ")");
  if (o.tieProbes < 0 || o.tieProbes > 100) bad("tie probes must be in [0, 100] (got " + std::to_string(o.tieProbes) + ")");
  if (!(o.tieMargin >= 0) || !std::isfinite(o.tieMargin))
    bad("tie margin must be >= 0 (got " + std::to_string(o.tieMargin) + ")");
  if (!(o.tieStandardErrors >= 0) || !std::isfinite(o.tieStandardErrors))
    bad("tie standard errors must be >= 0 (got " + std::to_string(o.tieStandardErrors) + ")");
  if (o.probeSpacing < 1 || o.probeSpacing > 100) bad("probe spacing must be in [1, 100] edges (got " + std::to_string(o.probeSpacing) + ")");
  if (!(o.impulseKurtosis >= 0) || !std::isfinite(o.impulseKurtosis))
    bad("impulse kurtosis must be >= 0 (0: always; got " + std::to_string(o.impulseKurtosis) + ")");
  if (!(o.impulseShrink >= 0) || !std::isfinite(o.impulseShrink))
    bad("impulse shrink must be >= 0 (0: never; got " + std::to_string(o.impulseShrink) + ")");
}

// docs/denoising.md#impulsive-noise. The displacement d = (x − y)·N of every vertex that has an N.
std::vector<double> displacementsAlongN(const std::vector<Vec3>& input, const std::vector<Vec3>& x,
                                        const std::vector<Vec3>& normals) {
  std::vector<double> d;
  d.reserve(x.size());
  for (size_t v = 0; v < x.size(); ++v)
    if (normals[v].squaredNorm() != 0) d.push_back((x[v] - input[v]).dot(normals[v]));
  return d;
}

// Their kurtosis E[d⁴] / E[d²]²: about 3 when every vertex moved by Gaussian noise is pulled back,
// about 1 / (share moved) when only a few were.
double kurtosis(const std::vector<double>& d) {
  double m2 = 0, m4 = 0;
  for (double e : d) {
    m2 += e * e;
    m4 += e * e * e * e;
  }
  return m2 > 0 ? m4 * static_cast<double>(d.size()) / (m2 * m2) : 0.0;
}

// Their robust spread, 1.4826 × the median of |d| (the standard deviation, were d Gaussian around
// 0): under impulsive noise, the scale of what the winner did to the vertices the noise left alone,
// which the outliers do not move.
double robustSpread(std::vector<double> d) {
  if (d.empty()) return 0.0;
  for (double& e : d) e = std::abs(e);
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return 1.4826 * d[d.size() / 2];
}

// The share of the mesh's adjacencies (the two vertices of an edge, the two faces across it) whose
// indices lie more than kFar apart, under the renumbering r (null: as numbered): those that a walk
// over neighbourhoods in index order is likely to read from outside the cache
// (docs/denoising.md#speed-and-memory, spatial order).
double farAdjacencies(const Mesh& mesh, const Renumbering* r) {
  constexpr int kFar = 4096;
  auto vertex = [&](int v) { return r ? r->newVertex[v] : v; };
  auto face = [&](int f) { return r ? r->newFace[f] : f; };
  long far = 0, all = 0;
  for (int h = 0; h < mesh.halfedgeCount(); ++h) {
    const int t = mesh.twin(h);
    if (t >= 0 && t < h) continue;  // each edge once
    ++all;
    far += std::abs(vertex(mesh.tail(h)) - vertex(mesh.head(h))) > kFar;
    if (t >= 0) far += std::abs(face(Mesh::faceOf(h)) - face(Mesh::faceOf(t))) > kFar;
  }
  return all > 0 ? static_cast<double>(far) / (2 * all) : 0.0;
}

// One copy of the mesh being denoised: its positions and the face normals its guard refers to.
struct Track {
  std::vector<Vec3> positions;
  const VertexUpdateOptions* update = nullptr;  // with the reference normals of its start, shared
};

// The two operations a candidate is made of, on the caller's mesh: Taubin steps, and passes of
// [face normal shift over the neighbourhoods → vertex update]. The mesh lends its connectivity; each
// track's positions are swapped in and out (a copy would cost 50 bytes a vertex).
class Passes {
 public:
  Passes(Mesh& work, const DenoiseOptions& o, const Progress& progress) : work_(work), o_(o) {
    parallel_.threads = o.threads;
    taubin_ = o.supportSmoothing;
    taubin_.parallel = parallel_;
    candidateTaubin_ = o.candidateTaubin;
    candidateTaubin_.parallel = parallel_;
    // Neighbourhoods on a smoothed support, found once.
    progress.step(0, "support");
    FaceNeighborhoodOptions hoodOptions = o.neighborhood;
    hoodOptions.parallel.threads = o.threads;
    const std::vector<Vec3> start = work.positions();
    taubinSmooth(work, taubin_);
    hoods_ = faceNeighborhoods(work, hoodOptions, progress.slice(0, 0.1));
    work.positions() = start;
  }

  size_t neighborhoodBytes() const { return hoods_.bytes(); }
  // Taubin smoothing as the support, the candidates' pre-smoothing and the risk's normals use it: the
  // support's settings, on the denoiser's threads.
  const TaubinOptions& taubin() const { return taubin_; }

  // Vertex update options of a start (input or probed input): its face normals are the flip guard's
  // reference for every candidate and pass that starts there.
  VertexUpdateOptions updateFrom(const std::vector<Vec3>& start) {
    VertexUpdateOptions update;
    update.iterations = o_.vertexIterations;
    update.flipGuard = FlipGuard::InputOrTarget;
    update.parallel = parallel_;
    work_.positions() = start;
    update.referenceNormals = referenceNormalsOf(work_);
    // Every pass of every start gathers over the same lists (the shift gives every face a target
    // but a degenerate one): listed once, at the first pass (docs/denoising.md#speed-and-memory).
    update.plan = &plan_;
    return update;
  }

  void presmooth(Track& t, int steps) { smooth(t, taubin_, steps); }

  // `steps` more steps of the Taubin-only candidates' smoothing (DenoiseOptions::candidateTaubin).
  void taubinOnly(Track& t, int steps) { smooth(t, candidateTaubin_, steps); }

  // A candidate computed alone: `steps` Taubin steps, then `count` passes at h_r; or, for a Taubin-only
  // candidate, `steps` steps of its own smoothing.
  void candidate(Track& t, int steps, bool taubinOnlyCandidate, int count, double rangeBandwidth, DenoiseResult& result) {
    if (taubinOnlyCandidate) return taubinOnly(t, steps);
    presmooth(t, steps);
    for (int i = 0; i < count; ++i) pass(t, rangeBandwidth, result);
  }

  void pass(Track& t, double rangeBandwidth, DenoiseResult& result) {
    // The track's positions move into the mesh (the update returns new ones): one copy fewer held
    // while the update runs, which is when memory peaks.
    work_.positions() = std::move(t.positions);
    if (plan_.firstFace.empty()) plan_ = planVertexUpdate(work_, *t.update);
    std::vector<Vec3> targets = shiftFaceNormals(hoods_, work_, rangeBandwidth, parallel_);
    VertexUpdateResult u = updateVertices(work_, std::move(targets), *t.update);
    result.limitedSteps += u.limitedSteps;
    t.positions = std::move(u.positions);
    ++result.passesRun;
  }

 private:
  Mesh& work_;
  const DenoiseOptions& o_;
  ParallelOptions parallel_;
  void smooth(Track& t, TaubinOptions taubin, int steps) {
    if (steps == 0) return;
    taubin.iterations = steps;
    work_.positions() = t.positions;
    taubinSmooth(work_, taubin);
    t.positions = work_.positions();
  }

  TaubinOptions taubin_, candidateTaubin_;
  FaceNeighborhoods hoods_;
  VertexUpdatePlan plan_;
};

// What candidates are ranked by: their position risk over σ², so that the race's tolerances are
// fractions of the noise's risk.
struct Ranking {
  const RiskEstimate& risk;
  double sigma = 0;  // the noise level candidates are ranked with (before the strength)
  double operator()(const RiskSums& s) const {
    const double ranked = sigma * risk.strength();
    return risk.at(s, sigma).ranked / (ranked * ranked);
  }
};

// The candidates race in step, one pass each in turn. A candidate stops after `patience` passes that
// did not lower its rank by kTolerance of the noise's, and, once it has run `patience` passes, as
// soon as its best rank is kRaceMargin of the noise's above the leader's: it is unlikely to catch
// up, and a lead smaller than that is within what one probe can tell apart anyway. The passes it
// would have run are half the cost (docs/denoising.md#the-race, with the figures behind kTolerance).
// Every score is kept (its sums), so that the noise level can be refined afterwards and the
// candidates ranked again.
class CandidateRace {
  static constexpr double kTolerance = 0.0015, kRaceMargin = 0.005;

 public:
  // newVertex: where the passes run in spatial order, the caller's vertex numbers to theirs (empty
  // otherwise); onCandidate is handed positions in the caller's order.
  CandidateRace(const DenoiseOptions& o, const RiskEstimate& risk, const Ranking& rank, DenoiseResult& result,
                const std::vector<int>& newVertex)
      : o_(o), risk_(risk), rank_(rank), result_(result), newVertex_(newVertex) {}

  struct Run {
    int steps;
    double rangeBandwidth;
    Track x, xp;
    int t = 0, lastBest = 0;
    double anchor = 0;  // the rank at the last pass that lowered it by more than the tolerance
    double best = 0;
    bool active = true;
  };
  struct Scored {
    int steps, passes;
    double rangeBandwidth;
    RiskSums sums;
    bool taubinOnly = false;
  };

  void add(Run run) {
    runs_.push_back(std::move(run));
    scoreRun(runs_.back());
  }

  void run(Passes& passes, const Progress& progress) {
    for (int done = 0;;) {
      bool any = false;
      for (Run& run : runs_) {
        if (!run.active) continue;
        // Done over done plus the most the runs still going can take: it only grows, and it
        // jumps when the race stops a run.
        double left = 0;
        for (const Run& r : runs_)
          if (r.active) left += o_.maxPasses - r.t;
        progress.step(0.1 + 0.9 * done / (done + left), "denoise passes");
        passes.pass(run.x, run.rangeBandwidth, result_);
        passes.pass(run.xp, run.rangeBandwidth, result_);
        ++run.t;
        ++done;
        scoreRun(run);
        if (run.t - run.lastBest >= o_.patience || run.t >= o_.maxPasses) run.active = false;
        any = any || run.active;
      }
      if (!any) break;
      double leader = runs_.front().best;
      for (const Run& run : runs_) leader = std::min(leader, run.best);
      for (Run& run : runs_)
        if (run.active && run.t >= o_.patience && run.best > leader + kRaceMargin) run.active = false;
      halve();
    }
  }

  // Every `patience` passes, the worse half of the runs still going stop (the best by rank stay):
  // with four runs, at most two run beyond the first checkpoint and one beyond the second.
  void halve() {
    if (!o_.halvingRace) return;
    std::vector<Run*> active;
    for (Run& run : runs_)
      if (run.active) active.push_back(&run);
    if (active.size() < 2 || active.front()->t % o_.patience != 0 || active.front()->t == 0) return;
    std::stable_sort(active.begin(), active.end(), [](const Run* a, const Run* b) { return a->best < b->best; });
    for (size_t i = (active.size() + 1) / 2; i < active.size(); ++i) active[i]->active = false;
  }

  // A Taubin-only candidate: scored once, no passes follow.
  void addTaubinOnly(int steps, const Track& x, const Track& xp) {
    offer(steps, 0.0, 0, x.positions, risk_.sums(x.positions, xp.positions), true);
  }

  const std::vector<Scored>& scored() const { return scored_; }
  // The runs' tracks, once the race is over (the scores and the best stay).
  void releaseRuns() { std::vector<Run>().swap(runs_); }
  // The best candidate by the race's ranking: its positions (moved out) and index in scored().
  std::vector<Vec3> takeBest() { return std::move(best_); }
  size_t bestIndex() const { return bestIndex_; }

 private:
  void scoreRun(Run& run) {
    const double value = offer(run.steps, run.rangeBandwidth, run.t, run.x.positions, risk_.sums(run.x.positions, run.xp.positions));
    if (run.t == 0 || value < run.anchor - kTolerance) {
      run.anchor = value;
      run.lastBest = run.t;
    }
    if (run.t == 0 || value < run.best) run.best = value;
  }

  double offer(int steps, double hr, int passes, const std::vector<Vec3>& x, const RiskSums& sums,
               bool taubinOnly = false) {
    if (o_.onCandidate) {
      const double risk = risk_.at(sums, rank_.sigma).positionUnbiased;
      if (newVertex_.empty()) {
        o_.onCandidate(steps, passes, x, risk);
      } else {
        std::vector<Vec3> callers(x.size());
        for (size_t v = 0; v < x.size(); ++v) callers[v] = x[newVertex_[v]];
        o_.onCandidate(steps, passes, callers, risk);
      }
    }
    scored_.push_back({steps, passes, hr, sums, taubinOnly});
    const double value = rank_(sums);
    if (best_.empty() || value < bestValue_) {
      bestValue_ = value;
      best_ = x;
      bestIndex_ = scored_.size() - 1;
    }
    return value;
  }

  const DenoiseOptions& o_;
  const RiskEstimate& risk_;
  const Ranking& rank_;
  DenoiseResult& result_;
  const std::vector<int>& newVertex_;
  std::vector<Run> runs_;
  std::vector<Scored> scored_;
  std::vector<Vec3> best_;
  size_t bestIndex_ = 0;
  double bestValue_ = 0;
};

// A tie between starts (docs/denoising.md#ties-between-starts): the best candidate of each start
// within o.tieMargin of the leader's rank is scored again with more probes, other signs on the same
// vertices, until the leader by mean rank leads every other by o.tieStandardErrors standard errors
// of the difference or o.tieProbes probes have run. If no leader is that far ahead after them all, the
// contenders it does not lead by that much are tied along N, and with o.tieByNormals the one whose
// normals turn least across an edge on average wins. Returns the winner's index in `scored`, moves its
// positions into x and sets `sums` to its sums with the mean divergence of the probes. `leaderX` holds
// the positions of scored[leaderIndex] (the race's best). The start of excludedStart steps (-1: none)
// takes no part.
size_t settleTie(const Mesh& mesh, const DenoiseOptions& o, Passes& passes, RiskEstimate& risk, const Ranking& rank,
                 const std::vector<CandidateRace::Scored>& scored, size_t chosen, size_t leaderIndex,
                 std::vector<Vec3>& leaderX, const std::vector<Vec3>& input, const VertexUpdateOptions& inputUpdate,
                 const Progress& progress, DenoiseResult& result, std::vector<Vec3>& x, RiskSums& sums,
                 int excludedStart) {
  struct Contender {
    size_t index;
    std::vector<Vec3> x;
    std::vector<double> ranks;  // one per probe, the race's first
    double div = 0;             // their divergences' sum
    double mean() const { return std::accumulate(ranks.begin(), ranks.end(), 0.0) / ranks.size(); }
    double variance() const {
      const double m = mean();
      double v = 0;
      for (double r : ranks) v += (r - m) * (r - m);
      return v / (ranks.size() - 1);
    }
  };
  // The best of each start (ties in rank to the earlier scored), if within the margin.
  std::vector<Contender> contenders;
  for (size_t i = 0; i < scored.size(); ++i) {
    const double r = rank(scored[i].sums);
    auto same = std::find_if(contenders.begin(), contenders.end(),
                             [&](const Contender& c) {
                               return scored[c.index].steps == scored[i].steps && scored[c.index].taubinOnly == scored[i].taubinOnly;
                             });
    if (same == contenders.end())
      contenders.push_back({i, {}, {r}, scored[i].sums.div});
    else if (r < same->ranks.front())
      *same = {i, {}, {r}, scored[i].sums.div};
  }
  const double top = rank(scored[chosen].sums);
  // Taubin-only candidates contend only when one won: behind a candidate with passes they lost by the
  // margin rule, whatever their rank.
  std::erase_if(contenders, [&](const Contender& c) {
    const CandidateRace::Scored& s = scored[c.index];
    return c.ranks.front() > top + o.tieMargin || (s.taubinOnly && !scored[chosen].taubinOnly) ||
           (!s.taubinOnly && s.steps == excludedStart);
  });
  sums = scored[chosen].sums;
  if (contenders.size() < 2 || o.tieProbes == 0) return chosen;

  for (Contender& c : contenders) {
    const CandidateRace::Scored& s = scored[c.index];
    if (c.index == leaderIndex && !leaderX.empty()) {
      c.x = std::move(leaderX);
      continue;
    }
    Track track{input, &inputUpdate};
    passes.candidate(track, s.steps, s.taubinOnly, s.passes, s.rangeBandwidth, result);
    c.x = std::move(track.positions);
  }
  auto leader = [&] {
    size_t l = 0;
    for (size_t c = 1; c < contenders.size(); ++c)
      if (contenders[c].mean() < contenders[l].mean()) l = c;
    return l;
  };
  auto ahead = [&o](const Contender& c, const Contender& l) {
    return c.mean() - l.mean() > o.tieStandardErrors * std::sqrt((c.variance() + l.variance()) / c.ranks.size());
  };
  bool apart = false;
  for (int k = 1; k <= o.tieProbes && !apart; ++k) {
    progress.step(1, "settling a tie");
    // Seeds apart from the race's (and from small user seeds) by multiples of 2⁶⁴/φ.
    risk.reseed(o.seed + 0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(k));
    const std::vector<Vec3> probed = risk.probedInput();
    const VertexUpdateOptions probedUpdate = passes.updateFrom(probed);
    for (Contender& c : contenders) {
      const CandidateRace::Scored& s = scored[c.index];
      Track xp{probed, &probedUpdate};
      passes.candidate(xp, s.steps, s.taubinOnly, s.passes, s.rangeBandwidth, result);
      const RiskSums probe = risk.sums(c.x, xp.positions);
      c.ranks.push_back(rank(probe));
      c.div += probe.div;
    }
    result.tieProbes = k;
    const Contender& l = contenders[leader()];
    apart = true;
    for (const Contender& c : contenders)
      if (&c != &l) apart = apart && ahead(c, l);
  }
  risk.reseed(o.seed);
  size_t wonAt = leader();
  if (!apart && o.tieByNormals) {
    const Contender& l = contenders[wonAt];
    double least = meanNormalTurn(mesh, l.x);
    for (size_t c = 0; c < contenders.size(); ++c) {
      if (c == wonAt || ahead(contenders[c], l)) continue;
      const double turn = meanNormalTurn(mesh, contenders[c].x);
      if (turn < least) {
        least = turn;
        wonAt = c;
      }
    }
    result.tieByNormals = true;
  }
  Contender& won = contenders[wonAt];
  x = std::move(won.x);
  sums = scored[won.index].sums;
  sums.div = won.div / won.ranks.size();
  return won.index;
}

// docs/denoising.md#impulsive-noise ("Vertices on untouched planes"). On a part of flat faces that
// the noise mostly left alone, a vertex that fits an untouched plane (within `bar` of the nearest
// plane of a confirmed face of its two-ring, and in the plane of the face across the edge opposite
// it in one of its faces), each of whose faces off its neighbours' planes holds another vertex
// that does not fit, was not moved by the noise: it keeps its input position. Returns how many
// moved back.
int keepUntouchedPlanes(const Mesh& mesh, const std::vector<Vec3>& input, std::vector<Vec3>& x, const DenoiseOptions& o,
                        double bar) {
  double share = 0;
  std::vector<char> confirmed, inPlane;
  const std::vector<double> residual = planarResiduals(mesh, input, &share, &confirmed, &inPlane);
  if (share < o.planarLevelShare) return 0;
  std::vector<char> fits(x.size(), 0), explained(x.size(), 1);
  for (size_t v = 0; v < x.size(); ++v) fits[v] = residual[v] >= 0 && residual[v] <= bar && inPlane[v];
  for (int f = 0; f < mesh.faceCount(); ++f) {
    if (confirmed[f]) continue;
    const Face& c = mesh.face(f);
    for (int k = 0; k < 3; ++k)
      if (fits[c[(k + 1) % 3]] && fits[c[(k + 2) % 3]]) explained[c[k]] = 0;
  }
  int kept = 0;
  for (size_t v = 0; v < x.size(); ++v)
    if (fits[v] && explained[v] && x[v] != input[v]) {
      x[v] = input[v];
      ++kept;
    }
  return kept;
}

}  // namespace

void correctOutliers(const Mesh& mesh, const std::vector<Vec3>& input, std::vector<Vec3>& x,
                     const std::vector<Vec3>& normals, double tau) {
  const int n = mesh.vertexCount();
  // Each vertex's garrote weight; -1 for a vertex without an N, which keeps x.
  std::vector<double> weight(n, -1.0);
  for (int v = 0; v < n; ++v) {
    if (normals[v].squaredNorm() == 0) continue;
    const double d = (x[v] - input[v]).dot(normals[v]);
    weight[v] = d * d > tau * tau ? 1 - tau * tau / (d * d) : 0.0;
  }
  const std::vector<Vec3> smoothed = x;
  for (int v = 0; v < n; ++v) {
    const double w = weight[v];
    if (w < 0) continue;
    if (w == 0) {
      x[v] = input[v];
      continue;
    }
    // What the smoothing took from the neighbours, each trusted as far as it is not an outlier.
    Vec3 detail = Vec3::Zero();
    double trust = 0;
    for (int j : mesh.neighbors(v)) {
      if (weight[j] < 0) continue;
      detail += (1 - weight[j]) * (input[j] - smoothed[j]);
      trust += 1 - weight[j];
    }
    if (trust > 0) detail /= trust;
    x[v] = input[v] + w * (smoothed[v] + detail - input[v]);
  }
}

double blendWeight(double gap, double difference, double spread) {
  if (!(difference > 0) || !(spread > 0)) return 0.0;
  return std::clamp(0.5 * (1 - gap / (spread * difference)), 0.0, 1.0);
}

DenoiseResult denoiseDefault(Mesh& mesh, const DenoiseOptions& o, const Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  validate(o);
  DenoiseResult result;
  result.filteredVertices = mesh.vertexCount();
  result.threads = resolveThreads(o.threads);
  const double ael = averageEdgeLength(mesh);
  double level = o.noiseLevel;
  NoiseEstimate estimate;
  // The level the candidates are finally ranked with (docs/denoising.md#the-noise-level): read
  // from the input's highest frequencies before the passes move it. 0: not used, or no vertex far
  // enough from a crease or a boundary.
  double highLevel = 0, highReading = 0;
  int highSamples = 0;
  PlanarNoise planar;  // read where the spectrum reads too few vertices (DenoiseOptions::planarLevelShare)
  const bool rankWithHigh = level == 0 && o.refineNoise && o.highFrequencyLevel;
  if (rankWithHigh || (o.impulseShrink > 0 && o.impulseSpectrumKurtosis > 0)) {
    ParallelOptions par;
    par.threads = o.threads;
    const HighFrequencyNoise high = highFrequencyNoise(mesh, par);
    // Too few vertices far from every crease and boundary, and the reading is one of a handful of
    // samples: its level is blended with the refined one below, and its kurtosis not used
    // (docs/denoising.md#the-noise-level, "A reading of few vertices").
    highReading = high.level;
    highSamples = high.samples;
    if (high.samples >= o.highFrequencyMinSamples) {
      if (rankWithHigh) highLevel = high.level;
      result.spectrumKurtosis = high.kurtosis;
    } else if (rankWithHigh && o.planarLevelShare > 0) {
      planar = planarNoise(mesh);
    }
  }
  if (level == 0) {
    estimate = estimateNoise(mesh);
    level = estimate.level;
    result.noiseEstimated = true;
  }
  level *= o.strength;
  result.noiseLevel = level;
  auto finish = [&] {
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  };
  if (!(level > 0)) return finish();  // nothing to remove
  const double sigma = level * ael;
  // The passes run in spatial order (DenoiseOptions::spatialOrder); the caller's order comes back on
  // the way out, after an exception too (the noise estimates above have read the caller's order).
  struct Order {
    Mesh& mesh;
    // The caller's numbers to the passes' while they run. Without newFace where every face is its
    // own input face: the faces are put back by it (Mesh::renumber), which saves 8 bytes a vertex at
    // the peak.
    Renumbering renumbering;
    ~Order() {
      if (renumbering.newVertex.empty()) return;
      invert(renumbering);
      mesh.renumber(renumbering);
    }
  } order{mesh, {}};
  if (o.spatialOrder) {
    // Taken where at least 1% of the adjacencies lie far apart and it halves them: a mesh numbered
    // along its surface (a grid, the rings of a surface of revolution) keeps its own order, which a
    // Z-curve does not better, and so does a mesh with too few far adjacencies to be worth results
    // that differ in their last digits.
    result.farAdjacencies = farAdjacencies(mesh, nullptr);
    Renumbering spatial;
    if (result.farAdjacencies >= 0.01) spatial = spatialOrder(mesh);
    if (!spatial.newVertex.empty() && farAdjacencies(mesh, &spatial) < 0.5 * result.farAdjacencies) {
      bool facesByInput = true;
      for (int f = 0; f < mesh.faceCount() && facesByInput; ++f) facesByInput = mesh.inputFace(f) == f;
      order.renumbering = std::move(spatial);
      mesh.renumber(order.renumbering);
      result.spatialOrder = true;
      if (facesByInput) std::vector<int>().swap(order.renumbering.newFace);
    }
  }
  const std::vector<Vec3> input = mesh.positions();
  // The passes run on `mesh` itself: on an exception it gets its input back. assign() into a vector
  // of the same size does not allocate, so the restore cannot throw.
  struct Restore {
    Mesh& mesh;
    const std::vector<Vec3>& input;
    bool armed = true;
    ~Restore() {
      if (armed) mesh.positions().assign(input.begin(), input.end());
    }
  } restore{mesh, input};

  Passes passes(mesh, o, progress);
  result.neighborhoodBytes = passes.neighborhoodBytes();
  const VertexUpdateOptions inputUpdate = passes.updateFrom(input);

  if (o.fixedPasses > 0) {
    const double hr = o.rangeBandwidths.front();
    Track x{input, &inputUpdate};
    passes.presmooth(x, o.presmoothing.front());
    for (int t = 1; t <= o.fixedPasses; ++t) {
      progress.step(0.1 + 0.9 * (t - 1) / o.fixedPasses, "denoise passes");
      passes.pass(x, hr, result);
    }
    result.presmoothingSteps = o.presmoothing.front();
    result.rangeBandwidth = hr;
    result.passes = o.fixedPasses;
    mesh.positions() = std::move(x.positions);
    restore.armed = false;
    return finish();
  }

  // The noise level the race ranks with: the estimate, or with refineNoise its upper estimate
  // (refined below from the candidates).
  const double lowSigma = sigma / o.strength;
  const double raceSigma = o.refineNoise && result.noiseEstimated ? std::max(lowSigma, estimate.upperLevel * ael) : lowSigma;
  RiskOptions riskOptions;
  riskOptions.normalSmoothing = o.riskNormalSmoothing;
  riskOptions.taubin = passes.taubin();
  riskOptions.seed = o.seed;
  riskOptions.probeSpacing = o.probeSpacing;
  riskOptions.boundedDivergence = o.boundedDivergence;
  riskOptions.gradientWeight = o.gradientRiskWeight;
  if (result.spatialOrder) riskOptions.visitOrder = &order.renumbering.newVertex;
  RiskEstimate risk(mesh, input, raceSigma, o.strength, riskOptions);
  std::vector<Vec3> probed = risk.probedInput();
  const VertexUpdateOptions probedUpdate = passes.updateFrom(probed);

  Ranking rank{risk, raceSigma};
  CandidateRace race(o, risk, rank, result, order.renumbering.newVertex);
  using Scored = CandidateRace::Scored;
  const std::vector<Scored>& scored = race.scored();
  // The candidate of least rank (at the ranking's level when called) among those `admits` takes,
  // ties to the earlier scored; scored.size() where none.
  auto bestOf = [&](auto&& admits) {
    size_t b = scored.size();
    for (size_t i = 0; i < scored.size(); ++i)
      if (admits(scored[i]) && (b == scored.size() || rank(scored[i].sums) < rank(scored[b].sums))) b = i;
    return b;
  };
  // A Taubin-only candidate c must lead the best candidate with passes (of those `admits` takes) by
  // the margin; otherwise that one.
  auto withMargin = [&](size_t c, auto&& admits) {
    if (!scored[c].taubinOnly) return c;
    const size_t b = bestOf([&](const Scored& s) { return !s.taubinOnly && admits(s); });
    return b < scored.size() && rank(scored[b].sums) - rank(scored[c].sums) < o.taubinOnlyMargin ? b : c;
  };
  const auto any = [](const Scored&) { return true; };

  auto addStart = [&](int steps) {
    // Smoothed once per step count; the runs of the other bandwidths start from copies.
    Track x{input, &inputUpdate}, xp{probed, &probedUpdate};
    passes.presmooth(x, steps);
    passes.presmooth(xp, steps);
    for (size_t i = 0; i < o.rangeBandwidths.size(); ++i) {
      const bool last = i + 1 == o.rangeBandwidths.size();
      CandidateRace::Run run{steps, o.rangeBandwidths[i], last ? std::move(x) : x, last ? std::move(xp) : xp};
      race.add(std::move(run));
    }
  };
  for (int steps : o.presmoothing) addStart(steps);
  {
    // Taubin-only candidates, each step count continued from the last.
    Track x{input, &inputUpdate}, xp{probed, &probedUpdate};
    int done = 0;
    for (int steps : o.taubinOnlySteps) {
      passes.taubinOnly(x, steps - done);
      passes.taubinOnly(xp, steps - done);
      done = steps;
      race.addTaubinOnly(steps, x, xp);
    }
  }
  // The light start (DenoiseOptions::lightStart): where the ladder ranks least at its first rung,
  // the noise wants little smoothing, as on thin parts and very uneven meshes.
  if (o.lightStart > 0 && !o.taubinOnlySteps.empty() &&
      std::find(o.presmoothing.begin(), o.presmoothing.end(), o.lightStart) == o.presmoothing.end() &&
      !(o.impulseSpectrumKurtosis > 0 && result.spectrumKurtosis > o.impulseSpectrumKurtosis)) {
    const size_t least = bestOf([](const Scored& c) { return c.taubinOnly; });
    if (least < scored.size() && scored[least].steps == o.taubinOnlySteps.front()) {
      addStart(o.lightStart);
      result.lightStartRaced = true;
    }
  }
  std::vector<Vec3>().swap(probed);  // the probe tracks have started from it
  race.run(passes, progress);

  // Refinement: the least noise variance a good candidate implies, kept between the two estimates,
  // then every candidate ranked again with it; the winner is recomputed if it changed.
  size_t chosen = race.bestIndex();
  double finalSigma = raceSigma;
  rank.sigma = finalSigma;
  if (o.refineNoise && result.noiseEstimated) {
    if (highLevel > 0) {
      // The level from the top of the spectrum, ranked with the lean (a level a little high smooths
      // the normals a little more, which pays).
      finalSigma = highLevel * ael;
      rank.sigma = o.levelLean * finalSigma;
    } else {
      double implied = raceSigma * raceSigma, linearImplied = implied;
      for (const auto& c : scored) {
        const double v = risk.impliedVariance(c.sums);
        if (v > 0) implied = std::min(implied, v);
        const double w = c.passes == 0 ? risk.linearImpliedVariance(c.sums) : 0.0;
        if (w > 0) linearImplied = std::min(linearImplied, w);
      }
      const double ratio = o.detailBoundRatio;
      if (linearImplied < ratio * ratio * implied) implied = linearImplied;
      finalSigma = std::clamp(std::sqrt(implied), 0.5 * lowSigma, raceSigma);
      rank.sigma = finalSigma;
      if (planar.samples > 0 && planar.confirmedShare >= o.planarLevelShare) {
        // Flat faces the noise mostly left alone: the level read against their planes (a clean
        // part reads 0: ranked with a level far below any candidate's change, it is kept).
        finalSigma = std::max(planar.level, 1e-3) * ael;
        rank.sigma = o.levelLean * finalSigma;
        result.planarLevel = true;
      } else if (rankWithHigh && highReading > 0) {
        // A reading of few vertices, weighted by how many.
        const double w = highSamples / (highSamples + 5.0);
        finalSigma = std::exp(w * std::log(highReading * ael) + (1 - w) * std::log(finalSigma));
        rank.sigma = std::pow(o.levelLean, w) * finalSigma;
      }
    }
    for (size_t i = 0; i < scored.size(); ++i)
      if (rank(scored[i].sums) < rank(scored[chosen].sums)) chosen = i;
  }
  chosen = withMargin(chosen, any);
  race.releaseRuns();
  // The light start's winner stands only if its normals turn no more than lightStartTurn times as
  // much as those of the best of the rest (chosen as above without it).
  const auto isLight = [&](const Scored& c) { return result.lightStartRaced && !c.taubinOnly && c.steps == o.lightStart; };
  if (isLight(scored[chosen])) {
    const auto notLight = [&](const Scored& c) { return !isLight(c); };
    const size_t rest = withMargin(bestOf(notLight), notLight);
    auto turnOf = [&](const Scored& c) {
      Track track{input, &inputUpdate};
      passes.candidate(track, c.steps, c.taubinOnly, c.passes, c.rangeBandwidth, result);
      return meanNormalTurn(mesh, track.positions);
    };
    if (turnOf(scored[chosen]) > o.lightStartTurn * turnOf(scored[rest])) {
      chosen = rest;
      result.lightStartTurnedDown = true;
    }
  }
  // Turned down, the light start takes no part in the tie or the blend either.
  const int excludedStart = result.lightStartTurnedDown ? o.lightStart : -1;
  const auto admitted = [&](const Scored& c) { return !(result.lightStartTurnedDown && isLight(c)); };
  std::vector<Vec3> x;
  RiskSums winnerSums;
  {
    std::vector<Vec3> leaderX = race.takeBest();
    chosen = settleTie(mesh, o, passes, risk, rank, scored, chosen, race.bestIndex(), leaderX, input, inputUpdate, progress,
                       result, x, winnerSums, excludedStart);
    if (x.empty() && chosen == race.bestIndex()) x = std::move(leaderX);
  }
  const CandidateRace::Scored& winner = scored[chosen];
  result.presmoothingSteps = winner.steps;
  result.taubinOnly = winner.taubinOnly;
  result.rangeBandwidth = winner.rangeBandwidth;
  result.passes = winner.passes;
  if (finalSigma != raceSigma || raceSigma != lowSigma) result.noiseLevel = finalSigma * o.strength / ael;
  // A correction asked for in any case (a trigger of 0: `--impulse on`) is not overruled.
  const bool correctionForced = o.impulseShrink > 0 && o.impulseKurtosis == 0;
  if (o.inputCandidate && !correctionForced && rank(winnerSums) >= rank(risk.sums(input, risk.probedInput()))) {
    // The input, scored as any candidate is (its rank is 1 up to rounding), is estimated at least as
    // close to the noise-free surface as the best of the others (docs/denoising.md#the-input-as-a-candidate).
    result.keptInput = true;
    result.presmoothingSteps = 0;
    result.taubinOnly = false;
    result.rangeBandwidth = 0;
    result.passes = 0;
    result.estimatedError = finalSigma / ael;  // the input's error is the noise
    return finish();                           // `restore` puts the input back
  }
  const Risk winnerRisk = risk.at(winnerSums, finalSigma);
  // Below a tenth of the noise the estimate is not resolved: one probe's spread is larger, and a
  // winner that set the refined noise level has an estimate of zero by construction.
  const double error = std::sqrt(std::max(0.0, winnerRisk.positionUnbiased));
  result.estimatedError = error >= 0.1 * finalSigma ? error / ael : 0.0;
  if (x.empty()) {
    Track track{input, &inputUpdate};
    passes.candidate(track, winner.steps, winner.taubinOnly, winner.passes, winner.rangeBandwidth, result);
    x = std::move(track.positions);
  }
  if (o.blendSpread > 0) {
    // The blend of least risk (DenoiseOptions::blendSpread): first the best of the other family,
    // then the best with passes from the other start, each against the blend so far.
    auto best = [&](auto&& admits) { return bestOf([&](const Scored& c) { return admitted(c) && admits(c); }); };
    const size_t other = best([&](const CandidateRace::Scored& c) { return c.taubinOnly != winner.taubinOnly; });
    double blendedRank = rank(winnerSums);
    auto blendIn = [&](size_t i, DenoiseResult::Blend& record) {
      if (i == scored.size()) return;
      const CandidateRace::Scored& c = scored[i];
      const double gap = rank(c.sums) - blendedRank;
      // Computed again only within reach: D has not exceeded 0.19 σ² on the tuning set, and a
      // candidate behind by more than spread × D takes no weight.
      constexpr double kBlendReach = 0.25;
      if (gap >= kBlendReach * o.blendSpread) return;
      Track track{input, &inputUpdate};
      passes.candidate(track, c.steps, c.taubinOnly, c.passes, c.rangeBandwidth, result);
      const std::vector<Vec3>& N = risk.normals();
      double squares = 0;
      for (size_t v = 0; v < x.size(); ++v) {
        const double d = (track.positions[v] - x[v]).dot(N[v]);
        squares += d * d;
      }
      const double ranked = rank.sigma * risk.strength();
      const double difference = squares / (std::max(1, risk.measuredVertices()) * ranked * ranked);
      const double w = blendWeight(gap, difference, o.blendSpread);
      if (w == 0) return;
      for (size_t v = 0; v < x.size(); ++v) x[v] = (1 - w) * x[v] + w * track.positions[v];
      blendedRank = (1 - w) * blendedRank + w * rank(c.sums) - w * (1 - w) * difference;
      record = {w, c.steps, c.taubinOnly, c.taubinOnly ? 0.0 : c.rangeBandwidth, c.passes};
    };
    blendIn(other, result.blend);
    // The other start than the winner's or, where Taubin alone won, than the best with passes.
    if (!winner.taubinOnly || other < scored.size()) {
      const int start = winner.taubinOnly ? scored[other].steps : winner.steps;
      blendIn(best([&](const CandidateRace::Scored& c) { return !c.taubinOnly && c.steps != start; }), result.startBlend);
    }
  }
  const std::vector<double> displacements = displacementsAlongN(input, x, risk.normals());
  result.displacementKurtosis = kurtosis(displacements);
  // The spectrum alone, where read from enough vertices for its fourth moment
  // (docs/denoising.md#the-noise-level, "The spectrum alone, from few vertices").
  const bool spectrumSaysImpulsive = o.impulseSpectrumKurtosis > 0 && result.spectrumKurtosis > o.impulseSpectrumKurtosis &&
                                     highSamples >= o.impulseSpectrumMinSamples;
  // The winner's trigger, unless a spectrum read from enough vertices says the noise's tails are
  // light (its kurtosis two standard errors under the veto). Not where the correction is asked for
  // in any case (impulseKurtosis 0: the CLI's --impulse on).
  const bool spectrumVetoes = o.impulseKurtosis > 0 && o.impulseSpectrumVeto > 0 && result.spectrumKurtosis > 0 && highSamples > 0 &&
                              result.spectrumKurtosis + 2 * std::sqrt(24.0 / highSamples) < o.impulseSpectrumVeto;
  const bool winnerSaysImpulsive = result.displacementKurtosis > o.impulseKurtosis && !spectrumVetoes;
  if (o.impulseShrink > 0 && (winnerSaysImpulsive || spectrumSaysImpulsive)) {
    correctOutliers(mesh, input, x, risk.normals(), o.impulseShrink * robustSpread(displacements));
    result.impulseGarrote = true;
    if (o.planarKeep > 0 && o.planarLevelShare > 0) result.planarKept = keepUntouchedPlanes(mesh, input, x, o, o.planarKeep * finalSigma);
  }
  mesh.positions() = std::move(x);
  restore.armed = false;
  return finish();
}

}  // namespace geoshift::denoise_detail
