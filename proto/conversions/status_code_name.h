// The names of gRPC status codes ("INVALID_ARGUMENT"), as the server's log and
// the CLI's error messages print them.
#pragma once

#include <grpcpp/support/status.h>

namespace scallop {

const char* StatusCodeName(grpc::StatusCode code);

}  // namespace scallop
