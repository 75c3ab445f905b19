// The metrics endpoint: an Asio acceptor with a connection cap, and one
// keep-alive HTTP session a connection.
#include "server/metrics_http_server.h"

#include <spdlog/spdlog.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <thread>

namespace scallop::server {
namespace {

namespace asio = boost::asio;
namespace http = boost::beast::http;
using tcp = asio::ip::tcp;

// How long accepting pauses after an error such as EMFILE: long enough not
// to spin while descriptors are short, short enough that scrapes resume at
// once when they come back.
constexpr auto kAcceptRetryDelay = std::chrono::milliseconds(100);

// One connection: read a request, answer it, repeat while keep-alive. The
// session owns itself through the shared_ptr its pending handler holds, and
// counts itself in `open` (the server's count, on the same single thread).
class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(tcp::socket socket, const MetricsHttpServer::Render& render, int& open)
      : stream_(std::move(socket)), render_(render), open_(open) {
    ++open_;
  }
  ~Session() { --open_; }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  void Read() {
    request_ = {};
    // A scrape that stalls must not hold a socket for ever.
    stream_.expires_after(std::chrono::seconds(30));
    http::async_read(stream_, buffer_, request_,
                     [self = shared_from_this()](boost::beast::error_code error, size_t) {
                       if (!error) self->Answer();
                     });
  }

 private:
  void Answer() {
    response_ = {};
    response_.version(request_.version());
    response_.keep_alive(request_.keep_alive());
    response_.set(http::field::server, "scallopd");
    if (request_.method() != http::verb::get && request_.method() != http::verb::head) {
      response_.result(http::status::method_not_allowed);
      response_.set(http::field::allow, "GET, HEAD");
      response_.body() = "only GET /metrics\n";
    } else if (request_.target() != "/metrics") {
      response_.result(http::status::not_found);
      response_.body() = "scallopd serves /metrics only\n";
    } else {
      response_.result(http::status::ok);
      response_.set(http::field::content_type, "text/plain; version=0.0.4; charset=utf-8");
      response_.body() = render_();
    }
    if (response_.result() != http::status::ok) {
      response_.set(http::field::content_type, "text/plain; charset=utf-8");
    }
    response_.prepare_payload();
    if (request_.method() == http::verb::head) response_.body().clear();
    http::async_write(stream_, response_,
                      [self = shared_from_this()](boost::beast::error_code error, size_t) {
                        if (error || !self->response_.keep_alive()) {
                          boost::beast::error_code ignored;
                          self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
                          return;
                        }
                        self->Read();
                      });
  }

  boost::beast::tcp_stream stream_;
  const MetricsHttpServer::Render& render_;
  int& open_;
  boost::beast::flat_buffer buffer_;
  http::request<http::string_body> request_;
  http::response<http::string_body> response_;
};

}  // namespace

struct MetricsHttpServer::State {
  // Declared before `context`, whose destruction destroys the sessions still
  // pending, which then uncount themselves here.
  int open_connections = 0;  // touched only on `thread`
  int max_connections = 16;
  asio::io_context context{1};
  tcp::acceptor acceptor{context};
  asio::steady_timer retry{context};
  Render render;
  std::thread thread;

  // Every path re-arms (but Stop's): a handler that returned on an error
  // left the endpoint dead for the life of the process.
  void Accept() {
    acceptor.async_accept([this](boost::beast::error_code error, tcp::socket socket) {
      if (error == asio::error::operation_aborted) return;  // closed by Stop
      if (error) {
        spdlog::warn("metrics: accept failed ({}); retrying in {} ms", error.message(),
                     kAcceptRetryDelay.count());
        retry.expires_after(kAcceptRetryDelay);
        retry.async_wait([this](boost::beast::error_code wait_error) {
          if (!wait_error) Accept();
        });
        return;
      }
      if (open_connections >= max_connections) {
        boost::beast::error_code ignored;
        socket.close(ignored);  // over the cap: its descriptor back at once
      } else {
        std::make_shared<Session>(std::move(socket), render, open_connections)->Read();
      }
      Accept();
    });
  }
};

StatusOr<std::unique_ptr<MetricsHttpServer>> MetricsHttpServer::Start(const std::string& listen,
                                                                      Render render,
                                                                      int max_connections) {
  const size_t colon = listen.rfind(':');
  if (colon == std::string::npos) {
    return InvalidArgument("--metrics-listen: '" + listen + "' is not HOST:PORT");
  }
  std::string host = listen.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  unsigned long port = 0;
  try {
    size_t used = 0;
    port = std::stoul(listen.substr(colon + 1), &used);
    if (used != listen.size() - colon - 1 || port > 65535) throw std::out_of_range("port");
  } catch (const std::exception&) {
    return InvalidArgument("--metrics-listen: port of '" + listen + "' must be in 0..65535");
  }
  auto state = std::make_unique<State>();
  state->render = std::move(render);
  state->max_connections = max_connections;
  boost::system::error_code error;
  const asio::ip::address address =
      asio::ip::make_address(host == "localhost" ? "127.0.0.1" : host, error);
  if (error) return InvalidArgument("--metrics-listen: '" + host + "' is not an IP address");
  const tcp::endpoint endpoint(address, static_cast<unsigned short>(port));
  state->acceptor.open(endpoint.protocol(), error);
  if (!error) state->acceptor.set_option(asio::socket_base::reuse_address(true), error);
  if (!error) state->acceptor.bind(endpoint, error);
  if (!error) state->acceptor.listen(asio::socket_base::max_listen_connections, error);
  if (error) {
    return InvalidArgument("--metrics-listen: cannot listen on " + listen + ": " + error.message());
  }
  state->Accept();
  state->thread = std::thread([context = &state->context] { context->run(); });
  return std::unique_ptr<MetricsHttpServer>(new MetricsHttpServer(std::move(state)));
}

MetricsHttpServer::MetricsHttpServer(std::unique_ptr<State> state) : state_(std::move(state)) {}

MetricsHttpServer::~MetricsHttpServer() { Stop(); }

int MetricsHttpServer::port() const { return state_->acceptor.local_endpoint().port(); }

void MetricsHttpServer::Stop() {
  if (!state_->thread.joinable()) return;
  state_->context.stop();
  state_->thread.join();
}

}  // namespace scallop::server
