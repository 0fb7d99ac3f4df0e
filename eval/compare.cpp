#include "compare.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <istream>
#include <map>
#include <numeric>
#include <ostream>
#include <stdexcept>
#include <set>
#include <sstream>
#include <tuple>

#include "geoshift/error.hpp"

namespace geoshift::eval {

namespace {

constexpr const char* kMagic = "# denoise_eval results 1";
constexpr const char* kHeader = "set\tmesh\tnoise\tseed\trms\tangle\tbest_rms\tbest_angle";

std::string fixed(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}

std::vector<std::string> splitTabs(const std::string& line) {
  std::vector<std::string> out;
  size_t start = 0;
  for (;;) {
    const size_t tab = line.find('\t', start);
    out.push_back(line.substr(start, tab - start));
    if (tab == std::string::npos) return out;
    start = tab + 1;
  }
}

}  // namespace

double printed(double x, int digits) {
  const double scale = std::pow(10.0, digits);
  return std::round(x * scale) / scale;
}

Verdict verdictOf(const CaseFigures& c) {
  const double rms = printed(c.rms, 3), angle = printed(c.angle, 2);
  const double bestRms = printed(c.bestRms, 3), bestAngle = printed(c.bestAngle, 2);
  Verdict v;
  v.win = rms <= bestRms && angle <= bestAngle;
  v.rmsRatio = rms / std::max(bestRms, 1e-12);
  v.angleRatio = angle / std::max(bestAngle, 1e-12);
  v.ratio = std::max(v.rmsRatio, v.angleRatio);
  return v;
}

namespace {
constexpr const char* kNoiseSeed = " (noise seed ";
}

std::string withNoiseSeed(const std::string& label, std::uint64_t noiseSeed) {
  return noiseSeed == 1 ? label : label + kNoiseSeed + std::to_string(noiseSeed) + ")";
}

std::uint64_t noiseSeedOf(const std::string& label) {
  const size_t at = label.rfind(kNoiseSeed);
  if (at == std::string::npos || label.back() != ')') return 1;
  const size_t from = at + std::char_traits<char>::length(kNoiseSeed);
  const std::string digits = label.substr(from, label.size() - 1 - from);
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) return 1;
  return std::stoull(digits);
}

void writeResults(std::ostream& out, const std::vector<CaseFigures>& cases) {
  out << kMagic << "\n" << kHeader << "\n";
  char buf[256];
  for (const CaseFigures& c : cases) {
    std::snprintf(buf, sizeof buf, "\t%llu\t%.17g\t%.17g\t%.17g\t%.17g", static_cast<unsigned long long>(c.seed), c.rms,
                  c.angle, c.bestRms, c.bestAngle);
    out << c.set << "\t" << c.mesh << "\t" << c.noise << buf << "\n";
  }
}

std::vector<CaseFigures> readResults(std::istream& in, const std::string& name) {
  std::vector<CaseFigures> out;
  std::set<std::tuple<std::string, std::string, std::string, std::uint64_t>> seen;
  std::string line;
  int number = 0;
  bool magic = false, header = false;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string where = name + " line " + std::to_string(number);
    if (!magic) {
      if (line != kMagic)
        throw InputError(name + ": not a results file of denoise_eval --results (its first line is not '" + kMagic + "')");
      magic = true;
      continue;
    }
    if (!header) {
      if (line != kHeader) throw InputError(where + ": expected the header '" + kHeader + "'");
      header = true;
      continue;
    }
    if (line.empty()) continue;
    const std::vector<std::string> f = splitTabs(line);
    if (f.size() != 8)
      throw InputError(where + ": expected 8 tab-separated fields, found " + std::to_string(f.size()));
    static const char* const columns[] = {"set", "mesh", "noise", "seed", "rms", "angle", "best_rms", "best_angle"};
    auto number_ = [&](int i) {
      size_t used = 0;
      double v = 0;
      try {
        v = std::stod(f[i], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != f[i].size() || f[i].empty() || !std::isfinite(v) || v < 0)
        throw InputError(where + ": '" + f[i] + "' in column " + columns[i] + " is not a finite number >= 0");
      return v;
    };
    CaseFigures c;
    c.set = f[0];
    c.mesh = f[1];
    c.noise = f[2];
    const double seed = number_(3);
    if (seed != std::floor(seed)) throw InputError(where + ": the seed '" + f[3] + "' is not a whole number");
    c.seed = static_cast<std::uint64_t>(seed);
    c.rms = number_(4);
    c.angle = number_(5);
    c.bestRms = number_(6);
    c.bestAngle = number_(7);
    if (!seen.insert({c.set, c.mesh, c.noise, c.seed}).second)
      throw InputError(where + ": " + c.mesh + ", " + c.noise + " at seed " + f[3] + " appears twice");
    out.push_back(std::move(c));
  }
  if (!header) throw InputError(name + ": no header (an empty or cut-short results file)");
  return out;
}

