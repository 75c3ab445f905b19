// RESOURCE_EXHAUSTED with a retry delay that clients can read: the delay in
// the message for people, and a google.rpc.RetryInfo in the status details
// (the grpc-status-details-bin trailer) for programs.
#pragma once

#include <grpcpp/support/status.h>

#include <string>

namespace scallop::server {

// REQUIRES: retry_after_seconds >= 0 and finite. The message gets
// "; retry after S s" appended, S rounded up to the millisecond.
grpc::Status ResourceExhaustedRetryAfter(const std::string& message, double retry_after_seconds);

// Clients read the delay back with client::RetryAfterSeconds (scallop_client.h).

}  // namespace scallop::server
