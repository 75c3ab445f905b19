// null_server: a scallop.v1.Scallop server whose GetPoints answers with real
// responses serialized at start-up (null_server_responses.h), copied by
// reference, on gRPC's own callback threads. It does no query work, so the
// load generator against it measures the transport limit that scallopd's
// figures are compared with. Other methods are UNIMPLEMENTED.
//
//   null_server --listen 127.0.0.1:0 --tile 64   # prints "null_server listening on HOST:PORT"
#include <grpcpp/grpcpp.h>
#include <signal.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstring>
#include <iostream>

#include "bench/load_tile_plan.h"
#include "bench/null_server_responses.h"
#include "scallop/v1/scallop.grpc.pb.h"
#include "server/lock_order_checks.h"

namespace scallop::load {
namespace {

// GetPoints on raw bytes: the request is parsed only to check the tile size,
// as any server must parse it; the answer is a stored buffer, whose slices
// are shared, not copied.
class NullScallopService final
    : public v1::Scallop::WithRawCallbackMethod_GetPoints<v1::Scallop::CallbackService> {
 public:
  NullScallopService(std::vector<grpc::ByteBuffer> responses, double tile_side)
      : responses_(std::move(responses)), tile_side_(tile_side) {}

  grpc::ServerUnaryReactor* GetPoints(grpc::CallbackServerContext* context,
                                      const grpc::ByteBuffer* request,
                                      grpc::ByteBuffer* response) override {
    grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
    grpc::ByteBuffer request_bytes = *request;
    v1::GetPointsRequest parsed;
    if (!grpc::SerializationTraits<v1::GetPointsRequest>::Deserialize(&request_bytes, &parsed)
             .ok()) {
      reactor->Finish({grpc::StatusCode::INVALID_ARGUMENT, "null server: unparsable request"});
      return reactor;
    }
    const v1::Rect& rect = parsed.rect();
    if (std::abs(rect.x1() - rect.x0() - tile_side_) > 1e-6 ||
        std::abs(rect.y1() - rect.y0() - tile_side_) > 1e-6) {
      reactor->Finish({grpc::StatusCode::INVALID_ARGUMENT,
                       "null server: answers only tiles of side " + std::to_string(tile_side_)});
      return reactor;
    }
    // The same rectangle always gets the same stored answer.
    uint64_t x_bits = 0;
    uint64_t y_bits = 0;
    const double x0 = rect.x0();
    const double y0 = rect.y0();
    std::memcpy(&x_bits, &x0, sizeof x_bits);
    std::memcpy(&y_bits, &y0, sizeof y_bits);
    *response = responses_[SplitMix64(x_bits ^ SplitMix64(y_bits)) % responses_.size()];
    reactor->Finish(grpc::Status::OK);
    return reactor;
  }

 private:
  const std::vector<grpc::ByteBuffer> responses_;
  const double tile_side_;
};

bool IsLoopbackListen(const std::string& listen) {
  return listen.rfind("127.", 0) == 0 || listen.rfind("localhost:", 0) == 0 ||
         listen.rfind("[::1]:", 0) == 0;
}

}  // namespace
}  // namespace scallop::load

int main(int argc, char** argv) {
  std::string listen = "127.0.0.1:0";
  scallop::load::NullResponseOptions options;
  options.world =
      *scallop::World::Create({.seed = 1});  // scallopd's built-in default world: seed 1, d 1, A3
  CLI::App app{"null_server: GetPoints answered with pre-serialized responses"};
  app.add_option("--listen", listen, "HOST:PORT, loopback only (port 0: any free port)")
      ->capture_default_str();
  app.add_option("--tile", options.tile_side, "Side in d of the tiles it answers")
      ->check(CLI::Range(1.0, 512.0))
      ->capture_default_str();
  app.add_option("--responses", options.count, "Distinct stored responses")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  if (!scallop::load::IsLoopbackListen(listen)) {
    std::cerr << "null_server: --listen must be a loopback address, got " << listen << '\n';
    return 2;
  }

  // As scallopd does, so that the two run the same transport.
  scallop::server::TurnOffLockOrderChecks();
  scallop::load::NullScallopService service(scallop::load::BuildNullResponses(options),
                                            options.tile_side);
  // Signals are taken by sigwait below; gRPC's threads inherit the mask.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(listen, grpc::InsecureServerCredentials(), &port);
  builder.RegisterService(&service);
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    std::cerr << "null_server: cannot listen on " << listen << '\n';
    return 1;
  }
  std::cout << "null_server listening on " << listen.substr(0, listen.rfind(':')) << ':' << port
            << std::endl;
  int signal_number = 0;
  sigwait(&stop_signals, &signal_number);
  server->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  return 0;
}
