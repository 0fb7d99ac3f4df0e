#pragma once
// The subcommands of the geoshift CLI. Each registers its subcommand and options on the app and
// returns it with the function that runs it; main() dispatches and turns errors into messages and exit codes.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "geoshift/io.hpp"
#include "geoshift/mesh.hpp"
#include "geoshift/params.hpp"

namespace geoshift::cli {

struct Command {
  CLI::App* sub = nullptr;
  std::function<void()> run;
};

Command addInfo(CLI::App& app);
Command addNoise(CLI::App& app);
Command addSmooth(CLI::App& app);
Command addCurvature(CLI::App& app);
Command addCompare(CLI::App& app);
Command addGeodesic(CLI::App& app);
Command addLogMap(CLI::App& app);
Command addExpMap(CLI::App& app);
Command addWavelet(CLI::App& app);
Command addTerrain(CLI::App& app);
Command addFilter(CLI::App& app);
Command addDenoise(CLI::App& app);

// --- shared by the commands ---

// The options every input file is read with (--max-vertices; an OBJ's text not kept, read again to
// write back).
ReadOptions& readOptions();
// Reads a file with readOptions(), printing its pass-through warnings to stderr.
Document load(const std::string& path);
// Writes atomically, printing the writer's warnings; the summary line names the output.
void save(const Document& doc, const std::string& path);

// A part as a welded mesh; build messages go to stderr prefixed with the file and part.
MeshBuild buildPart(const Document& doc, const MeshPart& part);

// After the welded mesh's positions changed: positions back into the part's own layout, and its
// normals (if it has any) recomputed on the part's own, unwelded faces so hard edges stay hard.
void writeBack(MeshPart& part, const MeshBuild& build);
// After the part's positions changed: its normals (if it has any) those of the new positions, on
// its own, unwelded faces (docs/io.md#normals).
void recomputeNormals(MeshPart& part);

// --- options from the core's parameter tables (params.hpp) ---

// The help of a table entry: where it applies, its doc, its choices and defaults, then `note`:
// "meanshift: spatial bandwidth h_s in AEL (default 0.6; meanshift/paper 3)".
std::string specHelp(const ParamSpec& spec, const std::string& note = "");

// The options of an op's parameters on a subcommand (--kebab-case names, help and defaults from the
// core's table), kept as the text given, so that request() checks them as the wasm op does and a
// bad value gets the op's message (the check vocabulary's words, exit code 1). Construct it in
// place (CLI11 keeps references into it) before the command parses.
class TableOptions {
 public:
  // `skip`: parameters the command does not offer; `notes`: text added to a parameter's help.
  TableOptions(CLI::App* sub, const std::string& op, const std::vector<std::string>& skip = {},
               const std::vector<std::pair<std::string, std::string>>& notes = {});
  TableOptions(const TableOptions&) = delete;
  TableOptions& operator=(const TableOptions&) = delete;

  // The options given on the command line as a checked request; InputError as ParamRequest.
  ParamRequest request() const;

 private:
  const OpParamSpecs* specs_;
  std::vector<CLI::Option*> options_;  // per parameter of the table; null when skipped
  std::vector<std::string> texts_;
};

// CLI11 checks in the check vocabulary's words (check.hpp), for options that have no table entry:
// CLI11 prints "--cell-size: must be > 0 (got -1)".
CLI::Validator positiveCheck();
CLI::Validator atLeastCheck(double min);
CLI::Validator rangeCheck(double min, double max);  // whole numbers in [min, max]

}  // namespace geoshift::cli
