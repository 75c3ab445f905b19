// Nearest and NoiseGrid: PLACEHOLDER until issue 5 lands (replaced in this session).
#include "scallop_service.h"

namespace scallop::server {

grpc::ServerUnaryReactor* ScallopService::Nearest(grpc::CallbackServerContext* context,
                                                  const v1::NearestRequest*,
                                                  v1::NearestResponse*) {
  return RunUnary(context, "Nearest", [](RequestLog&) {
    return grpc::Status(grpc::StatusCode::UNIMPLEMENTED, "Nearest: not yet");
  });
}

grpc::ServerUnaryReactor* ScallopService::NoiseGrid(grpc::CallbackServerContext* context,
                                                    const v1::NoiseGridRequest*,
                                                    v1::NoiseGridResponse*) {
  return RunUnary(context, "NoiseGrid", [](RequestLog&) {
    return grpc::Status(grpc::StatusCode::UNIMPLEMENTED, "NoiseGrid: not yet");
  });
}

}  // namespace scallop::server
