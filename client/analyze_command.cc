// `scallop analyze`: PLACEHOLDER until issue 6 lands (replaced in this session).
#include <iostream>

#include "commands.h"

namespace scallop::cli {

CommandRunner RegisterAnalyze(CLI::App& app) {
  app.add_subcommand("analyze", "(not yet available)");
  return [] {
    std::cerr << "scallop analyze: not yet available\n";
    return 2;
  };
}

}  // namespace scallop::cli
