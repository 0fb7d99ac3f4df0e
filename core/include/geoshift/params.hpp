#pragma once
// The parameters of every request a front end can make (the wasm ops, the CLI commands that mirror
// them, Python's keyword arguments): one table per op, with each parameter's type, default, range or
// choices, a one-line doc and which methods or presets it applies to (docs/architecture.md#parameters).
// It is the only place that knows them: the wasm ops validate against it, the CLI takes its checks
// and the defaults of its help from it, Python checks denoise keywords through it, and the wasm
// module exports it (paramSpecs()) for the TypeScript types. Defaults are read from the options
// structs' own initialisers, so a default changed there changes here.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace geoshift {

enum class ParamType {
  Number,   // a finite double
  Integer,  // a whole number (JS numbers carry integers up to 2^53 exactly)
  Boolean,
  Enum,     // one of `values`
  Text,     // any string (e.g. a comma-separated list of signal names)
};

// A value as a front end received it. `Unsupported` stands for anything else (null, an object,
// an array holding a non-number): it is refused with the type the parameter wants.
struct Unsupported {};
using ParamValue = std::variant<bool, double, std::string, std::vector<double>, Unsupported>;

// Holds when every listed parameter's value (given, else its default) is one of the listed values.
using ParamCondition = std::vector<std::pair<std::string, std::vector<std::string>>>;

// Another default or range where `when` holds (the first case that holds wins).
struct ParamCase {
  ParamCondition when;
  std::optional<ParamValue> defaultValue;
  std::optional<double> min, max;
};

struct ParamSpec {
  std::string name;  // as the wasm op and the request tables spell it (camelCase)
  ParamType type = ParamType::Number;
  std::string doc;   // one line, for help texts and TypeScript doc comments
  // nullopt: none, the op computes one (the doc says how), or the parameter is simply off.
  std::optional<ParamValue> defaultValue;
  std::optional<double> min, max;  // inclusive, except min with minExclusive
  bool minExclusive = false;
  std::vector<std::string> values;  // Enum: the choices
  bool list = false;                // Number/Integer: one value, or a list (e.g. one per level)
  std::vector<ParamCondition> appliesWhen;  // any of them; empty: always
  std::vector<ParamCase> cases;
  std::string cli;  // the CLI option's name when it is not --kebab-case of `name`
};

struct OpParamSpecs {
  std::string op;
  std::string doc;
  std::vector<ParamSpec> params;  // a parameter a condition refers to comes before the ones using it
};

// Every op's table: noise, smooth, curvature, geodesic, filter, denoise, wavelet.
const std::vector<OpParamSpecs>& paramSpecs();
// One op's table; InputError naming the known ops for another name.
const OpParamSpecs& paramSpecsOf(std::string_view op);
// The spec of one parameter of `specs` (std::out_of_range for another name: a programming error).
const ParamSpec& paramSpec(const OpParamSpecs& specs, std::string_view name);

// The CLI's spelling of a parameter: "--" + spec.cli, else kebab-case of its name (vertexIterations
// -> --vertex-iterations). Python's keyword is the snake_case of the name (vertex_iterations).
std::string cliOptionName(const ParamSpec& spec);

using ParamValues = std::vector<std::pair<std::string, ParamValue>>;

// A request of one op: the values a front end was given, checked against the op's table when made.
// Construction throws InputError, prefixed by the op's name, for (in this order) an unknown name
// (listing the accepted ones), then for each parameter in table order: a value of the wrong type,
// not a whole number, not one of the choices, a parameter that does not apply to the chosen method
// or preset, a number out of range. So every front end that builds the same request gets the same
// message, whatever order it lists the values in.
class ParamRequest {
 public:
  ParamRequest(const OpParamSpecs& specs, ParamValues given);

  const OpParamSpecs& specs() const { return *specs_; }
  bool has(std::string_view name) const;  // given by the caller
  // The given value, else the default of the case that holds; std::logic_error when there is none
  // (ask has() or use the optional forms for parameters without a default).
  double number(std::string_view name) const;
  int integer(std::string_view name) const;
  std::int64_t integer64(std::string_view name) const;
  bool flag(std::string_view name) const;
  std::string text(std::string_view name) const;
  std::vector<double> numbers(std::string_view name) const;  // a list parameter, one value or many
  std::optional<double> optionalNumber(std::string_view name) const;
  std::optional<int> optionalInteger(std::string_view name) const;

 private:
  const ParamValue* given(std::string_view name) const;
  std::optional<ParamValue> valueOf(const ParamSpec& spec) const;
  const OpParamSpecs* specs_;
  ParamValues given_;
};

// Whether `condition` holds for the request's current values (given, else default).
bool holds(const ParamRequest& request, const ParamCondition& condition);

// The default of `spec` where its first holding case says so, else its own.
std::optional<ParamValue> defaultOf(const ParamSpec& spec, const ParamRequest& request);

// A value for messages and help texts: 0.35, true, "paper", 3,15.
std::string formatValue(const ParamValue& value);

}  // namespace geoshift
