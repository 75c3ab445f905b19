// CLI11's App and Option, declared only: a header that names them in a registration function
// includes this, not <CLI/CLI.hpp>, whose header-only implementation costs several seconds of
// compile a translation unit; the .cc files that register options include CLI11 themselves.
#pragma once

namespace CLI {
class App;
class Option;
}  // namespace CLI
