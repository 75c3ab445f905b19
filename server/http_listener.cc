// The HTTP listener: an Asio acceptor with a connection cap, and one
// keep-alive session a connection whose answers may come from other threads.
#include "server/http_listener.h"

#include <spdlog/spdlog.h>

#include <atomic>
#include <boost/asio/dispatch.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <mutex>
#include <thread>
#include <vector>

namespace scallop::server {
namespace {

namespace asio = boost::asio;
namespace http = boost::beast::http;
using tcp = asio::ip::tcp;

// How long accepting pauses after an error such as EMFILE: long enough not
// to spin while descriptors are short, short enough that clients are served
// again at once when they come back.
constexpr auto kAcceptRetryDelay = std::chrono::milliseconds(100);
// A client that stalls must not hold a socket for ever.
constexpr auto kReadTimeout = std::chrono::seconds(30);
// An answer not ready by then (a bug, or a pool stuck) closes the connection.
constexpr auto kAnswerTimeout = std::chrono::seconds(120);

// What answers from other threads go through: once the listener stops, the
// gate is shut and they are dropped rather than posted to a dead context.
struct Gate {
  std::mutex mutex;
  bool open = true;
};

// One connection: read a request, hand it to the handler, write its answer,
// repeat while keep-alive. The session owns itself through the shared_ptrs
// its pending operations hold (a read, a write, or the answer timer while
// the handler works), and counts itself in `open`. Its socket's executor is
// a strand, so its handlers never run at once on the listener's threads.
class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(tcp::socket socket, const HttpListener::Handler& handler, std::shared_ptr<Gate> gate,
          std::atomic<int>& open)
      : stream_(std::move(socket)),
        answer_timer_(stream_.get_executor()),
        handler_(handler),
        gate_(std::move(gate)),
        open_(open) {
    ++open_;
    boost::beast::error_code error;
    const tcp::endpoint remote = stream_.socket().remote_endpoint(error);
    if (!error) {
      const std::string address = remote.address().to_string();
      peer_ = remote.address().is_v6() ? "ipv6:[" + address + "]:" + std::to_string(remote.port())
                                       : "ipv4:" + address + ":" + std::to_string(remote.port());
    }
  }
  ~Session() { --open_; }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Starts the session on its strand: the first operation on the stream, like
  // every later one, must not run beside a handler of the session's.
  static void Start(tcp::socket socket, const HttpListener::Handler& handler,
                    std::shared_ptr<Gate> gate, std::atomic<int>& open) {
    auto session = std::make_shared<Session>(std::move(socket), handler, std::move(gate), open);
    asio::dispatch(session->stream_.get_executor(), [session] { session->Read(); });
  }

 private:
  void Read() {
    request_ = {};
    stream_.expires_after(kReadTimeout);
    http::async_read(stream_, buffer_, request_,
                     [self = shared_from_this()](boost::beast::error_code error, size_t) {
                       if (!error) self->Dispatch();
                     });
  }

  void Dispatch() {
    const uint64_t serial = ++serial_;
    // The timer's wait keeps the session alive while the handler works; the
    // answer holds only a weak reference, so it can be dropped on any thread.
    answer_timer_.expires_after(kAnswerTimeout);
    answer_timer_.async_wait([self = shared_from_this()](boost::beast::error_code error) {
      if (error) return;  // cancelled: the answer came
      boost::beast::error_code ignored;
      self->stream_.socket().close(ignored);
    });
    std::weak_ptr<Session> weak = weak_from_this();
    auto executor = stream_.get_executor();
    handler_(request_, peer_,
             [weak, executor, gate = gate_, serial](HttpListener::Response response) {
               const std::lock_guard lock(gate->mutex);
               if (!gate->open) return;
               asio::post(executor, [weak, serial, response = std::move(response)]() mutable {
                 if (std::shared_ptr<Session> self = weak.lock())
                   self->Write(serial, std::move(response));
               });
             });
  }

