// glibc's malloc, set up for a server that builds ~100 kB responses over and
// over (docs/performance.md, "Service under load").
#pragma once

namespace scallop::server {

// Fixes glibc's trim and mmap thresholds (trim above 4 MiB of free heap top,
// mmap only for blocks of 1 MiB and more). With the defaults, freeing a
// response's buffers returned their pages to the kernel after every request,
// and the next request faulted them in again: about 10 page faults and a
// fifth of the server's CPU time per warm 64 d tile. Does nothing when the
// operator set malloc tunables in GLIBC_TUNABLES, which then win.
void TuneMallocForResponses();

}  // namespace scallop::server
