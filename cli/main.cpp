// geoshift: command-line front end of the core. Thin: parses arguments, calls the library.
#include <cstdio>  // first: it defines __GLIBC__ where glibc is the C library
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <exception>
#include <iostream>
#include <limits>

#include "commands.hpp"
#include "geoshift/error.hpp"

int main(int argc, char** argv) {
#ifdef __GLIBC__
  // Arrays of 1 MB and more get their own mappings, returned when freed. glibc's default raises
  // that threshold as large arrays are freed, after which the denoiser's per-pass arrays land in
  // the heap and fragment it: the 144k-vertex denoise peaked 8 MB higher (docs/denoising.md#speed-and-memory).
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
  CLI::App app{"geoshift: filters for signals on triangle meshes (glTF, OBJ, OFF, PLY, STL)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "geoshift 0.1.0");
  // Before or after the subcommand: subcommands pass options they do not know up to here.
  app.add_option("--max-vertices", geoshift::cli::readOptions().maxVertices,
                 "refuse input files declaring more vertices than this, before allocating (default 50000000)")
      ->check(geoshift::cli::atLeastCheck(1));
  app.fallthrough();
  using namespace geoshift::cli;
  const std::vector<Command> commands = {addInfo(app), addNoise(app), addSmooth(app),
                                         addCurvature(app), addCompare(app),  addGeodesic(app),
                                         addLogMap(app),    addExpMap(app),     addWavelet(app),     addFilter(app),
                                         addDenoise(app),
                                         addTerrain(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    for (const Command& c : commands)
      if (c.sub->parsed()) c.run();
  } catch (const geoshift::InputError& e) {
    std::cerr << "geoshift: error: " << e.what() << "\n";
    return 1;
  } catch (const geoshift::Cancelled&) {
    std::cerr << "geoshift: cancelled; nothing written\n";
    return 130;
  } catch (const std::bad_alloc&) {
    std::cerr << "geoshift: error: out of memory; nothing written\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "geoshift: internal error: " << e.what() << "; nothing written\n";
    return 2;
  }
  return 0;
}
