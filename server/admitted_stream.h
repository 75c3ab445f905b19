// The two ends every streaming call shares: it takes a slot of the streams'
// budget when it starts (or is shed with RESOURCE_EXHAUSTED), and when it ends
// it writes its log line and gives the slot back, exactly once.
#pragma once

#include <grpcpp/support/status.h>

#include <string>

#include "server/request_log.h"
#include "server/service_context.h"

namespace scallop::server {

// `Reactor` is one of gRPC's callback stream reactors (anything with
// Finish(const grpc::Status&)). A streaming call holds its slot for its whole
// life: it keeps per-client state and may ask for work at any moment.
template <typename Reactor>
class AdmittedStream : public Reactor {
 protected:
  // `shared` must outlive the call.
  AdmittedStream(ServiceContext& shared, const char* method)
      : log_(method, shared.metrics), shared_(shared) {}

  // Takes a slot (every stream costs 1). When `access`
  // (ServiceContext::Authorize) is not OK, or the client or the server is
  // over its limits, finishes the call and returns false.
  bool Admit(const grpc::ServerContextBase& context, const grpc::Status& access) {
    if (!access.ok()) {
      FinishWith(access);
      return false;
    }
    if (grpc::Status status = shared_.Admit(context, shared_.streams_in_flight, 1, client_);
        !status.ok()) {
      FinishWith(status);
      return false;
    }
    admitted_ = true;
    return true;
  }

  // Logs the call, frees its slot if it had one, and finishes it. Call once.
  void FinishWith(const grpc::Status& status) {
    log_.Finish(status);
    if (admitted_) shared_.streams_in_flight.Release(client_, 1);
    this->Finish(status);
  }

  RequestLog log_;

 private:
  ServiceContext& shared_;
  std::string client_;
  bool admitted_ = false;
};

}  // namespace scallop::server
