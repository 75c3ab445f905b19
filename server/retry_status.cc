#include "server/retry_status.h"

#include <cmath>

#include "google/rpc/status.pb.h"
#include "scallop/base/number_text.h"

namespace scallop::server {

grpc::Status ResourceExhaustedRetryAfter(const std::string& message, double retry_after_seconds) {
  const auto millis = static_cast<int64_t>(std::ceil(retry_after_seconds * 1000));
  const std::string text =
      message + "; retry after " + NumberText(static_cast<double>(millis) / 1000.0) + " s";
  google::rpc::RetryInfo retry;
  retry.mutable_retry_delay()->set_seconds(millis / 1000);
  retry.mutable_retry_delay()->set_nanos(static_cast<int32_t>(millis % 1000) * 1000000);
  google::rpc::Status details;
  details.set_code(grpc::StatusCode::RESOURCE_EXHAUSTED);
  details.set_message(text);
  details.add_details()->PackFrom(retry);
  return {grpc::StatusCode::RESOURCE_EXHAUSTED, text, details.SerializeAsString()};
}

}  // namespace scallop::server
