// Summarizing a load run and printing it as text, JSON or a TSV row.
#include "bench/load_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

namespace scallop::load {
namespace {

// Nearest rank: the smallest value with at least q of the sample at or below it.
double Percentile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0;
  const auto rank = static_cast<size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::clamp<size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace

LoadSummary Summarize(const std::vector<StreamTally>& tallies, double seconds) {
  LoadSummary summary;
  std::vector<double> latencies;
  int64_t points = 0;
  int64_t bytes = 0;
  for (const StreamTally& tally : tallies) {
    latencies.insert(latencies.end(), tally.latencies_ms.begin(), tally.latencies_ms.end());
    points += tally.points;
    bytes += tally.bytes;
    summary.errors += tally.errors;
    if (summary.first_error.empty()) summary.first_error = tally.first_error;
  }
  std::sort(latencies.begin(), latencies.end());
  summary.requests = static_cast<int64_t>(latencies.size());
  summary.seconds = seconds;
  if (seconds > 0) {
    summary.requests_per_second = static_cast<double>(summary.requests) / seconds;
    summary.points_per_second = static_cast<double>(points) / seconds;
    summary.bytes_per_second = static_cast<double>(bytes) / seconds;
  }
  if (summary.requests > 0) {
    summary.points_per_request =
        static_cast<double>(points) / static_cast<double>(summary.requests);
  }
  summary.p50_ms = Percentile(latencies, 0.50);
  summary.p90_ms = Percentile(latencies, 0.90);
  summary.p99_ms = Percentile(latencies, 0.99);
  summary.max_ms = latencies.empty() ? 0 : latencies.back();
  return summary;
}

void PrintText(const LoadSummary& s, std::ostream& out) {
  out << fmt::format("target {}  mode {}  streams {}  tile {} d  seed {}\n", s.target, s.mode,
                     s.streams, s.tile_side, s.run_seed);
  out << fmt::format("requests {} in {:.2f} s, errors {}\n", s.requests, s.seconds, s.errors);
  out << fmt::format("  {:.1f} requests/s  {:.3g} points/s  {:.1f} MB/s  ({:.0f} points/request)\n",
                     s.requests_per_second, s.points_per_second, s.bytes_per_second / 1e6,
                     s.points_per_request);
  out << fmt::format("  latency ms: p50 {:.3f}  p90 {:.3f}  p99 {:.3f}  max {:.3f}\n", s.p50_ms,
                     s.p90_ms, s.p99_ms, s.max_ms);
  if (!s.first_error.empty()) out << "  first error: " << s.first_error << '\n';
}

void PrintJson(const LoadSummary& s, std::ostream& out) {
  const nlohmann::json json = {
      {"target", s.target},
      {"mode", s.mode},
      {"streams", s.streams},
      {"tile_side", s.tile_side},
      {"run_seed", s.run_seed},
      {"requests", s.requests},
      {"errors", s.errors},
      {"first_error", s.first_error},
      {"seconds", s.seconds},
      {"requests_per_second", s.requests_per_second},
      {"points_per_second", s.points_per_second},
      {"bytes_per_second", s.bytes_per_second},
      {"points_per_request", s.points_per_request},
      {"latency_ms", {{"p50", s.p50_ms}, {"p90", s.p90_ms}, {"p99", s.p99_ms}, {"max", s.max_ms}}},
  };
  out << json.dump(2) << '\n';
}

std::string TsvHeader() {
  return "mode\tstreams\trequests\terrors\tseconds\trequests_per_s\tpoints_per_s\tbytes_per_s\t"
         "p50_ms\tp90_ms\tp99_ms\tmax_ms";
}

void PrintTsv(const LoadSummary& s, std::ostream& out) {
  out << fmt::format(
      "{}\t{}\t{}\t{}\t{:.3f}\t{:.1f}\t{:.0f}\t{:.0f}\t{:.3f}\t{:.3f}\t{:.3f}\t{:.3f}\n", s.mode,
      s.streams, s.requests, s.errors, s.seconds, s.requests_per_second, s.points_per_second,
      s.bytes_per_second, s.p50_ms, s.p90_ms, s.p99_ms, s.max_ms);
}

}  // namespace scallop::load
