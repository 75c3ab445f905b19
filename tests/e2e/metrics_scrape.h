// A minimal HTTP client for tests of scallopd's HTTP endpoints (/metrics,
// tiles), and a parser of Prometheus text into samples keyed by "name{labels}".
#pragma once

#include <boost/beast/http/verb.hpp>
#include <chrono>
#include <map>
#include <string>

namespace scallop::testing {

struct HttpAnswer {
  int status = 0;
  std::string content_type;
  std::string body;
  std::map<std::string, std::string> headers;  // names in lower case
};

// One request to HOST:PORT; throws on a transport error (a test failure),
// including no answer within `timeout` (a server that accepted and hung).
HttpAnswer Fetch(const std::string& host_port, boost::beast::http::verb verb,
                 const std::string& target,
                 std::chrono::milliseconds timeout = std::chrono::seconds(30));
// The same with request headers ("If-None-Match", "Authorization", ...).
HttpAnswer Fetch(const std::string& host_port, boost::beast::http::verb verb,
                 const std::string& target, const std::map<std::string, std::string>& headers,
                 std::chrono::milliseconds timeout = std::chrono::seconds(30));

// "name{labels} value" lines keyed by "name{labels}"; comments skipped.
std::map<std::string, double> ParseExposition(const std::string& text);

// GET /metrics of HOST:PORT, parsed; empty when the answer is not 200.
std::map<std::string, double> ScrapeMetrics(const std::string& host_port);

}  // namespace scallop::testing
