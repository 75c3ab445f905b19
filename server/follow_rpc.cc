// Follow: PLACEHOLDER until issue 8 lands (replaced in this session).
#include "scallop_service.h"

namespace scallop::server {

grpc::ServerBidiReactor<v1::FollowRequest, v1::FollowResponse>* ScallopService::Follow(
    grpc::CallbackServerContext* context) {
  return v1::Scallop::CallbackService::Follow(context);
}

}  // namespace scallop::server
