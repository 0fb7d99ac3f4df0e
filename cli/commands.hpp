#pragma once
// The subcommands of the geoshift CLI. Each registers its subcommand and options on the app and
// returns it with the function that runs it; main() dispatches and turns errors into messages and exit codes.
#include <functional>

#include <CLI/CLI.hpp>

#include "geoshift/io.hpp"
#include "geoshift/mesh.hpp"

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

// The options every input file is read with (--max-vertices).
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

}  // namespace geoshift::cli
