// `scallop nearest`: PLACEHOLDER until issue 5 lands (replaced in this session).
#include <iostream>

#include "commands.h"

namespace scallop::cli {

CommandRunner RegisterNearest(CLI::App& app) {
  app.add_subcommand("nearest", "(not yet available)");
  return [] {
    std::cerr << "scallop nearest: not yet available\n";
    return 2;
  };
}

}  // namespace scallop::cli
