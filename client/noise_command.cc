// `scallop noise`: PLACEHOLDER until issue 5 lands (replaced in this session).
#include <iostream>

#include "commands.h"

namespace scallop::cli {

CommandRunner RegisterNoise(CLI::App& app) {
  app.add_subcommand("noise", "(not yet available)");
  return [] {
    std::cerr << "scallop noise: not yet available\n";
    return 2;
  };
}

}  // namespace scallop::cli
