// A small HTTP/1.1 server on Boost.Beast, shared by the Prometheus endpoint
// and the tile endpoint: Asio threads of its own accept and parse, a handler
// answers (at once, or later from another thread). Connections are capped
// and accepting resumes after errors (out of file descriptors), so idle or
// abandoned connections cannot take the listener down for good.
#pragma once

#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "scallop/base/status.h"

namespace scallop::server {

class HttpListener {
 public:
  using Request = boost::beast::http::request<boost::beast::http::string_body>;
  using Response = boost::beast::http::response<boost::beast::http::string_body>;
  // Answers the request it was handed; call it exactly once, from any thread.
  // The listener fills in version, keep-alive, Server and Content-Length, and
  // drops the body of an answer to HEAD.
  using Respond = std::function<void(Response)>;
  // Runs on one of the listener's threads (for many connections at once), so
  // it must not block: slow work goes to a
  // pool, which calls `respond` when done. `request` lives only for the call:
  // copy what the work needs. The connection reads its next request only
  // after the answer is written. `peer` is the client's address as gRPC
  // writes a peer ("ipv4:127.0.0.1:51234", "ipv6:[::1]:51234"), for
  // per-client limits (client_key.h).
  using Handler =
      std::function<void(const Request& request, const std::string& peer, Respond respond)>;

  // Listens on HOST:PORT (port 0: any free port) and serves until Stop or
  // destruction, at most `max_connections` connections at once: one beyond
  // that is closed as soon as it is accepted (the client retries) rather than
  // left to hold a file descriptor. `name` starts its log lines ("metrics:
  // accept failed ...") and, as "--NAME-listen", its errors: INVALID_ARGUMENT
  // when the address cannot be parsed or bound. `threads` run the sockets
  // and the handler (a connection's requests in order, connections at once).
  static StatusOr<std::unique_ptr<HttpListener>> Start(const std::string& listen,
                                                       const std::string& name, Handler handler,
                                                       int max_connections, int threads = 1);
  ~HttpListener();
  HttpListener(const HttpListener&) = delete;
  HttpListener& operator=(const HttpListener&) = delete;

  int port() const;
  // Stops accepting and joins the threads; idempotent. Answers still pending
  // in a pool are dropped, so stop the pool first when they matter.
  void Stop();

 private:
  struct State;
  explicit HttpListener(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// Beast's header values are boost::string_view; ours are std::string_view.
inline boost::beast::string_view AsBeastText(std::string_view text) {
  return {text.data(), text.size()};
}
inline std::string_view AsStdText(boost::beast::string_view text) {
  return {text.data(), text.size()};
}

}  // namespace scallop::server
