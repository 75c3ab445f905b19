// What a load run measured, and its summary: throughput and latency
// percentiles, printed as text for people, JSON for tools, or one
// tab-separated row for bench/run-load-benchmark.sh.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace scallop::load {

// One stream's tally; streams fill their own and are merged at the end, so
// the request path takes no lock.
struct StreamTally {
  std::vector<double> latencies_ms;  // successful calls only
  int64_t points = 0;
  int64_t bytes = 0;  // serialized response bytes (the message, not HTTP/2 framing)
  int64_t errors = 0;
  std::string first_error;
};

struct LoadSummary {
  // What was run, echoed so that a row or a JSON file is self-describing.
  std::string target;
  std::string mode;  // "cold" or "warm"
  int streams = 0;
  double tile_side = 0;
  uint64_t run_seed = 0;  // repeats the run's tiles and cold world (--seed)

  int64_t requests = 0;  // successful calls
  int64_t errors = 0;
  std::string first_error;
  double seconds = 0;  // wall time from the first call to the last reply
  double requests_per_second = 0;
  double points_per_second = 0;
  double bytes_per_second = 0;
  double points_per_request = 0;
  // Nearest-rank percentiles of successful calls, in milliseconds.
  double p50_ms = 0;
  double p90_ms = 0;
  double p99_ms = 0;
  double max_ms = 0;
};

// Merges the streams' tallies over `seconds` of wall time. Sorts a copy of
// every latency: O(n log n) in the requests, done once after the run.
LoadSummary Summarize(const std::vector<StreamTally>& tallies, double seconds);

void PrintText(const LoadSummary& summary, std::ostream& out);
void PrintJson(const LoadSummary& summary, std::ostream& out);
// The columns of TsvHeader, tab-separated, one line.
void PrintTsv(const LoadSummary& summary, std::ostream& out);
std::string TsvHeader();

}  // namespace scallop::load
