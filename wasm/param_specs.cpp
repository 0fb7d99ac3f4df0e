// paramSpecs(): the core's parameter tables (params.hpp) as plain JS data, for generated TypeScript
// types and for front ends that show defaults and ranges. The shape (docs/architecture.md#parameters):
//   { [op]: { doc, params: { [name]: { type: 'number' | 'integer' | 'boolean' | 'enum' | 'string',
//     doc, default?, min?, max?, minExclusive?, values?, list?, when?: [{ [param]: [values] }],
//     cases?: [{ when: { [param]: [values] }, default?, min?, max? }] } } } }
// Keys are present only when they say something (no infinite bounds, no empty lists). A list
// parameter's default is a number when it is one value, else an array.
#include <cmath>

#include "adapters.hpp"
#include "convert.hpp"
#include "geoshift/params.hpp"

namespace geoshift::wasm {

using emscripten::val;

namespace {

const char* typeName(ParamType type) {
  switch (type) {
    case ParamType::Number:
      return "number";
    case ParamType::Integer:
      return "integer";
    case ParamType::Boolean:
      return "boolean";
    case ParamType::Enum:
      return "enum";
    case ParamType::Text:
      return "string";
  }
  return "?";
}

val strings(const std::vector<std::string>& values) {
  val out = val::array();
  for (const std::string& s : values) out.call<void>("push", s);
  return out;
}

val valueOf(const ParamValue& v) {
  if (const bool* b = std::get_if<bool>(&v)) return val(*b);
  if (const double* x = std::get_if<double>(&v)) return val(*x);
  if (const std::string* s = std::get_if<std::string>(&v)) return val(*s);
  if (const std::vector<double>* list = std::get_if<std::vector<double>>(&v)) {
    if (list->size() == 1) return val(list->front());
    val out = val::array();
    for (double x : *list) out.call<void>("push", x);
    return out;
  }
  return val::undefined();
}

val conditionOf(const ParamCondition& condition) {
  val out = val::object();
  for (const auto& [name, values] : condition) out.set(name, strings(values));
  return out;
}

void setBound(val& out, const char* key, const std::optional<double>& bound) {
  if (bound && std::isfinite(*bound)) out.set(key, *bound);
}

val specOf(const ParamSpec& s) {
  val out = val::object();
  out.set("type", std::string(typeName(s.type)));
  out.set("doc", s.doc);
  if (s.defaultValue) out.set("default", valueOf(*s.defaultValue));
  setBound(out, "min", s.min);
  setBound(out, "max", s.max);
  if (s.minExclusive) out.set("minExclusive", true);
  if (!s.values.empty()) out.set("values", strings(s.values));
  if (s.list) out.set("list", true);
  if (!s.appliesWhen.empty()) {
    val when = val::array();
    for (const ParamCondition& c : s.appliesWhen) when.call<void>("push", conditionOf(c));
    out.set("when", when);
  }
  if (!s.cases.empty()) {
    val cases = val::array();
    for (const ParamCase& c : s.cases) {
      val entry = val::object();
      entry.set("when", conditionOf(c.when));
      if (c.defaultValue) entry.set("default", valueOf(*c.defaultValue));
      setBound(entry, "min", c.min);
      setBound(entry, "max", c.max);
      cases.call<void>("push", entry);
    }
    out.set("cases", cases);
  }
  return out;
}

}  // namespace

val listParamSpecs() {
  val out = val::object();
  for (const OpParamSpecs& op : paramSpecs()) {
    val params = val::object();
    for (const ParamSpec& s : op.params) params.set(s.name, specOf(s));
    val entry = val::object();
    entry.set("doc", op.doc);
    entry.set("params", params);
    out.set(op.op, entry);
  }
  return out;
}

}  // namespace geoshift::wasm
