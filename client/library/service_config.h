// The gRPC service config of ScallopClient::Connect's channels to balanced
// targets (dns:///, ipv4:, ipv6:): round_robin over every address the target
// resolves to, and retries of the idempotent unary calls on UNAVAILABLE, so
// a replica that goes away (restart, crash, a proxy's 502) costs a retry,
// not an error. See docs/deploy.md, "Balancing: client-side round_robin".
#pragma once

#include <string_view>

namespace scallop::client {

// True for a target that names its resolver ("dns:///host:port",
// "ipv4:a:p,b:p", "ipv6:..."): Connect gives those the config below. A bare
// HOST:PORT keeps gRPC's defaults (pick_first, no retries), as before: a
// client asks for balancing and retries by naming the resolver, also for a
// single proxy (dns:///PROXY:PORT).
constexpr bool NamesBalancedTarget(std::string_view target) {
  return target.starts_with("dns:") || target.starts_with("ipv4:") || target.starts_with("ipv6:");
}

// The JSON given to grpc::ChannelArguments::SetServiceConfigJSON. Retried:
// GetPoints, Nearest, NoiseGrid, DescribeWorld, GetServerInfo and Verify,
// which are pure reads (the same request gives the same answer on any
// replica), up to 4 attempts with exponential backoff from 0.1 s to 1 s, and
// only on UNAVAILABLE (a call that never ran, or whose replica went away).
// Not retried: StreamPoints and Follow (a retry would repeat what was
// received; they resume instead, docs/streaming.md), the health check (a
// probe wants the truth), and every other code (RESOURCE_EXHAUSTED is load
// shedding: retrying at once would add to the load).
inline constexpr std::string_view kServiceConfigJson = R"json({
  "loadBalancingConfig": [{"round_robin": {}}],
  "methodConfig": [{
    "name": [
      {"service": "scallop.v1.Scallop", "method": "GetPoints"},
      {"service": "scallop.v1.Scallop", "method": "Nearest"},
      {"service": "scallop.v1.Scallop", "method": "NoiseGrid"},
      {"service": "scallop.v1.Scallop", "method": "DescribeWorld"},
      {"service": "scallop.v1.Scallop", "method": "GetServerInfo"},
      {"service": "scallop.v1.Scallop", "method": "Verify"}
    ],
    "retryPolicy": {
      "maxAttempts": 4,
      "initialBackoff": "0.1s",
      "maxBackoff": "1s",
      "backoffMultiplier": 2,
      "retryableStatusCodes": ["UNAVAILABLE"]
    }
  }]
})json";

}  // namespace scallop::client
