// End to end: scallopd serves gRPC server reflection (what grpcurl and
// grpc_cli use) listing the Scallop service and the standard health service.
#include <gtest/gtest.h>

#include <algorithm>

#include "grpc/reflection/v1alpha/reflection.grpc.pb.h"
#include "tests/e2e/scallopd_process.h"

namespace scallop::testing {
namespace {

TEST(E2eReflectionTest, ListsTheScallopAndHealthServices) {
  auto server = ScallopdProcess::Start({});
  ASSERT_NE(server, nullptr);
  auto stub = grpc::reflection::v1alpha::ServerReflection::NewStub(server->Client().channel());
  grpc::ClientContext context;
  auto stream = stub->ServerReflectionInfo(&context);
  grpc::reflection::v1alpha::ServerReflectionRequest request;
  request.set_list_services("");
  ASSERT_TRUE(stream->Write(request));
  stream->WritesDone();
  grpc::reflection::v1alpha::ServerReflectionResponse response;
  ASSERT_TRUE(stream->Read(&response));
  std::vector<std::string> names;
  for (const auto& service : response.list_services_response().service()) {
    names.push_back(service.name());
  }
  while (stream->Read(&response)) {
  }
  EXPECT_TRUE(stream->Finish().ok());
  EXPECT_NE(std::find(names.begin(), names.end(), "scallop.v1.Scallop"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "grpc.health.v1.Health"), names.end());
}

}  // namespace
}  // namespace scallop::testing