  void Write(uint64_t serial, HttpListener::Response response) {
    if (serial != serial_ || answered_ == serial) return;  // late, or a second answer
    answered_ = serial;
    answer_timer_.cancel();
    response_ = std::move(response);
    response_.version(request_.version());
    response_.keep_alive(request_.keep_alive());
    response_.set(http::field::server, "scallopd");
    response_.prepare_payload();
    if (request_.method() == http::verb::head) response_.body().clear();
    stream_.expires_after(kReadTimeout);
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
  asio::steady_timer answer_timer_;
  const HttpListener::Handler& handler_;
  std::shared_ptr<Gate> gate_;
  std::atomic<int>& open_;
  std::string peer_ = "unknown";
  uint64_t serial_ = 0;    // of the request being answered
  uint64_t answered_ = 0;  // the last serial written
  boost::beast::flat_buffer buffer_;
  HttpListener::Request request_;
  HttpListener::Response response_;
};

}  // namespace

struct HttpListener::State {
  // Declared before `context`, whose destruction destroys the sessions still
  // pending, which then uncount themselves here.
  std::atomic<int> open_connections{0};
  int max_connections = 16;
  std::string name;
  std::shared_ptr<Gate> gate = std::make_shared<Gate>();
  Handler handler;
  asio::io_context context;
  tcp::acceptor acceptor{context};
  asio::steady_timer retry{context};
  std::vector<std::thread> threads;

  // Each connection on a strand of its own: sessions run in parallel on the
  // threads, each one's handlers in order.
  void Accept() {
    acceptor.async_accept(asio::make_strand(context),
                          [this](boost::beast::error_code error, tcp::socket socket) {
                            OnAccept(error, std::move(socket));
                          });
  }

  // Every path re-arms (but Stop's): a handler that returned on an error
  // left the endpoint dead for the life of the process.
  void OnAccept(boost::beast::error_code error, tcp::socket socket) {
    if (error == asio::error::operation_aborted) return;  // closed by Stop
    if (error) {
      spdlog::warn("{}: accept failed ({}); retrying in {} ms", name, error.message(),
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
      // An answer is written whole at once: no reason to hold its tail back
      // for an ACK (Nagle), which costs a delayed ACK's 40 ms.
      boost::beast::error_code ignored;
      socket.set_option(tcp::no_delay(true), ignored);
      Session::Start(std::move(socket), handler, gate, open_connections);
    }
    Accept();
  }
};

StatusOr<std::unique_ptr<HttpListener>> HttpListener::Start(const std::string& listen,
                                                            const std::string& name,
                                                            Handler handler, int max_connections,
                                                            int threads) {
  const std::string flag = "--" + name + "-listen";
  const size_t colon = listen.rfind(':');
  if (colon == std::string::npos) {
    return InvalidArgument(flag + ": '" + listen + "' is not HOST:PORT");
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
    return InvalidArgument(flag + ": port of '" + listen + "' must be in 0..65535");
  }
  auto state = std::make_unique<State>();
  state->handler = std::move(handler);
  state->max_connections = max_connections;
  state->name = name;
  boost::system::error_code error;
  const asio::ip::address address =
      asio::ip::make_address(host == "localhost" ? "127.0.0.1" : host, error);
  if (error) return InvalidArgument(flag + ": '" + host + "' is not an IP address");
  const tcp::endpoint endpoint(address, static_cast<unsigned short>(port));
  state->acceptor.open(endpoint.protocol(), error);
  if (!error) state->acceptor.set_option(asio::socket_base::reuse_address(true), error);
  if (!error) state->acceptor.bind(endpoint, error);
  if (!error) state->acceptor.listen(asio::socket_base::max_listen_connections, error);
  if (error) {
    return InvalidArgument(flag + ": cannot listen on " + listen + ": " + error.message());
  }
  state->Accept();
  for (int k = 0; k < std::max(1, threads); ++k) {
    state->threads.emplace_back([context = &state->context] { context->run(); });
  }
  return std::unique_ptr<HttpListener>(new HttpListener(std::move(state)));
}

HttpListener::HttpListener(std::unique_ptr<State> state) : state_(std::move(state)) {}

HttpListener::~HttpListener() { Stop(); }

int HttpListener::port() const { return state_->acceptor.local_endpoint().port(); }

void HttpListener::Stop() {
  {
    const std::lock_guard lock(state_->gate->mutex);
    state_->gate->open = false;
  }
  if (state_->threads.empty()) return;
  state_->context.stop();
  for (std::thread& thread : state_->threads) thread.join();
  state_->threads.clear();
}

}  // namespace scallop::server
