#!/usr/bin/env python3
"""Joins the cold-call probe's server lines (SCALLOP_PROBE_FILE) with the load
generator's (SCALLOP_PROBE_CLIENT), call by call, and prints each stage's wall
time and CPU time: median, p90, p99, and the mean over the slowest 2% of calls.
One stream only: the k-th server line is the k-th call the client made.

    split.py SERVER_FILE CLIENT_FILE [calls to leave out first = 300]
"""
import sys


def quantile(values, q):
    ordered = sorted(values)
    return ordered[int(q * (len(ordered) - 1))]


def main():
    server_lines = [line.split() for line in open(sys.argv[1])]
    header = server_lines[0]
    rows = [dict(zip(header, map(int, line))) for line in server_lines[1:]]
    client = [tuple(map(int, line.split())) for line in open(sys.argv[2])]
    skip = int(sys.argv[3]) if len(sys.argv) > 3 else 300
    if len(client) != len(rows):
        sys.exit(f"split.py: {len(rows)} server lines against {len(client)} client lines")
    wall = {
        "client send -> handler": lambda r, s, e: r["arrive"] - s,
        "handler -> hand-off to the request pool": lambda r, s, e: r["posted"] - r["arrive"],
        "hand-off -> request thread starts": lambda r, s, e: r["pool_start"] - r["posted"],
        "request thread -> engine": lambda r, s, e: r["engine_start"] - r["pool_start"],
        "engine (WarmRegions)": lambda r, s, e: r["engine_end"] - r["engine_start"],
        "regions looked up again": lambda r, s, e: r["query_end"] - r["engine_end"],
        "answer written": lambda r, s, e: r["answer_end"] - r["query_end"],
        "log, admission released": lambda r, s, e: r["finish_start"] - r["answer_end"],
        "Finish call (gRPC's write)": lambda r, s, e: r["finish_end"] - r["finish_start"],
        "Finish -> client has the answer": lambda r, s, e: e - r["finish_start"],
        "the call, at the client": lambda r, s, e: e - s,
    }
    cpu = ["grpc_cpu", "engine_caller_cpu", "generate_cpu", "publish_cpu", "evict_cpu",
           "set_cpu", "take_cpu", "query_cpu", "answer_cpu", "log_cpu", "finish_cpu"]
    calls = list(zip(rows, client))[skip:]
    if not calls:
        sys.exit("split.py: no calls after the ones left out")
    out_of_order = sum(1 for r, (s, e) in calls if not s <= r["arrive"] <= r["finish_start"] <= e)
    latency = [e - s for r, (s, e) in calls]
    slowest = sorted(range(len(calls)), key=lambda k: latency[k])[int(0.98 * len(calls)):]
    print(f"{len(calls)} calls after the first {skip}; {out_of_order} not nested in their "
          "client call (a mismatched join)")
    print(f"{'wall, us':42s} {'median':>8s} {'p90':>8s} {'p99':>8s} {'slowest 2%':>11s}")
    for name, stage in wall.items():
        values = [stage(r, s, e) / 1e3 for r, (s, e) in calls]
        mean_slowest = sum(values[k] for k in slowest) / len(slowest)
        print(f"{name:42s} {quantile(values, .5):8.0f} {quantile(values, .9):8.0f} "
              f"{quantile(values, .99):8.0f} {mean_slowest:11.0f}")
    print(f"{'CPU, us (engine: both its threads)':42s}")
    for name in cpu:
        values = [r[name] / 1e3 for r, _ in calls]
        print(f"{name:42s} {quantile(values, .5):8.0f} {quantile(values, .9):8.0f} "
              f"{quantile(values, .99):8.0f}")
    regions = [r["regions"] for r, _ in calls]
    print(f"{'regions generated':42s} {quantile(regions, .5):8d} {quantile(regions, .9):8d} "
          f"{quantile(regions, .99):8d}")
    per_region = sorted(r["generate_cpu"] / r["regions"] / 1e3 for r, _ in calls if r["regions"])
    ratio = [(r["engine_end"] - r["engine_start"]) / (r["generate_cpu"] / 2)
             for r, _ in calls if r["generate_cpu"]]
    print(f"generation CPU a region: median {quantile(per_region, .5):.0f} us, "
          f"p99 {quantile(per_region, .99):.0f} us; engine wall / half its generation CPU: "
          f"median {quantile(ratio, .5):.2f}, in the slowest 2% "
          f"{sum(ratio[k] for k in slowest if k < len(ratio)) / len(slowest):.2f}")


if __name__ == "__main__":
    main()
