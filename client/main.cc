// `scallop`: the command line. Subcommands run the core locally (generate,
// plane, verify, analyze) or talk to a scallopd server.
#include <CLI/CLI.hpp>
#include <iostream>
#include <vector>

#include "client/commands/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"scallop: Poisson-disk points on an unbounded plane"};
  app.require_subcommand(1);
  const std::vector<std::pair<std::string, scallop::cli::CommandRunner>> commands{
      {"generate", scallop::cli::RegisterGenerate(app)},
      {"plane", scallop::cli::RegisterPlane(app)},
      {"verify", scallop::cli::RegisterVerify(app)},
      {"points", scallop::cli::RegisterPoints(app)},
      {"stream", scallop::cli::RegisterStream(app)},
      {"info", scallop::cli::RegisterInfo(app)},
      {"health", scallop::cli::RegisterHealth(app)},
      {"nearest", scallop::cli::RegisterNearest(app)},
      {"noise", scallop::cli::RegisterNoise(app)},
      {"analyze", scallop::cli::RegisterAnalyze(app)},
      {"follow", scallop::cli::RegisterFollow(app)},
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;  // bad arguments, whatever CLI11's own code
  }
  for (const auto& [name, run] : commands) {
    if (app.got_subcommand(name)) return run();
  }
  return 2;
}
