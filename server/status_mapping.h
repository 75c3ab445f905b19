// The core's Status to gRPC's: the core's codes mirror gRPC's, and its
// messages already name the field and the allowed range.
#pragma once

#include <grpcpp/support/status.h>

#include "scallop/base/status.h"

namespace scallop::server {

grpc::Status ToGrpcStatus(const Status& status);

}  // namespace scallop::server
