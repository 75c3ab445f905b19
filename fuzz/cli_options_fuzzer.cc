// The CLI's option parsing on arbitrary command lines: the input, split at
// newlines into arguments, is parsed by CLI11 with the world options every
// plane command registers (AddWorldOptions), then checked as the commands
// check it (ParseWorldQuery: --seed, the world, --rect, --threads). Each
// argument is also read as a --rect (ParseRect) and a --seed (ParseSeed)
// directly. Invariants: no crash; CLI11 fails only by its ParseError; every
// refusal names its option ("--rect: ...") or world field; an accepted
// rectangle is finite and not inverted, and printed back exactly (%.17g) it
// parses to the same bits; an accepted seed prints back as the same number.
#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "client/options/rect_option.h"
#include "client/options/world_options.h"
#include "fuzz/fuzz_check.h"

namespace {

using namespace scallop;

void CheckRect(const std::string& text) {
  const StatusOr<Rect> rect = cli::ParseRect(text, "--rect");
  if (!rect.ok()) {
    SCALLOP_FUZZ_CHECK(rect.status().message().starts_with("--rect: "), rect.status().message());
    return;
  }
  SCALLOP_FUZZ_CHECK(std::isfinite(rect->x0) && std::isfinite(rect->y1) && rect->x0 < rect->x1 &&
                         rect->y0 < rect->y1,
                     "accepted a bad rectangle: " + text);
  char printed[160];
  std::snprintf(printed, sizeof printed, "%.17g,%.17g,%.17g,%.17g", rect->x0, rect->y0, rect->x1,
                rect->y1);
  const StatusOr<Rect> again = cli::ParseRect(printed, "--rect");
  SCALLOP_FUZZ_CHECK(again.ok() && std::memcmp(&*again, &*rect, sizeof(Rect)) == 0,
                     std::string("rectangle does not round-trip: ") + printed);
}

void CheckSeed(const std::string& text) {
  const StatusOr<uint64_t> seed = cli::ParseSeed(text);
  if (!seed.ok()) {
    SCALLOP_FUZZ_CHECK(seed.status().message().starts_with("--seed: "), seed.status().message());
    return;
  }
  SCALLOP_FUZZ_CHECK(
      cli::ParseSeed(std::to_string(*seed)).ok() && *cli::ParseSeed(std::to_string(*seed)) == *seed,
      "seed does not round-trip: " + text);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> arguments{"scallop"};
  std::string current;
  for (size_t k = 0; k < size; ++k) {
    if (data[k] == '\n') {
      arguments.push_back(current);
      current.clear();
    } else {
      current.push_back(static_cast<char>(data[k]));
    }
  }
  arguments.push_back(current);
  for (size_t k = 1; k < arguments.size(); ++k) {
    CheckRect(arguments[k]);
    CheckSeed(arguments[k]);
  }

  CLI::App app{"fuzzed"};
  cli::WorldArguments world;
  cli::AddWorldOptions(app, world, /*with_rect=*/size % 2 == 0);
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError&) {
    return 0;  // what CLI11 reports to the user, with the usage
  }
  // A --world-file path from the input could name a device that never ends (/dev/zero): the
  // file's reading is the YAML library's, not what this fuzzer is for.
  world.world_file.clear();
  const Status status =
      world.rect.empty() ? cli::ParseWorld(world).status() : cli::ParseWorldQuery(world).status();
  SCALLOP_FUZZ_CHECK(status.ok() || status.message().find(": ") != std::string::npos,
                     "refusal without an option's name: " + status.message());
  return 0;
}
