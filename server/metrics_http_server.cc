// The metrics endpoint: GET /metrics on an HttpListener of its own.
#include "server/metrics_http_server.h"

#include <boost/beast/http.hpp>

namespace scallop::server {
namespace {

namespace http = boost::beast::http;

HttpListener::Response AnswerScrape(const HttpListener::Request& request,
                                    const MetricsHttpServer::Render& render) {
  HttpListener::Response response;
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    response.result(http::status::method_not_allowed);
    response.set(http::field::allow, "GET, HEAD");
    response.body() = "only GET /metrics\n";
  } else if (request.target() != "/metrics") {
    response.result(http::status::not_found);
    response.body() = "scallopd serves /metrics only\n";
  } else {
    response.result(http::status::ok);
    response.set(http::field::content_type, "text/plain; version=0.0.4; charset=utf-8");
    response.body() = render();
  }
  if (response.result() != http::status::ok) {
    response.set(http::field::content_type, "text/plain; charset=utf-8");
  }
  return response;
}

}  // namespace

StatusOr<std::unique_ptr<MetricsHttpServer>> MetricsHttpServer::Start(const std::string& listen,
                                                                      Render render,
                                                                      int max_connections) {
  StatusOr<std::unique_ptr<HttpListener>> listener = HttpListener::Start(
      listen, "metrics",
      [render = std::move(render)](const HttpListener::Request& request, const std::string&,
                                   const HttpListener::Respond& respond) {
        respond(AnswerScrape(request, render));
      },
      max_connections);
  if (!listener.ok()) return listener.status();
  return std::unique_ptr<MetricsHttpServer>(new MetricsHttpServer(std::move(*listener)));
}

}  // namespace scallop::server
