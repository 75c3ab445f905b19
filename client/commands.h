// The CLI's subcommands. Each registers its options on the app and returns
// the function that runs it; the function returns the process exit code:
// 0 on success, 1 on a failure reported by a server, 2 on bad arguments.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace scallop::cli {

using CommandRunner = std::function<int()>;

// `scallop generate`: a bounded-domain sampler's output.
CommandRunner RegisterGenerate(CLI::App& app);

}  // namespace scallop::cli
