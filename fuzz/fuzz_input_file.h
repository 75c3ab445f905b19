// For fuzz targets of readers that take a path (the YAML config, point
// files, PNG rasters): the input written to one file per process, rewritten
// for every input, so the reader under test runs unchanged, file I/O and all.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

namespace scallop::fuzz {

// Writes `data` to this process's input file (in /tmp, named by the pid and
// `suffix`, e.g. ".yaml") and returns its path. Aborts if it cannot write:
// a fuzzer that silently tested an empty file would report coverage it lacks.
inline const std::string& WriteInputFile(const uint8_t* data, size_t size, const char* suffix) {
  static const std::string path = "/tmp/scallop-fuzz-input-" + std::to_string(getpid()) + suffix;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) std::abort();
  return path;
}

}  // namespace scallop::fuzz
