// Counters and latency histograms of the requests scallopd served, rendered
// in Prometheus's text exposition format (version 0.0.4) for /metrics.
// Debian 12 has no Prometheus client library, so the format is written here;
// it is small: counters, gauges and cumulative histograms with labels.
#pragma once

#include <grpcpp/support/status.h>

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <utility>

#include "scallop/plane/region_cache.h"

namespace scallop::server {

class RequestMetrics {
 public:
  // Upper bounds of the latency buckets, in seconds (+Inf is implicit): from
  // a warm page (sub-millisecond) to a large verify (seconds).
  static constexpr std::array<double, 14> kLatencyBuckets{
      0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10};

  // Counts one finished call of `method` (e.g. "GetPoints") with its status
  // code, wall time and the points it sent. Thread-safe; a short lock.
  void Record(const std::string& method, grpc::StatusCode code, double seconds, int64_t points);

  // Every metric, with the cache's counters and gauges beside the requests'.
  // Families and label sets come out sorted, so the text is stable.
  std::string Exposition(const RegionCacheStats& cache, int requests_in_flight) const;

 private:
  struct Latency {
    std::array<int64_t, kLatencyBuckets.size()> bucket_counts{};  // not cumulative
    int64_t count = 0;
    double sum_seconds = 0;
  };

  mutable std::mutex mutex_;
  std::map<std::pair<std::string, std::string>, int64_t> requests_;  // (method, code)
  std::map<std::string, Latency> latency_;                           // by method
  std::map<std::string, int64_t> points_;                            // by method
};

}  // namespace scallop::server
