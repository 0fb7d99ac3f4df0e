#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

#include "allocation.hpp"
#include "commands.hpp"
#include "geoshift/check.hpp"
#include "geoshift/error.hpp"
#include "geoshift/geometry.hpp"

namespace geoshift::cli {

ReadOptions& readOptions() {
  // A command reads its input once and writes at most once: an OBJ's text is read again when it is
  // written back instead of being held through the command (docs/io.md, OBJ).
  static ReadOptions options = [] {
    ReadOptions o;
    o.keepSourceText = false;
    return o;
  }();
  return options;
}

Document load(const std::string& path) {
  Document doc = readDocument(path, readOptions());
  for (const std::string& w : doc.warnings) std::cerr << "geoshift: warning: " << w << "\n";
  return doc;
}

void save(const Document& doc, const std::string& path) {
  releaseKeptArrays();  // none held while the result is written (allocation.cpp)
  for (const std::string& w : writeDocument(doc, path)) std::cerr << "geoshift: warning: " << w << "\n";
}

namespace {

// "file: part" for messages, the part left out where it is only the file's name again (OBJ, OFF).
std::string where(const Document& doc, const MeshPart& part) {
  const std::string name = std::filesystem::path(doc.path).filename().string();
  return part.label.empty() || part.label == name ? doc.path : doc.path + ": " + part.label;
}

}  // namespace

MeshBuild buildPart(const Document& doc, const MeshPart& part) {
  MeshBuild b;
  try {
    b = buildMesh(partSoup(part));
  } catch (const InputError& e) {  // the core names the faces; the file and part are known here
    throw InputError(where(doc, part) + ": " + e.what());
  }
  for (const std::string& m : b.report.messages)
    std::cerr << "geoshift: note: " << where(doc, part) << ": " << m << "\n";
  return b;
}

void writeBack(MeshPart& part, const MeshBuild& build) {
  for (size_t i = 0; i < part.positions.size(); ++i) part.positions[i] = build.mesh.position(build.vertexOf[i]);
  recomputeNormals(part);
}

void recomputeNormals(MeshPart& part) {
  if (part.normals.empty()) return;
  const MeshBuild own = buildMesh(partSoup(part), MeshBuildOptions::withoutWelding());
  const std::vector<Vec3> n = vertexNormals(own.mesh);
  for (size_t i = 0; i < part.normals.size(); ++i) {
    const Vec3& v = n[own.vertexOf[i]];
    // Vertices of dropped faces keep their normal rather than getting a zero one.
    if (v.squaredNorm() > 0) part.normals[i] = v;
  }
}

namespace {

// "meanshift/paper": the values a condition asks for.
std::string describe(const ParamCondition& condition) {
  std::string out;
  for (const auto& [name, values] : condition)
    for (const std::string& v : values) out += (out.empty() ? "" : "/") + v;
  return out;
}

std::string plain(const ParamValue& v) {
  const std::string s = formatValue(v);
  return s.size() >= 2 && s.front() == '"' ? s.substr(1, s.size() - 2) : s;
}

// A CLI11 validator from a problem function of the check vocabulary ("" when the text is fine).
CLI::Validator numberCheck(std::function<std::string(double)> problem, std::string description) {
  return CLI::Validator(
      [problem = std::move(problem)](std::string& text) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size()) return "must be a number (got '" + text + "')";
        return problem(x);
      },
      std::move(description));
}

}  // namespace

std::string specHelp(const ParamSpec& s, const std::string& note) {
  std::string where;
  for (const ParamCondition& c : s.appliesWhen) where += (where.empty() ? "" : ", ") + describe(c);
  std::string text = (where.empty() ? "" : where + ": ") + s.doc;
  if (!s.values.empty()) {
    std::string choices;
    for (const std::string& v : s.values) choices += (choices.empty() ? "" : ", ") + v;
    text += " (" + choices + ")";
  }
  std::string defaults;
  if (s.type != ParamType::Boolean) {
    if (s.defaultValue) defaults = "default " + plain(*s.defaultValue);
    for (const ParamCase& c : s.cases)
      if (c.defaultValue) defaults += (defaults.empty() ? "" : "; ") + describe(c.when) + " " + plain(*c.defaultValue);
  }
  if (!note.empty()) defaults += (defaults.empty() ? "" : "; ") + note;
  return defaults.empty() ? text : text + " (" + defaults + ")";
}

namespace {

std::optional<double> parsed(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() ? std::optional(x) : std::nullopt;
}

// The command line's text as a value of the parameter's type; text that is no number stays text,
// which the core refuses as it refuses a wrong type from the other front ends.
ParamValue valueOf(const ParamSpec& s, const std::string& text) {
  if (s.type == ParamType::Boolean) return true;
  if (s.type == ParamType::Enum || s.type == ParamType::Text) return text;
  if (!s.list) {
    const std::optional<double> x = parsed(text);
    return x ? ParamValue(*x) : ParamValue(text);
  }
  std::vector<double> list;
  std::stringstream items(text);
  for (std::string item; std::getline(items, item, ',');) {
    const std::optional<double> x = parsed(item);
    if (!x) return text;
    list.push_back(*x);
  }
  return list;
}

std::string typeName(const ParamSpec& s) {
  const std::string type = s.type == ParamType::Number ? "FLOAT" : s.type == ParamType::Integer ? "INT" : "TEXT";
  return s.list ? type + "[,...]" : type;
}

}  // namespace

TableOptions::TableOptions(CLI::App* sub, const std::string& op, const std::vector<std::string>& skip,
                           const std::vector<std::pair<std::string, std::string>>& notes)
    : specs_(&paramSpecsOf(op)), texts_(specs_->params.size()) {
  for (size_t i = 0; i < specs_->params.size(); ++i) {
    const ParamSpec& s = specs_->params[i];
    if (std::find(skip.begin(), skip.end(), s.name) != skip.end()) {
      options_.push_back(nullptr);
      continue;
    }
    std::string note;
    for (const auto& [name, text] : notes)
      if (name == s.name) note = text;
    const std::string help = specHelp(s, note);  // const: add_flag takes a non-const string as its target
    options_.push_back(s.type == ParamType::Boolean
                           ? sub->add_flag(cliOptionName(s), help)
                           : sub->add_option(cliOptionName(s), texts_[i], help)->type_name(typeName(s)));
  }
}

ParamRequest TableOptions::request() const {
  ParamValues given;
  for (size_t i = 0; i < specs_->params.size(); ++i)
    if (options_[i] && options_[i]->count() > 0) given.emplace_back(specs_->params[i].name, valueOf(specs_->params[i], texts_[i]));
  return ParamRequest(*specs_, std::move(given));
}

CLI::Validator positiveCheck() { return numberCheck(positiveProblem, "> 0"); }

CLI::Validator rangeCheck(double min, double max) {
  return numberCheck(
      [min, max](double x) {
        const std::string whole = wholeProblem(x);
        return whole.empty() ? rangeProblem(x, min, max) : whole;
      },
      "INT [" + formatNumber(min) + ", " + formatNumber(max) + "]");
}

CLI::Validator atLeastCheck(double min) {
  return numberCheck([min](double x) { return atLeastProblem(x, min); }, ">= " + formatNumber(min));
}

}  // namespace geoshift::cli
