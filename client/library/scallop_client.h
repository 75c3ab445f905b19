// ScallopClient: a small synchronous C++ client of scallopd, for the CLI and
// for any program that links `scallop_client`. Paging and stream reading are
// done here, so callers get whole rectangles as the core's PlanePoints.
// Thread-safe: one client (one channel) may serve many threads.
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "scallop/plane/plane_engine.h"
#include "scallop/v1/scallop.grpc.pb.h"

namespace scallop::client {

// How to reach scallopd: plaintext by default; TLS when `tls` is set, with
// mutual TLS when a client certificate and key are given; a bearer token
// sent with every call when `token` is not empty. PEM texts, not file names,
// so that callers choose where keys come from (the CLI reads files).
struct ConnectionOptions {
  bool tls = false;
  std::string tls_ca_pem;    // roots that sign the server; empty: the system's roots
  std::string tls_cert_pem;  // client certificate chain, for mutual TLS (with the key)
  std::string tls_key_pem;   // its private key
  // Sent as "authorization: Bearer TOKEN". Over plaintext anyone on the path
  // reads it: use it with TLS outside a trusted network.
  std::string token;
};

struct CallOptions {
  // Deadline of each call, from when it starts; none when unset.
  std::optional<std::chrono::milliseconds> timeout;
};

class ScallopClient {
 public:
  // `token`, when not empty, goes with every call as a bearer token.
  explicit ScallopClient(std::shared_ptr<grpc::Channel> channel, std::string token = {});

  // A client of `address` over plaintext. Cheap: connects on the first call.
  // `address` is HOST:PORT or any gRPC target: dns:///HOST:PORT (every
  // address the name resolves to), ipv4:ADDR:PORT,ADDR:PORT,... A target
  // that names its resolver (dns:, ipv4:, ipv6:) balances calls round_robin
  // over its addresses and retries the idempotent unary calls on UNAVAILABLE
  // (service_config.h); through a proxy, dns:///PROXY:PORT asks for the
  // retries.
  static ScallopClient Connect(const std::string& address);
  // The same with TLS, mutual TLS and a token as `options` asks. PEM texts
  // are checked only at the handshake: a bad one fails the first call
  // (UNAVAILABLE), so read and check files before (as the CLI does).
  static ScallopClient Connect(const std::string& address, const ConnectionOptions& options);

  // Sets the deadline and the token on a context, for callers that make
  // their own stubs on channel() (FollowClient).
  void Configure(grpc::ClientContext& context, const CallOptions& options) const;

  // One page, as the server returns it.
  grpc::Status GetPoints(const v1::GetPointsRequest& request, v1::GetPointsResponse& response,
                         const CallOptions& options = {});

  // Every point of request.rect, following next_page_token until the last page
  // (request.page_token is the first page's). Points are appended to `points`,
  // and for a field world their radii (R at each point) to `radii` if given.
  grpc::Status GetAllPoints(v1::GetPointsRequest request, PlanePoints& points,
                            const CallOptions& options = {}, std::vector<double>* radii = nullptr);

  // Reads a stream, calling on_chunk for each chunk in order. on_chunk returns
  // false to cancel the call (the result is then CANCELLED).
  grpc::Status StreamPoints(const v1::StreamPointsRequest& request,
                            const std::function<bool(const v1::PointsChunk&)>& on_chunk,
                            const CallOptions& options = {});

  // Every chunk's points appended to `points` (and radii, as GetAllPoints).
  grpc::Status StreamAllPoints(const v1::StreamPointsRequest& request, PlanePoints& points,
                               const CallOptions& options = {},
                               std::vector<double>* radii = nullptr);

  grpc::Status Verify(const v1::VerifyRequest& request, v1::VerifyResponse& response,
                      const CallOptions& options = {});
  grpc::Status DescribeWorld(const v1::DescribeWorldRequest& request,
                             v1::DescribeWorldResponse& response, const CallOptions& options = {});
  grpc::Status GetServerInfo(v1::GetServerInfoResponse& response, const CallOptions& options = {});

  // The noise basis at request.positions (at most the server's
  // max_nearest_batch: split larger sets into several calls), in their order.
  grpc::Status Nearest(const v1::NearestRequest& request, v1::NearestResponse& response,
                       const CallOptions& options = {});
  // One channel on a grid of at most max_noise_grid_samples samples.
  grpc::Status NoiseGrid(const v1::NoiseGridRequest& request, v1::NoiseGridResponse& response,
                         const CallOptions& options = {});

  // The standard health check: true when SERVING. `service` "" asks about
  // the server as a whole (NOT_SERVING while draining or saturated);
  // scallopd's "liveness" only whether the process answers.
  grpc::Status CheckHealth(bool& serving, const CallOptions& options = {},
                           const std::string& service = "");

  const std::shared_ptr<grpc::Channel>& channel() const { return channel_; }

 private:
  std::shared_ptr<grpc::Channel> channel_;
  std::string token_;
  std::unique_ptr<v1::Scallop::Stub> stub_;
};

// "INVALID_ARGUMENT: rect.x0: must be finite", for messages on stderr.
std::string DescribeStatus(const grpc::Status& status);

// How long the server asks the client to wait before calling again, in
// seconds: the google.rpc.RetryInfo of a rate-limited call's status details
// (RESOURCE_EXHAUSTED); -1 when the status carries none.
double RetryAfterSeconds(const grpc::Status& status);

}  // namespace scallop::client
