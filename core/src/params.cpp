// Checking a request against its op's parameter table (params.hpp).
#include "geoshift/params.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include "geoshift/check.hpp"
#include "geoshift/error.hpp"

namespace geoshift {

const ParamSpec& paramSpec(const OpParamSpecs& specs, std::string_view name) {
  for (const ParamSpec& s : specs.params)
    if (s.name == name) return s;
  throw std::out_of_range(specs.op + " has no parameter " + std::string(name));
}

std::string cliOptionName(const ParamSpec& spec) {
  if (!spec.cli.empty()) return "--" + spec.cli;
  std::string out = "--";
  for (const char c : spec.name) {
    if (std::isupper(static_cast<unsigned char>(c))) {
      out += '-';
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out;
}

// Strings appended piece by piece: GCC 12 warns (-Wrestrict, wrongly) about chains of operator+.
std::string formatValue(const ParamValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const double* x = std::get_if<double>(&value)) return formatNumber(*x);
  if (const std::string* s = std::get_if<std::string>(&value)) {
    std::string quoted = "\"";
    quoted += *s;
    quoted += '"';
    return quoted;
  }
  if (const std::vector<double>* v = std::get_if<std::vector<double>>(&value)) {
    std::string out;
    for (double x : *v) {
      if (!out.empty()) out += ',';
      out += formatNumber(x);
    }
    return out;
  }
  return "?";
}

namespace {

std::string quotedList(const std::vector<std::string>& values, const char* separator) {
  std::string out;
  for (size_t i = 0; i < values.size(); ++i) out += (i ? separator : "") + ("\"" + values[i] + "\"");
  return out;
}

// The message head naming a parameter: "denoise: parameter hs".
std::string head(const OpParamSpecs& specs, const ParamSpec& spec) { return specs.op + ": parameter " + spec.name; }

const char* typeWanted(const ParamSpec& spec) {
  switch (spec.type) {
    case ParamType::Number:
      return spec.list ? "must be a number or a list of numbers" : "must be a number";
    case ParamType::Integer:
      return spec.list ? "must be a whole number or a list of them" : "must be a number";
    case ParamType::Boolean:
      return "must be true or false";
    case ParamType::Enum:
    case ParamType::Text:
      return "must be a string";
  }
  return "has the wrong type";
}

// The value's numbers, when it has the type the parameter wants; nothing for booleans and strings.
std::vector<double> checkType(const OpParamSpecs& specs, const ParamSpec& spec, const ParamValue& value) {
  const bool ok = spec.type == ParamType::Boolean                                   ? std::holds_alternative<bool>(value)
                  : spec.type == ParamType::Enum || spec.type == ParamType::Text ? std::holds_alternative<std::string>(value)
                  : std::holds_alternative<double>(value) ||
                        (spec.list && std::holds_alternative<std::vector<double>>(value));
  if (!ok) throw InputError(head(specs, spec) + " " + typeWanted(spec));
  if (const double* x = std::get_if<double>(&value)) return {*x};
  if (const std::vector<double>* v = std::get_if<std::vector<double>>(&value)) {
    if (v->empty()) throw InputError(head(specs, spec) + " is an empty list");
    return *v;
  }
  return {};
}

void checkChoice(const OpParamSpecs& specs, const ParamSpec& spec, const ParamValue& value) {
  if (spec.type != ParamType::Enum) return;
  const std::string& s = std::get<std::string>(value);
  if (std::find(spec.values.begin(), spec.values.end(), s) != spec.values.end()) return;
  std::string list;
  for (const std::string& c : spec.values) list += (list.empty() ? "" : ", ") + c;
  throw InputError(head(specs, spec) + " = \"" + s + "\" is not one of " + list);
}

// The condition's parameters whose value (given or default) is not among the listed ones.
std::vector<std::pair<std::string, std::string>> failing(const ParamRequest& request, const ParamCondition& condition) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [name, values] : condition) {
    const std::string value = request.has(name) || defaultOf(paramSpec(request.specs(), name), request)
                                  ? request.text(name)
                                  : std::string();
    if (std::find(values.begin(), values.end(), value) == values.end()) out.emplace_back(name, value);
  }
  return out;
}

// Whether the parameter applies to the request's method and preset at all.
bool applies(const ParamRequest& request, const ParamSpec& spec) {
  return spec.appliesWhen.empty() || std::any_of(spec.appliesWhen.begin(), spec.appliesWhen.end(),
                                                 [&](const ParamCondition& c) { return holds(request, c); });
}

// "belongs to method "meanshift" or "bilateral"; vertexIterations does not apply to method "taubin"": what the
// parameter needs (the unmet part of each condition) and what the request has instead.
void checkApplies(const ParamRequest& request, const ParamSpec& spec) {
  if (spec.appliesWhen.empty()) return;
  std::vector<std::string> needs;
  std::vector<std::pair<std::string, std::string>> has;
  for (const ParamCondition& condition : spec.appliesWhen) {
    const std::vector<std::pair<std::string, std::string>> unmet = failing(request, condition);
    if (unmet.empty()) return;
    std::string need;
    for (const auto& entry : condition) {  // not a structured binding: clang 14 cannot capture one
      const std::string& name = entry.first;
      if (std::none_of(unmet.begin(), unmet.end(), [&](const auto& u) { return u.first == name; })) continue;
      need += (need.empty() ? "" : " with ") + name + " " + quotedList(entry.second, " or ");
    }
    needs.push_back(need);
    for (const auto& u : unmet)
      if (std::find(has.begin(), has.end(), u) == has.end()) has.push_back(u);
  }
  std::string needText, hasText;
  for (size_t i = 0; i < needs.size(); ++i) needText += (i ? " or to " : "") + needs[i];
  for (const auto& [name, value] : has)
    if (!value.empty() && applies(request, paramSpec(request.specs(), name)))
      hasText += (hasText.empty() ? "" : " with ") + name + " \"" + value + "\"";
  throw InputError(head(request.specs(), spec) + " belongs to " + needText + "; " + spec.name + " does not apply to " + hasText);
}

void checkRange(const ParamRequest& request, const ParamSpec& spec, const std::vector<double>& values) {
  if (spec.type != ParamType::Number && spec.type != ParamType::Integer) return;
  double min = spec.min.value_or(-std::numeric_limits<double>::infinity());
  double max = spec.max.value_or(std::numeric_limits<double>::infinity());
  bool minExclusive = spec.minExclusive;
  for (const ParamCase& c : spec.cases) {
    if (!holds(request, c.when)) continue;
    if (c.min) min = *c.min, minExclusive = false;
    if (c.max) max = *c.max;
    break;
  }
  for (double x : values) {
    requireFinite(head(request.specs(), spec), x);
    if (spec.type == ParamType::Integer && x != std::floor(x))
      throw InputError(head(request.specs(), spec) + " " + wholeProblem(x));
    requireRange(head(request.specs(), spec), x, min, max, minExclusive);
  }
}

}  // namespace

