#pragma once
// One vocabulary for checking parameters and inputs (docs/architecture.md#checks). Each check names
// what it checks (a parameter, "vertex 12 of face 3", ...) and prints the value as it was given:
// numbers through formatNumber, so that 1e-7 reads 1e-07 and not the 0.000000 of std::to_string.
//
// The *Problem functions give the tail of a message ("must be > 0 (got -1e-07)"), or "" when the
// value is fine, for callers that add their own head (CLI11 validators put the option's name
// first); the require* functions throw InputError(what + " " + tail).
#include <string>
#include <string_view>

namespace geoshift {

// The shortest text that reads back as exactly x (std::to_chars): 0.35, 3, 1e-07, inf, nan. The
// writers use it too, so a file's numbers and a message's read alike.
std::string formatNumber(double x);

std::string finiteProblem(double x);                    // "must be a finite number (got nan)"
std::string positiveProblem(double x);                  // "must be > 0 (got -1e-07)"
std::string atLeastProblem(double x, double min);       // "must be >= 1 (got 0)"
// "is outside [min, max] (got x)"; with minExclusive the interval reads (min, max]. An infinite
// max leaves the upper end out: "must be >= min" or "must be > min".
std::string rangeProblem(double x, double min, double max, bool minExclusive = false);
std::string wholeProblem(double x);                     // "must be a whole number (got 1.5)"
// An index into `count` things: "is outside [0, count - 1] (got i)"; "(there are none)" for 0.
std::string indexProblem(long long i, long long count);

void requireFinite(std::string_view what, double x);
void requirePositive(std::string_view what, double x);
void requireAtLeast(std::string_view what, double x, double min);
void requireRange(std::string_view what, double x, double min, double max, bool minExclusive = false);
void requireIndex(std::string_view what, long long i, long long count);

}  // namespace geoshift
