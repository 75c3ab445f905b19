// The HTTP endpoint Prometheus scrapes: GET /metrics answers the text of a
// render function; anything else is 404 (405 for other methods). A listener
// of its own (http_listener.h: capped connections, accepting resumes after
// errors), so scrapes never wait behind gRPC or tile work.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "scallop/base/status.h"
#include "server/http_listener.h"

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

  int port() const { return listener_->port(); }
  // Stops accepting and joins the thread; idempotent.
  void Stop() { listener_->Stop(); }

 private:
  explicit MetricsHttpServer(std::unique_ptr<HttpListener> listener)
      : listener_(std::move(listener)) {}
  std::unique_ptr<HttpListener> listener_;
};

}  // namespace scallop::server
