// How a command ends when it does not succeed: the exit codes commands.h
// promises, and the one line on stderr, "scallop COMMAND: why", that says so.
#pragma once

#include <grpcpp/support/status.h>

#include <string_view>

#include "scallop/base/status.h"

namespace scallop::cli {

// Prints "scallop COMMAND: message" for arguments the command or the core
// refused before any work or call; returns exit code 2.
int ReportBadArguments(std::string_view command, const Status& status);

// Prints "scallop COMMAND: CODE: message" for a failed call to scallopd (or a
// malformed reply); returns exit code 1.
int ReportCallFailure(std::string_view command, const grpc::Status& status);

}  // namespace scallop::cli
