// The tests' HTTP client (Boost.Beast, blocking) and Prometheus text parser.
#include "tests/e2e/metrics_scrape.h"

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <sstream>

namespace scallop::testing {

namespace http = boost::beast::http;
using tcp = boost::asio::ip::tcp;

HttpAnswer Fetch(const std::string& host_port, http::verb verb, const std::string& target,
                 std::chrono::milliseconds timeout) {
  return Fetch(host_port, verb, target, {}, timeout);
}

HttpAnswer Fetch(const std::string& host_port, http::verb verb, const std::string& target,
                 const std::map<std::string, std::string>& headers,
                 std::chrono::milliseconds timeout) {
  const size_t colon = host_port.rfind(':');
  boost::asio::io_context context;
  tcp::resolver resolver(context);
  boost::beast::tcp_stream stream(context);
  // Each step asynchronous, so that the stream's timeout bounds them all:
  // a blocking read waits for ever on a server that accepted and hung.
  boost::beast::error_code error;
  auto step = [&](auto start) {
    start();
    context.restart();
    context.run();
    if (error) throw boost::system::system_error(error);
  };
  auto done = [&](boost::beast::error_code result, auto&&...) { error = result; };
  stream.expires_after(timeout);
  const auto endpoints = resolver.resolve(host_port.substr(0, colon), host_port.substr(colon + 1));
  step([&] { stream.async_connect(endpoints, done); });
  http::request<http::empty_body> request(verb, target, 11);
  request.set(http::field::host, host_port);
  for (const auto& [name, value] : headers) request.set(name, value);
  step([&] { http::async_write(stream, request, done); });
  boost::beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.skip(verb == http::verb::head);  // a HEAD answer has a length but no body
  step([&] { http::async_read(stream, buffer, parser, done); });
  const http::response<http::string_body>& response = parser.get();
  HttpAnswer answer{static_cast<int>(response.result_int()),
                    std::string(response[http::field::content_type]),
                    response.body(),
                    {}};
  for (const auto& field : response) {
    std::string name(field.name_string());
    for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    answer.headers[name] = std::string(field.value());
  }
  return answer;
}

std::map<std::string, double> ParseExposition(const std::string& text) {
  std::map<std::string, double> samples;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    const size_t space = line.rfind(' ');
    samples[line.substr(0, space)] = std::stod(line.substr(space + 1));
  }
  return samples;
}

std::map<std::string, double> ScrapeMetrics(const std::string& host_port) {
  const HttpAnswer answer = Fetch(host_port, http::verb::get, "/metrics");
  return answer.status == 200 ? ParseExposition(answer.body) : std::map<std::string, double>{};
}

}  // namespace scallop::testing
