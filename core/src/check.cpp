// The check vocabulary (check.hpp).
#include "geoshift/check.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "geoshift/error.hpp"

namespace geoshift {

#ifndef __EMSCRIPTEN__
std::string formatNumber(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}
#else
// As std::to_chars(first, last, x), which Emscripten 3.1.6's libc++ lacks for floating point: the
// fewest significant digits that read back as x, written fixed or in printf's %e style, whichever
// is shorter (fixed on a tie).
std::string formatNumber(double x) {
  if (std::isnan(x)) return std::signbit(x) ? "-nan" : "nan";
  if (std::isinf(x)) return x < 0 ? "-inf" : "inf";
  char sci[64];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(sci, sizeof sci, "%.*e", digits - 1, x);
    if (std::strtod(sci, nullptr) == x) break;
  }
  // sci = [-]d[.ddd]e±XX: its digits and exponent give the fixed form.
  const std::string s(sci);
  const size_t e = s.find('e');
  const bool negative = s[0] == '-';
  std::string digits;
  for (size_t i = negative ? 1 : 0; i < e; ++i)
    if (s[i] != '.') digits += s[i];
  const int exponent = std::atoi(s.c_str() + e + 1);
  const int n = static_cast<int>(digits.size());
  std::string fixed = negative ? "-" : "";
  if (exponent >= n - 1) {
    // An integer: printf's %f writes its exact digits (beyond 17 they are not all zeros).
    char whole[400];
    std::snprintf(whole, sizeof whole, "%.0f", x);
    fixed = whole;
  } else if (exponent >= 0) {
    fixed += digits.substr(0, static_cast<size_t>(exponent) + 1) + "." + digits.substr(static_cast<size_t>(exponent) + 1);
  } else {
    fixed += "0." + std::string(static_cast<size_t>(-exponent - 1), '0') + digits;
  }
  return fixed.size() <= s.size() ? fixed : s;
}
#endif

std::string finiteProblem(double x) {
  return std::isfinite(x) ? "" : "must be a finite number (got " + formatNumber(x) + ")";
}

std::string positiveProblem(double x) {
  return std::isfinite(x) && x > 0 ? "" : "must be > 0 (got " + formatNumber(x) + ")";
}

std::string atLeastProblem(double x, double min) {
  return std::isfinite(x) && x >= min ? "" : "must be >= " + formatNumber(min) + " (got " + formatNumber(x) + ")";
}

std::string rangeProblem(double x, double min, double max, bool minExclusive) {
  const bool aboveMin = minExclusive ? x > min : x >= min;
  if (std::isfinite(x) && aboveMin && x <= max) return "";
  if (std::isinf(max) && !std::isinf(min))
    return std::string(minExclusive ? "must be > " : "must be >= ") + formatNumber(min) + " (got " + formatNumber(x) + ")";
  if (!std::isfinite(x) && std::isinf(min) && std::isinf(max)) return finiteProblem(x);
  return "is outside " + std::string(minExclusive ? "(" : "[") + formatNumber(min) + ", " + formatNumber(max) +
         "] (got " + formatNumber(x) + ")";
}

std::string wholeProblem(double x) {
  return std::isfinite(x) && x == std::floor(x) ? "" : "must be a whole number (got " + formatNumber(x) + ")";
}

std::string indexProblem(long long i, long long count) {
  if (i >= 0 && i < count) return "";
  if (count <= 0) return "is not an index (got " + std::to_string(i) + "; there are none)";
  return "is outside [0, " + std::to_string(count - 1) + "] (got " + std::to_string(i) + ")";
}

namespace {

void require(std::string_view what, const std::string& problem) {
  if (!problem.empty()) throw InputError(std::string(what) + " " + problem);
}

}  // namespace

void requireFinite(std::string_view what, double x) { require(what, finiteProblem(x)); }
void requirePositive(std::string_view what, double x) { require(what, positiveProblem(x)); }
void requireAtLeast(std::string_view what, double x, double min) { require(what, atLeastProblem(x, min)); }
void requireRange(std::string_view what, double x, double min, double max, bool minExclusive) {
  require(what, rangeProblem(x, min, max, minExclusive));
}
void requireIndex(std::string_view what, long long i, long long count) { require(what, indexProblem(i, count)); }

}  // namespace geoshift
