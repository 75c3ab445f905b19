// The HTTP endpoint Prometheus scrapes: GET /metrics answers the text of a
// render function; anything else is 404 (405 for other methods). Boost.Beast
// on its own Asio thread, so scrapes never wait behind gRPC work. Connections
// are capped and accepting resumes after errors (out of file descriptors), so
// idle or abandoned connections cannot take the endpoint down for good.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "scallop/base/status.h"

namespace scallop::server {

class MetricsHttpServer {
 public:
  using Render = std::function<std::string()>;

  // Listens on HOST:PORT (port 0: any free port) and serves until Stop or
  // destruction, at most `max_connections` connections at once: one beyond
  // that is closed as soon as it is accepted (the scraper retries) rather
  // than left to hold a file descriptor. INVALID_ARGUMENT naming
  // `--metrics-listen` when the address cannot be parsed or bound.
  static StatusOr<std::unique_ptr<MetricsHttpServer>> Start(const std::string& listen,
                                                            Render render,
                                                            int max_connections = 16);
  ~MetricsHttpServer();

  int port() const;
  // Stops accepting and joins the thread; idempotent.
  void Stop();

 private:
  struct State;
  explicit MetricsHttpServer(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace scallop::server
