// The network rule of the load programs: they only ever drive a server on
// this machine, so a mistyped target cannot load someone else's service.
#pragma once

#include <string>

namespace scallop::load {

// True for 127.x.x.x:PORT, localhost:PORT and [::1]:PORT.
inline bool IsLoopbackTarget(const std::string& target) {
  for (const char* prefix : {"127.", "localhost:", "[::1]:"}) {
    if (target.rfind(prefix, 0) == 0) return true;
  }
  return false;
}

}  // namespace scallop::load
