// What a server started by a test (scallopd, nginx) does in the child between
// fork and exec, so that a test that dies without stopping it (an abort, a
// timeout's kill) leaves no server running on.
#pragma once

#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

namespace scallop::testing {

// Call in the child, with the parent's pid read before fork: the child is
// killed when the thread that forked it ends (PR_SET_PDEATHSIG), and exits at
// once if that thread had already ended before the request took hold.
inline void DieWithTheTest(pid_t parent) {
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(127);
}

}  // namespace scallop::testing
