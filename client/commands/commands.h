// The CLI's subcommands. Each registers its options on the app and returns
// the function that runs it; the function returns the process exit code:
// 0 on success, 1 on a failure found (a contract violation or one reported
// by a server), 2 on bad arguments.
#pragma once

#include <functional>

#include "client/options/cli_fwd.h"

namespace scallop::cli {

using CommandRunner = std::function<int()>;

// `scallop generate`: a bounded-domain sampler's output.
CommandRunner RegisterGenerate(CLI::App& app);

// `scallop plane`: a rectangle of an infinite world, with point ids.
CommandRunner RegisterPlane(CLI::App& app);

// `scallop verify`: the contract checked on a rectangle of a world, locally or
// with --server by scallopd; exit 1 when it fails or the server reports an error.
CommandRunner RegisterVerify(CLI::App& app);

// `scallop points`: a rectangle from scallopd's GetPoints, all pages.
CommandRunner RegisterPoints(CLI::App& app);

// `scallop stream`: a rectangle from scallopd's StreamPoints.
CommandRunner RegisterStream(CLI::App& app);

// `scallop info`: scallopd's version, limits, worlds and health.
CommandRunner RegisterInfo(CLI::App& app);

// `scallop health`: exit 0 when scallopd is SERVING, for probes.
CommandRunner RegisterHealth(CLI::App& app);

// `scallop nearest`: nearest point id, F1 and F2 at positions, locally or
// with --server by scallopd.
CommandRunner RegisterNearest(CLI::App& app);

// `scallop noise`: a noise channel on a grid, rendered as a PNG image.
CommandRunner RegisterNoise(CLI::App& app);

// `scallop analyze`: periodogram, radial power, anisotropy and spacing
// statistics of a point set, as images and JSON.
CommandRunner RegisterAnalyze(CLI::App& app);

// `scallop follow`: replays a path of viewports through scallopd's Follow.
CommandRunner RegisterFollow(CLI::App& app);

}  // namespace scallop::cli
