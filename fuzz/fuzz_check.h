// The invariant check of the fuzz targets: on failure it prints what was
// expected and the values involved, then aborts, so libFuzzer saves the input
// as a crash to replay.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

#define SCALLOP_FUZZ_CHECK(condition, detail)                                                     \
  do {                                                                                            \
    if (!(condition)) {                                                                           \
      std::fprintf(stderr, "%s:%d: invariant failed: %s\n  %s\n", __FILE__, __LINE__, #condition, \
                   std::string(detail).c_str());                                                  \
      std::abort();                                                                               \
    }                                                                                             \
  } while (false)