SignedRank signedRankTest(const std::vector<double>& differences) {
  SignedRank r;
  std::vector<double> d;
  for (double x : differences) {
    if (std::abs(x) <= 1e-12)
      ++r.zeros;
    else
      d.push_back(x);
  }
  r.n = static_cast<int>(d.size());
  std::sort(d.begin(), d.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  double tieTerm = 0;
  for (size_t i = 0; i < d.size();) {
    size_t j = i;
    while (j < d.size() && std::abs(d[j]) == std::abs(d[i])) ++j;
    const double rank = 0.5 * static_cast<double>(i + 1 + j);  // the mean of ranks i + 1 .. j
    for (size_t k = i; k < j; ++k) {
      if (d[k] > 0) {
        r.wPlus += rank;
        ++r.positive;
      } else {
        ++r.negative;
      }
    }
    const double t = static_cast<double>(j - i);
    tieTerm += t * t * t - t;
    i = j;
  }
  const double n = r.n;
  r.mean = n * (n + 1) / 4;
  r.variance = n * (n + 1) * (2 * n + 1) / 24 - tieTerm / 48;
  if (r.variance > 0) {
    r.z = (r.wPlus - r.mean) / std::sqrt(r.variance);
    r.p = std::erfc(std::abs(r.z) / std::sqrt(2.0));
  }
  return r;
}

std::vector<double> groupMeans(const std::vector<std::string>& groups, const std::vector<double>& values) {
  if (groups.size() != values.size())
    throw std::invalid_argument("groupMeans: " + std::to_string(groups.size()) + " groups for " +
                                std::to_string(values.size()) + " values");
  std::map<std::string, std::pair<double, int>> sums;
  for (size_t i = 0; i < values.size(); ++i) {
    auto& [sum, count] = sums[groups[i]];
    sum += values[i];
    ++count;
  }
  std::vector<double> out;
  out.reserve(sums.size());
  for (const auto& [group, sc] : sums) out.push_back(sc.first / sc.second);
  return out;
}

ShareInterval groupBootstrapShare(const std::vector<std::string>& groups, const std::vector<bool>& won, int resamples,
                                  std::uint64_t seed) {
  if (groups.size() != won.size())
    throw std::invalid_argument("groupBootstrapShare: " + std::to_string(groups.size()) + " groups for " +
                                std::to_string(won.size()) + " cases");
  if (resamples < 1) throw std::invalid_argument("groupBootstrapShare: resamples must be >= 1");
  ShareInterval out;
  if (groups.empty()) return out;
  // Per group: cases and cases won.
  std::map<std::string, std::pair<int, int>> tally;
  int wins = 0;
  for (size_t i = 0; i < groups.size(); ++i) {
    auto& [cases, w] = tally[groups[i]];
    ++cases;
    w += won[i];
    wins += won[i];
  }
  std::vector<std::pair<int, int>> g;
  for (const auto& [name, t] : tally) g.push_back(t);
  const auto n = static_cast<std::uint64_t>(g.size());
  out.groups = static_cast<int>(n);
  out.share = static_cast<double>(wins) / static_cast<double>(groups.size());
  std::uint64_t state = seed;
  auto next = [&state]() {  // splitmix64
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  std::vector<double> shares(resamples);
  for (double& share : shares) {
    int cases = 0, w = 0;
    for (std::uint64_t k = 0; k < n; ++k) {
      const auto& [c, gw] = g[next() % n];  // the modulo's bias is below n / 2^64
      cases += c;
      w += gw;
    }
    share = static_cast<double>(w) / cases;
  }
  std::sort(shares.begin(), shares.end());
  // The 2.5th and 97.5th percentiles, each the resample at its rank (no interpolation).
  const auto at = [&](double q) {
    const auto i = static_cast<size_t>(std::floor(q * (resamples - 1) + 0.5));
    return shares[std::min(i, shares.size() - 1)];
  };
  out.low = at(0.025);
  out.high = at(0.975);
  return out;
}

namespace {

using Key = std::pair<std::string, std::string>;  // mesh, noise
using BySeed = std::map<std::uint64_t, const CaseFigures*>;
using BySet = std::map<std::string, std::map<Key, BySeed>>;

BySet index(const std::vector<CaseFigures>& cases) {
  BySet out;
  for (const CaseFigures& c : cases) out[c.set][{c.mesh, c.noise}][c.seed] = &c;
  return out;
}

std::string caseName(const Key& k) { return k.first + ", " + k.second; }

struct Means {
  double logRms = 0, logAngle = 0;
  int n = 0, within = 0;
  void add(const CaseFigures& c) {
    const Verdict v = verdictOf(c);
    logRms += std::log(std::max(v.rmsRatio, 1e-6));
    logAngle += std::log(std::max(v.angleRatio, 1e-6));
    within += v.ratio <= 1.25;
    ++n;
  }
  std::string text() const {
    return n ? fixed(std::exp(logRms / n), 3) + " / " + fixed(std::exp(logAngle / n), 3) : "–";
  }
};

std::string testRow(const std::string& what, const std::vector<double>& d) {
  const SignedRank t = signedRankTest(d);
  std::ostringstream s;
  s << "| " << what << " | " << t.negative << " | " << t.positive << " | " << t.zeros << " | " << fixed(t.z, 2) << " | "
    << (t.n == 0 ? "–" : t.p < 0.001 ? "< 0.001" : fixed(t.p, 3)) << " |\n";
  return s.str();
}

}  // namespace

std::string compareResults(const std::vector<CaseFigures>& before, const std::vector<CaseFigures>& after) {
  const BySet a = index(before), b = index(after);
  std::set<std::string> sets;
  for (const auto& [set, cases] : a) sets.insert(set);
  for (const auto& [set, cases] : b) sets.insert(set);
  std::ostringstream s;
  for (const std::string& set : sets) {
    const auto ia = a.find(set), ib = b.find(set);
    const std::map<Key, BySeed> none;
    const auto& ca = ia == a.end() ? none : ia->second;
    const auto& cb = ib == b.end() ? none : ib->second;
    // The cases both runs hold, and the seeds all of them share.
    std::vector<Key> common;
    std::vector<std::string> onlyBefore, onlyAfter;
    for (const auto& [k, seeds] : ca) {
      if (cb.count(k))
        common.push_back(k);
      else
        onlyBefore.push_back(caseName(k));
    }
    for (const auto& [k, seeds] : cb)
      if (!ca.count(k)) onlyAfter.push_back(caseName(k));
    std::set<std::uint64_t> shared;
    bool first = true;
    for (const Key& k : common) {
      std::set<std::uint64_t> here;
      for (const auto& [seed, c] : ca.at(k))
        if (cb.at(k).count(seed)) here.insert(seed);
      if (first) {
        shared = here;
        first = false;
      } else {
        std::set<std::uint64_t> both;
        std::set_intersection(shared.begin(), shared.end(), here.begin(), here.end(), std::inserter(both, both.end()));
        shared = std::move(both);
      }
    }
    s << "## " << set << ": " << common.size() << " cases in both runs\n\n";
    if (!onlyBefore.empty() || !onlyAfter.empty()) {
      s << "Left out, in one run only:";
      for (const std::string& n : onlyBefore) s << " " << n << " (before);";
      for (const std::string& n : onlyAfter) s << " " << n << " (after);";
      s << "\n\n";
    }
    if (common.empty() || shared.empty()) {
      s << "No case at a probe seed both runs share.\n\n";
      continue;
    }
    const std::uint64_t seed1 = *shared.begin();
    s << "| | before | after |\n|---|---|---|\n";
    for (std::uint64_t seed : shared) {
      int wa = 0, wb = 0;
      for (const Key& k : common) {
        wa += won(*ca.at(k).at(seed));
        wb += won(*cb.at(k).at(seed));
      }
      s << "| won at probe seed " << seed << " | " << wa << " | " << wb << " |\n";
    }
    // Several realizations of the noise: the first probe seed's count at each (the pairs, which keep
    // their own noise, count at noise seed 1).
    std::map<std::uint64_t, std::array<int, 3>> byNoise;  // won before, won after, cases
    for (const Key& k : common) {
      std::array<int, 3>& n = byNoise[noiseSeedOf(k.second)];
      n[0] += won(*ca.at(k).at(*shared.begin()));
      n[1] += won(*cb.at(k).at(*shared.begin()));
      ++n[2];
    }
    if (byNoise.size() > 1)
      for (const auto& [noise, n] : byNoise)
        s << "| won at noise seed " << noise << " (of " << n[2] << ", probe seed " << *shared.begin() << ") | " << n[0]
          << " | " << n[1] << " |\n";
    Means ma, mb;
    std::vector<std::string> lost, gained;
    std::vector<double> dRms, dAngle;
    std::vector<std::string> meshes;
    for (const Key& k : common) {
      meshes.push_back(k.first);
      const CaseFigures &x = *ca.at(k).at(seed1), &y = *cb.at(k).at(seed1);
      ma.add(x);
      mb.add(y);
      if (won(x) != won(y))
        (won(x) ? lost : gained).push_back(caseName(k) + " (ratio " + fixed(ratio(x), 2) + " → " + fixed(ratio(y), 2) + ")");
      double r = 0, g = 0;
      for (std::uint64_t seed : shared) {
        const CaseFigures &p = *ca.at(k).at(seed), &q = *cb.at(k).at(seed);
        r += std::log(std::max(q.rms, 1e-12) / std::max(p.rms, 1e-12));
        g += std::log(std::max(q.angle, 1e-12) / std::max(p.angle, 1e-12));
      }
      dRms.push_back(r / shared.size());
      dAngle.push_back(g / shared.size());
    }
    s << "| geometric mean ratio, RMS / normal error (seed " << seed1 << ") | " << ma.text() << " | " << mb.text()
      << " |\n| within 1.25× of the better oracle (seed " << seed1 << ") | " << ma.within << " | " << mb.within << " |\n\n";
    s << "Won before and lost after (seed " << seed1 << "):";
    for (size_t i = 0; i < lost.size(); ++i) s << (i ? "; " : " ") << lost[i];
    s << (lost.empty() ? " none" : "") << ".\n\nLost before and won after (seed " << seed1 << "):";
    for (size_t i = 0; i < gained.size(); ++i) s << (i ? "; " : " ") << gained[i];
    s << (gained.empty() ? " none" : "") << ".\n\n";
    s << "Each case's change in ours, log(after / before)"
      << (shared.size() > 1 ? ", averaged over the " + std::to_string(shared.size()) + " shared probe seeds" : "")
      << ", and Wilcoxon's signed-rank test of it (z < 0: after is lower; p: the chance of a shift at least as large "
         "if the change moved the cases up and down alike):\n\n"
      << "| number | lower after | higher after | the same | z | p |\n|---|---|---|---|---|---|\n"
      << testRow("RMS", dRms) << testRow("normal error", dAngle) << "\n";
    const std::vector<double> mRms = groupMeans(meshes, dRms), mAngle = groupMeans(meshes, dAngle);
    s << "The same test over the " << mRms.size()
      << " meshes, each mesh's cases averaged first (the noises of one mesh share its shape: a mesh that moves "
         "with every noise counts once):\n\n"
      << "| number | meshes lower after | higher after | the same | z | p |\n|---|---|---|---|---|---|\n"
      << testRow("RMS", mRms) << testRow("normal error", mAngle) << "\n";
  }
  return s.str();
}

}  // namespace geoshift::eval
