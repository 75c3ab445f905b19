#include "server/request_metrics.h"

#include <fmt/format.h>

#include "status_code_name.h"

namespace scallop::server {
namespace {

void AppendHeader(std::string& out, const char* name, const char* type, const char* help) {
  out += fmt::format("# HELP {} {}\n# TYPE {} {}\n", name, help, name, type);
}

}  // namespace

void RequestMetrics::Record(const std::string& method, grpc::StatusCode code, double seconds,
                            int64_t points) {
  const std::lock_guard lock(mutex_);
  ++requests_[{method, StatusCodeName(code)}];
  Latency& latency = latency_[method];
  size_t bucket = 0;
  while (bucket < kLatencyBuckets.size() && seconds > kLatencyBuckets[bucket]) ++bucket;
  if (bucket < kLatencyBuckets.size()) ++latency.bucket_counts[bucket];
  ++latency.count;
  latency.sum_seconds += seconds;
  points_[method] += points;
}

std::string RequestMetrics::Exposition(const RegionCacheStats& cache,
                                       int requests_in_flight) const {
  std::string out;
  {
    const std::lock_guard lock(mutex_);
    AppendHeader(out, "scallop_requests_total", "counter", "Finished calls by method and code.");
    for (const auto& [key, count] : requests_) {
      out += fmt::format("scallop_requests_total{{method=\"{}\",code=\"{}\"}} {}\n", key.first,
                         key.second, count);
    }
    AppendHeader(out, "scallop_request_duration_seconds", "histogram",
                 "Wall time of finished calls, from arrival to status.");
    for (const auto& [method, latency] : latency_) {
      int64_t cumulative = 0;
      for (size_t b = 0; b < kLatencyBuckets.size(); ++b) {
        cumulative += latency.bucket_counts[b];
        out +=
            fmt::format("scallop_request_duration_seconds_bucket{{method=\"{}\",le=\"{}\"}} {}\n",
                        method, kLatencyBuckets[b], cumulative);
      }
      out +=
          fmt::format("scallop_request_duration_seconds_bucket{{method=\"{}\",le=\"+Inf\"}} {}\n",
                      method, latency.count);
      out += fmt::format("scallop_request_duration_seconds_sum{{method=\"{}\"}} {}\n", method,
                         latency.sum_seconds);
      out += fmt::format("scallop_request_duration_seconds_count{{method=\"{}\"}} {}\n", method,
                         latency.count);
    }
    AppendHeader(out, "scallop_points_served_total", "counter", "Points sent, by method.");
    for (const auto& [method, count] : points_) {
      out += fmt::format("scallop_points_served_total{{method=\"{}\"}} {}\n", method, count);
    }
  }
  AppendHeader(out, "scallop_requests_in_flight", "gauge",
               "Calls admitted and not yet finished (max_in_flight sheds beyond).");
  out += fmt::format("scallop_requests_in_flight {}\n", requests_in_flight);
  AppendHeader(out, "scallop_cache_hits_total", "counter",
               "Region lookups answered by a stored or in-flight region.");
  out += fmt::format("scallop_cache_hits_total {}\n", cache.hits);
  AppendHeader(out, "scallop_cache_misses_total", "counter", "Region lookups that generated.");
  out += fmt::format("scallop_cache_misses_total {}\n", cache.misses);
  AppendHeader(out, "scallop_regions_generated_total", "counter",
               "Regions generated (one per miss: a region is generated once at a time).");
  out += fmt::format("scallop_regions_generated_total {}\n", cache.misses);
  AppendHeader(out, "scallop_cache_evictions_total", "counter",
               "Regions evicted to stay in budget.");
  out += fmt::format("scallop_cache_evictions_total {}\n", cache.evictions);
  AppendHeader(out, "scallop_cache_regions", "gauge", "Regions stored in the cache now.");
  out += fmt::format("scallop_cache_regions {}\n", cache.regions);
  AppendHeader(out, "scallop_cache_bytes", "gauge", "Bytes of the regions stored now.");
  out += fmt::format("scallop_cache_bytes {}\n", cache.bytes);
  AppendHeader(out, "scallop_cache_budget_bytes", "gauge", "The cache's byte budget.");
  out += fmt::format("scallop_cache_budget_bytes {}\n", cache.byte_budget);
  return out;
}

}  // namespace scallop::server
