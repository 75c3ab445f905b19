// ScallopClient: unary calls, paging, stream reading and the health check.
#include "scallop_client.h"

#include "google/rpc/status.pb.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "service_config.h"
#include "status_code_name.h"
#include "world_messages.h"

namespace scallop::client {
namespace {

grpc::Status FromCore(const Status& status) {
  return status.ok()
             ? grpc::Status::OK
             : grpc::Status(grpc::StatusCode::INTERNAL, "malformed reply: " + status.message());
}

}  // namespace

ScallopClient::ScallopClient(std::shared_ptr<grpc::Channel> channel, std::string token)
    : channel_(std::move(channel)),
      token_(std::move(token)),
      stub_(v1::Scallop::NewStub(channel_)) {}

ScallopClient ScallopClient::Connect(const std::string& address) {
  return Connect(address, ConnectionOptions{});
}

ScallopClient ScallopClient::Connect(const std::string& address, const ConnectionOptions& options) {
  grpc::ChannelArguments arguments;
  // Pages reach max_page_size * 24 bytes (1.5 MB by default); allow larger servers.
  arguments.SetMaxReceiveMessageSize(64 << 20);
  if (NamesBalancedTarget(address)) arguments.SetServiceConfigJSON(std::string(kServiceConfigJson));
  std::shared_ptr<grpc::ChannelCredentials> credentials = grpc::InsecureChannelCredentials();
  if (options.tls) {
    credentials = grpc::SslCredentials({.pem_root_certs = options.tls_ca_pem,
                                        .pem_private_key = options.tls_key_pem,
                                        .pem_cert_chain = options.tls_cert_pem});
  }
  return ScallopClient(grpc::CreateCustomChannel(address, credentials, arguments), options.token);
}

void ScallopClient::Configure(grpc::ClientContext& context, const CallOptions& options) const {
  if (options.timeout) context.set_deadline(std::chrono::system_clock::now() + *options.timeout);
  // Per call rather than as channel call-credentials, which gRPC sends only
  // over TLS: a token on plaintext suits a TLS-terminating proxy in front.
  if (!token_.empty()) context.AddMetadata("authorization", "Bearer " + token_);
}

grpc::Status ScallopClient::GetPoints(const v1::GetPointsRequest& request,
                                      v1::GetPointsResponse& response, const CallOptions& options) {
  grpc::ClientContext context;
  Configure(context, options);
  return stub_->GetPoints(&context, request, &response);
}

grpc::Status ScallopClient::GetAllPoints(v1::GetPointsRequest request, PlanePoints& points,
                                         const CallOptions& options, std::vector<double>* radii) {
  while (true) {
    v1::GetPointsResponse response;
    if (grpc::Status status = GetPoints(request, response, options); !status.ok()) return status;
    if (grpc::Status status = FromCore(ReadPoints(response.points(), points, radii));
        !status.ok()) {
      return status;
    }
    if (response.next_page_token().empty()) return grpc::Status::OK;
    request.set_page_token(response.next_page_token());
  }
}

grpc::Status ScallopClient::StreamPoints(
    const v1::StreamPointsRequest& request,
    const std::function<bool(const v1::PointsChunk&)>& on_chunk, const CallOptions& options) {
  grpc::ClientContext context;
  Configure(context, options);
  std::unique_ptr<grpc::ClientReader<v1::PointsChunk>> reader =
      stub_->StreamPoints(&context, request);
  v1::PointsChunk chunk;
  while (reader->Read(&chunk)) {
    if (!on_chunk(chunk)) {
      context.TryCancel();
      while (reader->Read(&chunk)) {
      }
      break;
    }
  }
  return reader->Finish();
}

grpc::Status ScallopClient::StreamAllPoints(const v1::StreamPointsRequest& request,
                                            PlanePoints& points, const CallOptions& options,
                                            std::vector<double>* radii) {
  Status malformed;
  grpc::Status status = StreamPoints(
      request,
      [&](const v1::PointsChunk& chunk) {
        malformed = ReadPoints(chunk.points(), points, radii);
        return malformed.ok();
      },
      options);
  return malformed.ok() ? status : FromCore(malformed);
}

grpc::Status ScallopClient::Verify(const v1::VerifyRequest& request, v1::VerifyResponse& response,
                                   const CallOptions& options) {
  grpc::ClientContext context;
  Configure(context, options);
  return stub_->Verify(&context, request, &response);
}

grpc::Status ScallopClient::DescribeWorld(const v1::DescribeWorldRequest& request,
                                          v1::DescribeWorldResponse& response,
                                          const CallOptions& options) {
  grpc::ClientContext context;
  Configure(context, options);
  return stub_->DescribeWorld(&context, request, &response);
}

grpc::Status ScallopClient::GetServerInfo(v1::GetServerInfoResponse& response,
                                          const CallOptions& options) {
  grpc::ClientContext context;
  Configure(context, options);
  return stub_->GetServerInfo(&context, v1::GetServerInfoRequest(), &response);
}

grpc::Status ScallopClient::Nearest(const v1::NearestRequest& request,
                                    v1::NearestResponse& response, const CallOptions& options) {
  grpc::ClientContext context;
  Configure(context, options);
  return stub_->Nearest(&context, request, &response);
}

grpc::Status ScallopClient::NoiseGrid(const v1::NoiseGridRequest& request,
                                      v1::NoiseGridResponse& response, const CallOptions& options) {
  grpc::ClientContext context;
  Configure(context, options);
  return stub_->NoiseGrid(&context, request, &response);
}

grpc::Status ScallopClient::CheckHealth(bool& serving, const CallOptions& options,
                                        const std::string& service) {
  grpc::ClientContext context;
  Configure(context, options);
  grpc::health::v1::HealthCheckRequest request;
  request.set_service(service);
  grpc::health::v1::HealthCheckResponse response;
  const grpc::Status status =
      grpc::health::v1::Health::NewStub(channel_)->Check(&context, request, &response);
  serving = status.ok() && response.status() == grpc::health::v1::HealthCheckResponse::SERVING;
  return status;
}

std::string DescribeStatus(const grpc::Status& status) {
  return std::string(StatusCodeName(status.error_code())) + ": " + status.error_message();
}

double RetryAfterSeconds(const grpc::Status& status) {
  google::rpc::Status details;
  if (status.error_details().empty() || !details.ParseFromString(status.error_details())) {
    return -1;
  }
  for (const google::protobuf::Any& any : details.details()) {
    google::rpc::RetryInfo retry;
    if (any.UnpackTo(&retry)) {
      return static_cast<double>(retry.retry_delay().seconds()) +
             retry.retry_delay().nanos() * 1e-9;
    }
  }
  return -1;
}

}  // namespace scallop::client
