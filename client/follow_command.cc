// `scallop follow`: PLACEHOLDER until issue 8 lands (replaced in this session).
#include <iostream>

#include "commands.h"

namespace scallop::cli {

CommandRunner RegisterFollow(CLI::App& app) {
  app.add_subcommand("follow", "(not yet available)");
  return [] {
    std::cerr << "scallop follow: not yet available\n";
    return 2;
  };
}

}  // namespace scallop::cli
