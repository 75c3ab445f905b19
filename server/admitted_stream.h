// The two ends every streaming call shares: it takes an in-flight slot when it
// starts (or is shed with RESOURCE_EXHAUSTED), and when it ends it writes its
// log line and gives the slot back, exactly once.
#pragma once

#include <grpcpp/support/status.h>

#include <string>

#include "server/in_flight_limit.h"
#include "server/request_log.h"

namespace scallop::server {

// `Reactor` is one of gRPC's callback stream reactors (anything with
// Finish(const grpc::Status&)). A streaming call holds its slot for its whole
// life: it keeps per-client state and may ask for work at any moment.
template <typename Reactor>
class AdmittedStream : public Reactor {
 protected:
  // `limit` and `metrics` (may be null) must outlive the call.
  AdmittedStream(InFlightLimit& limit, const char* method, RequestMetrics* metrics)
      : log_(method, metrics), limit_(limit) {}

  // Takes a slot. When `access` (ServiceContext::Authorize) is not OK or the
  // server is full, finishes the call and returns false.
  bool Admit(const grpc::Status& access) {
    if (!access.ok()) {
      FinishWith(access);
      return false;
    }
    if (!limit_.TryAdmit()) {
      FinishWith(limit_.Refusal());
      return false;
    }
    admitted_ = true;
    return true;
  }

  // Logs the call, frees its slot if it had one, and finishes it. Call once.
  void FinishWith(const grpc::Status& status) {
    log_.Finish(status);
    if (admitted_) limit_.Release();
    this->Finish(status);
  }

  RequestLog log_;

 private:
  InFlightLimit& limit_;
  bool admitted_ = false;
};

}  // namespace scallop::server
