// The point-file reader of `scallop analyze --input` (client/analysis/
// point_file.h) on arbitrary files, CSV and JSON. Invariants: no crash and no
// exception; a refusal names the file; an accepted file has at least one
// point, every coordinate finite.
#include <cmath>
#include <cstdint>
#include <string>

#include "client/analysis/point_file.h"
#include "fuzz/fuzz_check.h"
#include "fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& path = scallop::fuzz::WriteInputFile(data, size, ".points");
  const scallop::StatusOr<std::vector<scallop::Vec2>> points = scallop::cli::ReadPointFile(path);
  if (!points.ok()) {
    SCALLOP_FUZZ_CHECK(points.status().message().find(path) != std::string::npos,
                       "error without the file's name: " + points.status().message());
    return 0;
  }
  SCALLOP_FUZZ_CHECK(!points->empty(), "accepted a file without points");
  for (const scallop::Vec2& p : *points) {
    SCALLOP_FUZZ_CHECK(std::isfinite(p.x) && std::isfinite(p.y), "accepted a non-finite point");
  }
  return 0;
}
