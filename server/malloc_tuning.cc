#include "server/malloc_tuning.h"

#include <malloc.h>

#include <cstdlib>
#include <cstring>

namespace scallop::server {

void TuneMallocForResponses() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables != nullptr && std::strstr(tunables, "glibc.malloc.") != nullptr) return;
  // Setting either threshold also turns off glibc's dynamic mmap threshold,
  // which otherwise moves with the sizes freed and brought the faults back.
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  mallopt(M_TRIM_THRESHOLD, 4 << 20);
}

}  // namespace scallop::server