ParamRequest::ParamRequest(const OpParamSpecs& specs, ParamValues given) : specs_(&specs), given_(std::move(given)) {
  for (size_t i = 0; i < given_.size(); ++i) {
    const std::string& name = given_[i].first;
    const bool known = std::any_of(specs.params.begin(), specs.params.end(), [&](const ParamSpec& s) { return s.name == name; });
    if (!known) {
      std::string list;
      for (const ParamSpec& s : specs.params) list += (list.empty() ? "" : ", ") + s.name;
      throw InputError(specs.op + ": unknown parameter \"" + name + "\" (accepted: " + (list.empty() ? "none" : list) + ")");
    }
    for (size_t j = 0; j < i; ++j)
      if (given_[j].first == name) throw InputError(specs.op + ": parameter " + name + " is given twice");
  }
  // Table order, so that the first problem reported does not depend on the order of the values.
  for (const ParamSpec& spec : specs.params) {
    const ParamValue* value = this->given(spec.name);
    if (!value) continue;
    const std::vector<double> numbers = checkType(specs, spec, *value);
    checkChoice(specs, spec, *value);
    checkApplies(*this, spec);
    checkRange(*this, spec, numbers);
  }
}

const ParamValue* ParamRequest::given(std::string_view name) const {
  for (const auto& [n, v] : given_)
    if (n == name) return &v;
  return nullptr;
}

bool ParamRequest::has(std::string_view name) const { return given(name) != nullptr; }

std::optional<ParamValue> defaultOf(const ParamSpec& spec, const ParamRequest& request) {
  for (const ParamCase& c : spec.cases)
    if (c.defaultValue && holds(request, c.when)) return c.defaultValue;
  return spec.defaultValue;
}

std::optional<ParamValue> ParamRequest::valueOf(const ParamSpec& spec) const {
  if (const ParamValue* v = given(spec.name)) return *v;
  return defaultOf(spec, *this);
}

bool holds(const ParamRequest& request, const ParamCondition& condition) { return failing(request, condition).empty(); }

namespace {

[[noreturn]] void noValue(const OpParamSpecs& specs, std::string_view name) {
  throw std::logic_error(specs.op + ": parameter " + std::string(name) + " has no value and no default");
}

}  // namespace

std::optional<double> ParamRequest::optionalNumber(std::string_view name) const {
  const std::optional<ParamValue> v = valueOf(paramSpec(*specs_, name));
  if (!v) return std::nullopt;
  if (const double* x = std::get_if<double>(&*v)) return *x;
  if (const std::vector<double>* list = std::get_if<std::vector<double>>(&*v)) return list->front();
  throw std::logic_error(specs_->op + ": parameter " + std::string(name) + " is not a number");
}

double ParamRequest::number(std::string_view name) const {
  const std::optional<double> x = optionalNumber(name);
  if (!x) noValue(*specs_, name);
  return *x;
}

std::optional<int> ParamRequest::optionalInteger(std::string_view name) const {
  const std::optional<double> x = optionalNumber(name);
  return x ? std::optional<int>(static_cast<int>(*x)) : std::nullopt;
}

int ParamRequest::integer(std::string_view name) const { return static_cast<int>(number(name)); }

std::int64_t ParamRequest::integer64(std::string_view name) const { return static_cast<std::int64_t>(number(name)); }

bool ParamRequest::flag(std::string_view name) const {
  const std::optional<ParamValue> v = valueOf(paramSpec(*specs_, name));
  if (!v) noValue(*specs_, name);
  return std::get<bool>(*v);
}

std::string ParamRequest::text(std::string_view name) const {
  const std::optional<ParamValue> v = valueOf(paramSpec(*specs_, name));
  if (!v) noValue(*specs_, name);
  return std::get<std::string>(*v);
}

std::vector<double> ParamRequest::numbers(std::string_view name) const {
  const std::optional<ParamValue> v = valueOf(paramSpec(*specs_, name));
  if (!v) noValue(*specs_, name);
  if (const double* x = std::get_if<double>(&*v)) return {*x};
  return std::get<std::vector<double>>(*v);
}

}  // namespace geoshift
