// One keep-alive HTTP/1.1 client connection for the tile benchmarks
// (http_tiles_bench, nginx_tiles_bench): a request, its whole answer, repeat,
// with TCP_NODELAY so that small requests are not held back. Not thread-safe:
// one connection per client thread.
#pragma once

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <string>

namespace scallop {

class HttpConnection {
 public:
  // Connects to HOST:PORT; throws on failure.
  explicit HttpConnection(const std::string& host_port) : host_port_(host_port) {
    const size_t colon = host_port.rfind(':');
    boost::asio::ip::tcp::resolver resolver(context_);
    boost::asio::connect(socket_,
                         resolver.resolve(host_port.substr(0, colon), host_port.substr(colon + 1)));
    socket_.set_option(boost::asio::ip::tcp::no_delay(true));
  }

  // The answer's status, its body in `body`, or throws on a transport error.
  int Get(const std::string& target, std::string& body, const std::string& if_none_match = {}) {
    namespace http = boost::beast::http;
    http::request<http::empty_body> request(http::verb::get, target, 11);
    request.set(http::field::host, host_port_);
    if (!if_none_match.empty()) request.set(http::field::if_none_match, if_none_match);
    http::write(socket_, request);
    http::response<http::string_body> response;
    http::read(socket_, buffer_, response);
    body = std::move(response.body());
    etag_ = std::string(response[http::field::etag]);
    cache_status_ = std::string(response["X-Cache-Status"]);
    return static_cast<int>(response.result_int());
  }
  // Of the last answer: its ETag, and nginx's X-Cache-Status (empty if none).
  const std::string& last_etag() const { return etag_; }
  const std::string& last_cache_status() const { return cache_status_; }

 private:
  std::string host_port_;
  boost::asio::io_context context_;
  boost::asio::ip::tcp::socket socket_{context_};
  boost::beast::flat_buffer buffer_;
  std::string etag_;
  std::string cache_status_;
};

}  // namespace scallop
