#!/usr/bin/env python3
"""Renders docs/performance.md from one run of scripts/make-performance-page.sh.

    render_page.py RESULTS_DIR > docs/performance.md
    render_page.py RESULTS_DIR --apart TITLE PAGE [REASON] > new page

The second form renders section TITLE alone from RESULTS_DIR (a run of that section's
benchmarks only) into PAGE, in place of the section there, with a line saying it was
measured apart from the page's run, when, on what and why (ONLY= in make-performance-page.sh).

Exits 1, naming them on stderr, when some sections had no input (the page is written anyway).

RESULTS_DIR holds what the run wrote: the Google Benchmark JSON files
(<bench>.json), the text outputs of cold_tile_latency, the verifier test and
the load benchmark, and run.json (machine, commit, commands, load averages).
Every figure on the page comes from those files; an input that is missing
renders as "not measured in this run", never as an old figure.
"""
import json
import pathlib
import re
import sys

RESULTS = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")


def load_json(name):
    path = RESULTS / name
    return json.loads(path.read_text()) if path.exists() else None


def read_text(name):
    path = RESULTS / name
    return path.read_text() if path.exists() else None


def medians(bench_json):
    """name -> the median aggregate's row (or the single run's row)."""
    rows = {}
    if not bench_json:
        return rows
    for row in bench_json["benchmarks"]:
        name = row["run_name"]
        if row.get("run_type") == "aggregate":
            if row.get("aggregate_name") == "median":
                rows[name] = row
        else:
            rows.setdefault(name, row)
    return rows


def si(value, unit=""):
    """4,010,000 -> '4.01M'."""
    for factor, suffix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if abs(value) >= factor:
            return f"{value / factor:.3g}{suffix}{unit}"
    return f"{value:.3g}{unit}"


def ratio(value, baseline):
    return f"{value / baseline:.2f}x" if baseline else "-"


MISSING = "_Not measured in this run._\n"


def command_block(run, key):
    command = run.get("commands", {}).get(key)
    return f"    {command}\n" if command else ""


def bounded_samplers(run):
    rows = medians(load_json("samplers_bench.json"))
    if not rows:
        return MISSING
    sizes = (1000, 10000, 100000, 1000000)
    methods = (("bridson_baseline", "Bridson, k = 30 (baseline)"),
               ("a3", "**A3**, boundary sampling"),
               ("a2", "**A2**, O(N) dart throwing"),
               ("a1", "**A1**, exact dart throwing with cells"),
               ("a1_paper", "the paper's A1 (within r' = 2 d), with cells"),
               ("dart", "dart throwing, 1000 misses (not maximal)"),
               ("best_candidate", "Mitchell's best candidate (k = 1)"))

    def row_for(method, n):
        return rows.get(f"BM_Sampler/{method}/{n}/min_time:0.500")

    out = [command_block(run, "samplers_bench"), "\n",
           "Points per second on a square expected to hold N points at d = 1, with the ratio\n"
           "to our Bridson at the same N in the same run; heap bytes per point at the largest N\n"
           "measured.\n\n",
           "| method | N ≈ 1k | N ≈ 10k | N ≈ 100k | N ≈ 1M | peak heap bytes / point |\n",
           "|---|---|---|---|---|---|\n"]
    for method, label in methods:
        cells, last = [], None
        for n in sizes:
            row, base = row_for(method, n), row_for("bridson_baseline", n)
            if row is None:
                cells.append("–")
                continue
            last = row
            pps = row["points_per_second"]
            cells.append(si(pps) if method == "bridson_baseline" or base is None else
                         f"{si(pps)} ({ratio(pps, base['points_per_second'])})")
        bytes_cell = f"{last['peak_bytes_per_point']:.0f}" if last else "–"
        out.append(f"| {label} | {' | '.join(cells)} | {bytes_cell} |\n")
    exact = [(n, row_for("a1", n), row_for("a1_paper", n)) for n in sizes]
    exact = [f"{ratio(a['points_per_second'], p['points_per_second'])} at N ≈ {si(n)}"
             for n, a, p in exact if a and p]
    if exact:
        out.append("\nExact A1 against the paper's A1 (its speed before it became exact; target: at\n"
                   f"least 1x): {', '.join(exact)}.\n")
    return "".join(out)


def radius_fields(run):
    rows = medians(load_json("field_bench.json"))
    size = "1M/1000000" if "uniform_a3_1M/1000000" in rows else "smoke/10000"
    uniform, field, bridson = (rows.get(f"{name}_{size}")
                               for name in ("uniform_a3", "field_noise8", "field_bridson"))
    if not (uniform and field and bridson):
        return MISSING
    u, f, b = (r["points_per_second"] for r in (uniform, field, bridson))
    return "".join([
        command_block(run, "field_bench"), "\n",
        f"About {'1M' if size.startswith('1M') else '10k'} points on a square; the field is noise"
        " with r_max / r_min = 8\n"
        "(`bench/field_bench.cc`). Targets (issue 24): at least 0.5x uniform A3, at least\n"
        "5x the field Bridson.\n\n",
        "| sampler | points/s | against uniform A3 | against field Bridson |\n",
        "|---|---|---|---|\n",
        f"| uniform A3 (baseline) | {si(u)} | 1 | {ratio(u, b)} |\n",
        f"| **SampleField**, noise field | {si(f)} | **{ratio(f, u)}** | **{ratio(f, b)}** |\n",
        f"| field Bridson, k = 30 (not maximal) | {si(b)} | {ratio(b, u)} | 1 |\n",
        field_work(field), field_before(run, size)])


def field_before(run, size):
    """When the results hold field_bench_before.json (the same benchmark built from the code
    before a round of speed work, run right after): its ratios, so that a round's gain reads
    against the load of the same hour. Absent from a regular run."""
    rows = medians(load_json("field_bench_before.json"))
    bounded = [rows.get(f"{name}_{size}") for name in ("uniform_a3", "field_noise8", "field_bridson")]
    plane = [rows.get(f"plane_cold_{name}_250k/250000") for name in ("uniform_a3", "field_noise8")]
    if not all(bounded) or not all(plane):
        return ""
    u, f, b = (r["points_per_second"] for r in bounded)
    pu, pf = (r["points_per_second"] for r in plane)
    return (f"\nThe code before the last round of speed work (commit {run.get('before_commit', '?')}),"
            " the same benchmark run right after\n"
            f"this one: SampleField {si(f)} points/s, {ratio(f, u)} uniform A3 and {ratio(f, b)}"
            " the field Bridson;\n"
            f"on the plane, cold, {ratio(pf, pu)} the uniform world.\n")


def field_work(row):
    """The field sampler's work a point, from its benchmark counters (absent: nothing)."""
    names = ("spots_per_point", "evaluations_per_point", "cells_per_point", "swept_share")
    if not all(name in row for name in names):
        return ""
    spots, evaluations, cells, swept = (row[name] for name in names)
    return ("\nWhere SampleField's time goes, a point: "
            f"{spots:.2f} tries on candidates' curves, {evaluations:.1f} evaluations of R,\n"
            f"{cells:.1f} sweep cells; {100 * swept:.2f}% of the points seeded by the sweep"
            " (docs/design.md,\n\"The sampler\").\n")


def radius_fields_on_the_plane(run):
    rows = medians(load_json("field_bench.json"))
    size = "250k/250000" if "plane_cold_uniform_a3_250k/250000" in rows else "smoke/10000"
    uniform, field = (rows.get(f"plane_cold_{name}_{size}") for name in ("uniform_a3", "field_noise8"))
    if not (uniform and field):
        return MISSING
    u, f = (r["points_per_second"] for r in (uniform, field))
    return "".join([
        command_block(run, "field_bench"), "\n",
        f"A cold query (a fresh one-thread engine, so every region it needs is generated) of a\n"
        f"square holding about {'250k' if size.startswith('250k') else '10k'} points: the noise"
        " field world (r_max / r_min = 8, regions of\n"
        "6 r_max) against the uniform A3 world at d = 1 on a square of the same point count.\n"
        "Target (issue 24): at least 0.5x.\n\n",
        "| world | points/s | against uniform |\n", "|---|---|---|\n",
        f"| uniform A3 (baseline) | {si(u)} | 1 |\n",
        f"| **noise field** | {si(f)} | **{ratio(f, u)}** |\n"])


def layered_worlds(run):
    rows = medians(load_json("layers_bench.json"))
    size = "250k/250000" if "layers_cold_250k/250000" in rows else "smoke/5000"
    names = ("uniform_cold", "layers_cold", "studio_passes", "studio_plane_passes",
             "layers_bounded")
    uniform, layered, studio, studio_plane, bounded = (
        rows.get(f"{name}_{size}") for name in names)
    if not (uniform and layered and studio):
        return MISSING

    def empty(row, layer):
        value = row.get(f"empty_{layer}_in_d")
        return f"{value:+.3f} d" if value is not None else ""

    def line(label, row):
        if not row:
            return ""
        cells = [label, f"{row['points'] / 1e3:.1f}k", si(row["points_per_second"]),
                 ratio(row["points_per_second"], uniform["points_per_second"])]
        cells += [empty(row, layer) for layer in ("trees", "bushes", "rocks")]
        return "| " + " | ".join(cells) + " |\n"

    def against(row, rival):
        return ratio(row["points_per_second"], rival["points_per_second"])

    # Three decimals here: at two, a ratio just under the target reads as the target itself.
    share = layered["points_per_second"] / uniform["points_per_second"]
    verdict = [
        "Against the one-layer world the three layers on the plane are ", f"{share:.3f}x",
        " (target 0.5x: ",
        "met" if layered["points_per_second"] >= 0.5 * uniform["points_per_second"] else "missed",
        ")"]
    if studio_plane:
        verdict += [";\nagainst the studios' passes on the plane, ", against(layered, studio_plane)]
    if bounded:
        verdict += [";\nsampled on the square alone, against the studios' bounded passes, ",
                    against(bounded, studio)]
    verdict += [" (target: at least 1x each),\nin points per second (the passes keep fewer points:"
                " they are not maximal). The plane's layers\nagainst the bounded passes: ",
                against(layered, studio),
                ". Constant later layers grow by A3 with the earlier layers' points as exclusion\n"
                "disks (docs/design.md, \"Layered worlds\").\n"]
    return "".join([
        command_block(run, "layers_bench"), "\n",
        "Trees (d 8), bushes (3) and rocks (1.5), the default matrix (`bench/layers_bench.cc`),\n"
        "on a square holding about "
        f"{'250k' if size.startswith('250k') else '5k'} points: a cold query of the layered world\n"
        "(a fresh one-thread engine) against the one-layer uniform A3 world of d = 1.5 on the same\n"
        "square; the studios' way: three uniform passes, each pass's points dropped within D of a\n"
        "point an earlier pass kept, taken from three uniform worlds of the plane (cold queries),\n"
        "as a studio using this service would; and the same layers sampled on the square alone\n"
        "(`SampleLayers`, `scallop generate --layer`) against the passes of bounded A3 on it.\n"
        "\"Empty\" is each layer's largest slack min(|x - q| - d, |x - c| - D) over the central\n"
        "150 x 150, probed every d / 20: positive means a point of that layer still fits (the layer\n"
        "is not maximal). Targets (issue 19): at least 0.5x the one-layer world, at least the\n"
        "studios' speed, maximal where they are not. Each row's repetitions run interleaved at\n"
        "random with the other rows' (medians shown), so that a change of load between rows moves\n"
        "them alike: the layered rows are the most memory-bound of the page and move the most.\n\n",
        "| world | points | points/s | against uniform | empty trees | empty bushes |"
        " empty rocks |\n",
        "|---|---|---|---|---|---|---|\n",
        line("uniform A3 world, d = 1.5 (baseline)", uniform),
        line("**three layers**, plane", layered),
        line("studios' passes on the plane", studio_plane),
        line("**three layers**, bounded (`SampleLayers`)", bounded),
        line("studios' bounded passes", studio), "\n",
        *verdict])


def infinite_plane(run):
    rows = medians(load_json("plane_bench.json"))
    bounded = rows.get("BM_BoundedA3/real_time")
    if not bounded:
        return MISSING
    base = bounded["points_per_second"]
    out = [command_block(run, "plane_bench"), "\n",
           "A 1000 d square of an A3 world (about 855k points), generated cold by the plane\n"
           "engine, against bounded A3 on the same square in the same run. Target (issue 23):\n"
           "cold, 1 thread, at least 0.85x bounded A3.\n\n",
           "| measure | points/s | ratio | cache bytes / point |\n", "|---|---|---|---|\n",
           f"| bounded A3, same square (baseline) | {si(base)} | 1 | |\n"]
    for name, label in (("BM_PlaneCold/1/real_time", "plane, cold, 1 thread"),
                        ("BM_PlaneCold/2/real_time", "plane, cold, 2 threads"),
                        ("BM_PlaneWarm/real_time", "plane, warm, copied out")):
        row = rows.get(name)
        if row:
            cache = row.get("cache_bytes_per_point")
            out.append(f"| {label} | {si(row['points_per_second'])} | "
                       f"**{ratio(row['points_per_second'], base)}** | "
                       f"{f'{cache:.1f}' if cache else ''} |\n")
    return "".join(out)


def a1_worlds(run):
    rows = medians(load_json("plane_bench.json"))
    exact = rows.get("BM_PlaneColdA1/200/real_time")
    paper = rows.get("BM_PlaneColdA1/199/real_time")
    if not exact or not paper:
        return MISSING
    base = paper["points_per_second"]
    return "".join([
        command_block(run, "plane_bench"), "\n",
        "A 192 d square of an A1 world (about 26k points), generated cold by a fresh one-thread\n"
        "engine. Density 2 is dart throwing in every region (generator version 4, docs/design.md,\n"
        "\"A1 world regions\"); density 1.99 runs the paper's A1 in its regions, as density 2 did\n"
        "until version 4: the baseline. Target (issue 22): at least as fast as the baseline.\n\n",
        "| world | points/s | ratio |\n", "|---|---|---|\n",
        f"| the paper's A1 regions, density 1.99 (baseline) | {si(base)} | 1 |\n",
        f"| **dart throwing regions**, density 2 | {si(exact['points_per_second'])} | "
        f"**{ratio(exact['points_per_second'], base)}** |\n"])


def text_section(run, key, description, keep=lambda line: bool(line.strip())):
    """A section that quotes the lines `keep` selects from KEY.txt, indented."""
    text = read_text(f"{key}.txt")
    lines = [line.strip() for line in (text or "").splitlines() if keep(line)]
    if not lines:
        return MISSING
    return "".join([command_block(run, key), "\n", description, "\n"] +
                   [f"    {line}\n" for line in lines])


def cold_tile_pairs():
    """cold_tile_pairs.txt ("before|after THREADS | <cold_tile_latency's line>", rounds taking
    turns going first) -> {(which, threads): [(median, p99), ...]} in round order."""
    runs = {}
    for line in (read_text("cold_tile_pairs.txt") or "").splitlines():
        match = re.match(r"(before|after) (\d+) \|.*median ([\d.]+) ms.*p99 ([\d.]+) ms", line)
        if match:
            runs.setdefault((match[1], int(match[2])), []).append((float(match[3]),
                                                                    float(match[4])))
    return runs


def cold_tiles(run):
    section = text_section(
        run, "cold_tile_latency",
        "The engine alone on cold 64 d tiles at random places (a fresh engine and world a\n"
        "tile): thread CPU time on one engine thread, and wall time on two, as scallopd's\n"
        "`--threads 2` (its share of a cold call's latency; target, issue 23: the tile through\n"
        "scallopd within 5 ms at p99):\n")
    runs = cold_tile_pairs()
    if section == MISSING or not runs:
        return section
    out = [section, "\n", command_block(run, "cold_tile_pairs"), "\n",
           "The same against an earlier build (`before`), round by round, taking turns going\n"
           "first; the ratio is the median of the rounds' ratios:\n\n",
           "| engine threads | measure | before, ms | after, ms | after / before |\n",
           "|---|---|---|---|---|\n"]
    for threads in sorted({t for _, t in runs}):
        before, after = runs.get(("before", threads), []), runs.get(("after", threads), [])
        for index, measure in ((0, "median"), (1, "p99")):
            ratios = sorted(a[index] / b[index] for b, a in zip(before, after))
            if not ratios:
                continue
            middle = ratios[len(ratios) // 2] if len(ratios) % 2 else (
                ratios[len(ratios) // 2 - 1] + ratios[len(ratios) // 2]) / 2
            out.append(f"| {threads} | {measure} | {', '.join(f'{b[index]:.2f}' for b in before)} | "
                       f"{', '.join(f'{a[index]:.2f}' for a in after)} | **{middle:.2f}x** |\n")
    return "".join(out)


def nearest(run):
    rows = medians(load_json("nearest_bench.json"))
    if not rows:
        return MISSING
    out = [command_block(run, "nearest_bench"), "\n",
           "65,536 positions a call in a warm 256 d square of an A3 world, against a\n"
           "jittered-grid cellular noise (the usual shader baseline) on the same positions.\n"
           "Target (issue 23): at least 1.6x the baseline and 30M lookups/s. The build is\n"
           "generic x86-64 (no `-march`); the first pass takes AVX2 where the CPU has it,\n"
           "chosen at run time, and no AVX-512 anywhere. The SSE2 row is the code a CPU\n"
           "without AVX2 runs, measured on this one (docs/noise.md, \"Speed\").\n\n",
           "| order | jittered grid (baseline) | `NearestLookup::Nearest` | ratio |\n",
           "|---|---|---|---|\n"]
    cases = ((0, "random positions", "BM_NearestWarm/image_order:0"),
             (1, "image order", "BM_NearestWarm/image_order:1"),
             (0, "random positions, SSE2 (no AVX2)", "BM_NearestWarmTwoLanes"))
    for order, label, name in cases:
        base = rows.get(f"BM_JitteredGridBaseline/image_order:{order}")
        ours = rows.get(name)
        if base and ours:
            b, o = base["lookups_per_second"], ours["lookups_per_second"]
            out.append(f"| {label} | {si(b, '/s')} | **{si(o, '/s')}** | **{ratio(o, b)}** |\n")
    # A run of the same benchmark built with -march=x86-64-v3 (AVX2, no AVX-512), when the
    # results hold one (scripts/make-performance-page.sh does not build it).
    v3 = medians(load_json("nearest_bench_x86_64_v3.json"))
    base, ours = v3.get("BM_JitteredGridBaseline/image_order:0"), v3.get("BM_NearestWarm/image_order:0")
    if base and ours:
        b, o = base["lookups_per_second"], ours["lookups_per_second"]
        out.append(f"| random positions, built for x86-64-v3 (its own run) | {si(b, '/s')} | "
                   f"**{si(o, '/s')}** | **{ratio(o, b)}** |\n")
    warm = rows.get("BM_NearestWarm/image_order:0")
    if warm and "grid_bytes_per_region" in warm:
                out.append(f"\nThe search grids take {warm['grid_bytes_per_region'] / 1000:.1f} KB a region.\n")
    grid = rows.get("BM_NoiseGridWarm")
    if grid and "lookups_per_second" in grid:
        out.append(f"\nA 256 x 256 noise image (`NoiseGrid`): {si(grid['lookups_per_second'], '/s')}"
                   " lookups.\n")
    return "".join(out)


def field_lookups(run):
    rows = medians(load_json("nearest_bench.json"))
    base = rows.get("BM_NearestWarm/image_order:0")
    fields = [(ratio_arg, rows.get(f"BM_NearestWarmField/ratio:{ratio_arg}")) for ratio_arg in (4, 16)]
    if not base or not all(row for _, row in fields):
        return MISSING
    b = base["lookups_per_second"]
    out = [command_block(run, "nearest_bench"), "\n",
           "The same 65,536 random positions (in units of r_min) on noise-field worlds over\n"
           "[1, 4] and [1, 16] at 90% of the slope bound, against the constant world (d = 1)\n"
           "in the same run (docs/noise.md). No target was set.\n\n",
           "| world | lookups/s | against the constant world |\n", "|---|---|---|\n",
           f"| constant, d = 1 (baseline) | {si(b, '/s')} | 1 |\n"]
    for ratio_arg, row in fields:
        f = row["lookups_per_second"]
        out.append(f"| noise, r_max / r_min = {ratio_arg} | {si(f, '/s')} | **{ratio(f, b)}** |\n")
    return "".join(out)


def deterministic_math(run):
    rows = medians(load_json("deterministic_math_bench.json"))
    if not rows:
        return MISSING
    out = [command_block(run, "deterministic_math_bench"), "\n",
           "Our bit-reproducible functions (`base/deterministic_math.h`) against glibc's,\n"
           "nanoseconds a call (lower is better).\n\n",
           "| function | measure | ours | glibc | ours / glibc |\n", "|---|---|---|---|---|\n"]
    for name, row in rows.items():
        match = re.fullmatch(r"BM_(\w+?)_(Throughput|Latency)_Ours", name)
        if not match:
            continue
        theirs = rows.get(name.replace("_Ours", "_Glibc"))
        if theirs:
            o, g = (1e9 / r["items_per_second"] for r in (row, theirs))
            out.append(f"| {match.group(1)} | {match.group(2).lower()} | {o:.2f} | {g:.2f} | "
                       f"{o / g:.2f} |\n")
    return "".join(out)


def verifier(run):
    return text_section(run, "verifier", "About a million spaced points through the CGAL verifier:\n",
                        keep=lambda line: " points in " in line)


def follow(run):
    rows = medians(load_json("follow_bench.json"))
    row = next(iter(rows.values()), None)
    if not row:
        return MISSING
    out = [command_block(run, "follow_bench"), "\n",
           "A player walks 10,000 d at 2,000 d/s with a 64 d view (an update every 2 ms)\n"
           "against a real scallopd on loopback: Follow with prefetch, without, and the\n"
           "baseline, the whole view by GetPoints every step.\n\n",
           "| walk | bytes / step | p50 ms | p90 ms | p99 ms |\n", "|---|---|---|---|---|\n"]
    for prefix, label in (("prefetch", "Follow, prefetch"), ("no_prefetch", "Follow, no prefetch"),
                          ("naive", "GetPoints each step (baseline)")):
        if f"{prefix}_p99_ms" in row:
            out.append(f"| {label} | {row[prefix + '_bytes_per_step']:.0f} | "
                       f"{row[prefix + '_p50_ms']:.2f} | {row[prefix + '_p90_ms']:.2f} | "
                       f"{row[prefix + '_p99_ms']:.2f} |\n")
    out.append(f"\nGetPoints sends {row['naive_over_follow_bytes']:.1f}x the bytes of Follow; "
               f"its p99 is {row['naive_over_prefetch_p99']:.2f}x Follow's with prefetch.\n")
    return "".join(out)


def service_load(run):
    return text_section(
        run, "load",
        "scallopd (`--threads 2 --cache-megabytes 64`) and `null_server` (real responses\n"
        "serialized once: the transport's limit) side by side on loopback, driven by\n"
        "`load_generator` with 64 d tiles of A3 worlds: warm (inside a 256 d square\n"
        "queried once before) and cold (a fresh world, tiles 1024 d apart). Targets\n"
        "(issue 23): warm at least 0.85x the null server in every round, and cold p99 for\n"
        "one stream at most 5 ms, beside the engine alone on as many threads on the same\n"
        "work (`cold_tile_latency` with a full cache of the same budget and the load\n"
        "generator's tiles, wall time) in the same run.\n\n"
        "A warm round is one `load_generator` run that drives the null server and scallopd\n"
        "in turns of 1 s (`SLICE`), null, scallopd, scallopd, null, ..., 10 s each in all\n"
        "(who goes first turns by one server a round), from the same client process,\n"
        "connections and tiles; each turn's first call a\n"
        "stream is not counted (a gRPC server idle for a second naps 100 ms between polls).\n"
        "So the ratio of a round is one run's: a change of the machine's load slower than a\n"
        "second reaches both servers alike, and one that drifts steadily through the round\n"
        "cancels in the A B B A order, where runs of 10 s each, seconds apart, let the other\n"
        "work on these two cores decide the worst round (the null server's own rate moved by\n"
        "up to 80% from one such run to the next). Three rounds for one stream and three for\n"
        "four are the run of six the target counts. With `BEFORE=` an earlier build's\n"
        "scallopd (`before`) takes its turns in the same rounds. `cpu_us/req` is the\n"
        "server's CPU time a call, the figure a loaded machine disturbs least.\n",
        keep=lambda line: bool(line.strip()) and not line.startswith("#"))


def warm_answer(run):
    rows = medians(load_json("warm_answer_bench.json"))
    control, ours = rows.get("BM_WarmAnswerControl"), rows.get("BM_WarmAnswer")
    if not (control and ours):
        return MISSING
    c, o = control["points_per_second"], ours["points_per_second"]
    return "".join([
        command_block(run, "warm_answer_bench"), "\n",
        "What a warm GetPoints costs scallopd before gRPC sends it: 256 random 64 d tiles\n"
        "of a warm 256 d square (the load benchmark's warm mode), each tile's cached regions\n"
        "copied into a packed `Points` message by `VisitPoints` (as `AnswerGetPoints` does for\n"
        "the answers it does not write as bytes: radii, layers, encodings), a filter without\n"
        "a branch of the regions the tile cuts, against the control in the same\n"
        "run: the same copy with a branch a point, as `VisitPoints` filtered before. CPU time,\n"
        "points a second of the answers.\n\n",
        "| copy | points/s | ns / point | against the control |\n", "|---|---|---|---|\n",
        f"| a branch a point (control) | {si(c)} | {1e9 / c:.2f} | 1 |\n",
        f"| **`VisitPoints`** | {si(o)} | {1e9 / o:.2f} | **{ratio(o, c)}** |\n",
        warm_answer_bytes(rows)])


def warm_answer_bytes(rows):
    message = rows.get("BM_WarmAnswerBytesThroughMessage")
    packed = rows.get("BM_WarmAnswerBytesPacked")
    if not (message and packed):
        return ""
    m, p = message["points_per_second"], packed["points_per_second"]
    two_pass = rows.get("BM_WarmAnswerBytesPackedTwoPass")
    two_pass_row = ""
    if two_pass:
        t = two_pass["points_per_second"]
        two_pass_row = (f"| `PackedAnswerWriter`, cut regions in two passes (before) | {si(t)} | "
                        f"{1e9 / t:.2f} | {ratio(t, m)} |\n")
    return "".join([
        "\nThe whole answer's bytes, as gRPC sends them, the same tiles in the same run: the copy\n"
        "above into a `GetPointsResponse` serialized by protobuf (scallopd's way before issue\n"
        "23's warm path) against `PackedAnswerWriter`, which writes the same bytes straight into\n"
        "gRPC's slices, whole regions as runs and the regions the tile cuts in one pass each\n"
        "(`AppendInside`; the row before it sends those through `VisitPoints`' two passes, the\n"
        "indices kept and then an `Append` each), docs/design.md, \"The warm path\".\n\n",
        "| the answer's bytes | points/s | ns / point | against the message |\n", "|---|---|---|---|\n",
        f"| through the message (before) | {si(m)} | {1e9 / m:.2f} | 1 |\n",
        two_pass_row,
        f"| **`PackedAnswerWriter`** | {si(p)} | {1e9 / p:.2f} | **{ratio(p, m)}** |\n"])


def http_tiles(run):
    return text_section(
        run, "http_tiles",
        "A real scallopd (`--http-listen`, `--threads 2`): a warm square of 16 x 16 level-1\n"
        "tiles (32 d, about 880 A3 points) asked by GetPoints of each tile's rectangle (the\n"
        "baseline) and over HTTP as binary, JSON and PNG tiles and as a revalidation\n"
        "(`If-None-Match`, answered 304), one keep-alive connection or channel; the ways take\n"
        "turns, each way's median pass shown (docs/tiles.md):\n",
        keep=lambda line: bool(line.strip()) and not line.startswith("#"))


def nginx_tiles(run):
    return text_section(
        run, "nginx_tiles",
        "nginx with deploy/nginx/scallop.conf's tile cache in front of one scallopd\n"
        "(`--http-listen`, `--threads 2`): a square of tiles asked cold through nginx (a MISS\n"
        "that scallopd generates) and again (a HIT no replica sees); then the warm tiles from\n"
        "nginx's cache against scallopd directly, one keep-alive connection each, the two\n"
        "ways taking turns (docs/tiles.md):\n",
        keep=lambda line: bool(line.strip()) and not line.startswith("#"))

def soak(run):
    """The soak's calls by kind and its resource figures (scripts/soak.sh's own lines)."""
    text = read_text("soak.txt")
    samples = read_text("soak-samples.tsv")
    if not text or "soak: passed" not in text or not samples:
        return MISSING
    rows = [line.split("\t") for line in samples.splitlines()[1:] if line.strip()]
    rss = [float(row[1]) for row in rows]
    out = [command_block(run, "soak"), "\n",
           "A real scallopd (`--threads 2 --cache-megabytes 64`) under `bench/soak_load`'s bounded\n"
           "mixed load (6 workers: warm, cold and paged GetPoints, StreamPoints read whole or\n"
           "cancelled, Follow walked or abandoned, Nearest, NoiseGrid, 1 ms deadlines, bad inputs),\n"
           "its resident memory, open files and threads sampled every 5 s. It passes when every call\n"
           "ends with a code its kind may end with (shedding allowed), memory stays within the\n"
           "cache budget plus 192 MB, open files and threads do not grow in the second half, and\n"
           "scallopd exits cleanly on SIGTERM (docs/quality.md, \"Soak\", says why each bound).\n\n"]
    quoted = [re.sub(r", samples in .*\)", ")", line.strip()) for line in text.splitlines()
              if line.startswith("soak_load") or line.startswith("soak:")]
    out += [f"    {line}\n" for line in quoted]
    quarter = max(1, len(rss) // 4)
    out.append(f"\nResident memory: {rss[0]:.1f} MB at the first sample, "
               f"{max(rss[:quarter]):.1f} MB peak in the first quarter, "
               f"{max(rss[-quarter:]):.1f} MB peak in the last, {rss[-1]:.1f} MB idle after the load.\n")
    return "".join(out)


def wire_encodings(run):
    rows = medians(load_json("wire_bench.json"))
    if not rows:
        return MISSING
    names = ("packed", "exact", "quantised")
    places = ("origin", "1e6 d", "1e9 d")
    out = [command_block(run, "wire_bench"), "\n",
           "The points of a 64 d and a 240 d square of an A3 world (seed 7, d = 1) at the\n"
           "origin, 1e6 d and 1e9 d, in each encoding of docs/wire.md against the packed\n"
           "arrays in the same run: bytes a point of the serialized `Points`, points a second\n"
           "decoded by the client library (`ReadPoints`) and encoded by scallopd. Target\n"
           "(issue 23): at most 8 bytes a point quantised.\n\n",
           "| square | where | bytes a point: packed / exact / quantised | decoded: packed / exact / quantised | encoded: packed / exact / quantised |\n",
           "|---|---|---|---|---|\n"]
    found = False
    for side in (64, 240):
        for place, where in enumerate(places):
            cells = {}
            for kind in ("Encode", "Decode"):
                cells[kind] = [rows.get(f"BM_{kind}/encoding:{e}/place:{place}/side:{side}")
                               for e in range(3)]
            if not all(cells["Encode"]) or not all(cells["Decode"]):
                continue
            found = True
            sizes = " / ".join(f"{r['bytes_per_point']:.2f}" for r in cells["Encode"])

            def rates(kind):
                packed = cells[kind][0]["points_per_second"]
                return " / ".join([si(packed)] + [
                    f"{si(r['points_per_second'])} ({ratio(r['points_per_second'], packed)})"
                    for r in cells[kind][1:]])

            out.append(f"| {side} d | {where} | {sizes} | {rates('Decode')} | {rates('Encode')} |\n")
    return "".join(out) if found else MISSING


def apart_note(run, reason):
    """The line that says a section comes from a run of its own, not the page's."""
    why = f"; {reason}" if reason else ""
    return (f"_Measured apart from the run above (commit {run.get('commit', '?')}, "
            f"{run.get('date', '?')}, on {run.get('cpu', '?')}, load average "
            f"{run.get('load_before', '?')} before and {run.get('load_after', '?')} after){why}; "
            "it joins the page's run at its next regeneration._\n\n")


def splice_apart(sections, run, title, page_path, reason):
    """PAGE with section TITLE rendered from RESULTS alone, marked as measured apart."""
    render = dict(sections).get(title)
    page = pathlib.Path(page_path).read_text()
    heading = f"\n## {title}\n\n"
    if render is None or heading not in page:
        sys.stderr.write(f"render_page: no section '{title}' to render or to replace\n")
        sys.exit(2)
    text = render(run)
    if text == MISSING:
        sys.stderr.write(f"render_page: '{title}' not measured in {RESULTS}\n")
        sys.exit(1)
    start = page.index(heading) + len(heading)
    end = page.find("\n## ", start)
    end = len(page) if end < 0 else end
    return page[:start] + apart_note(run, reason) + text + page[end:]


def main():
    run = load_json("run.json") or {}
    sections = (("Bounded samplers", bounded_samplers), ("Radius fields, bounded", radius_fields),
                ("Radius fields on the plane", radius_fields_on_the_plane),
                ("Layered worlds", layered_worlds),
                ("Infinite plane", infinite_plane), ("A1 worlds", a1_worlds),
                ("Cold tiles", cold_tiles),
                ("Nearest lookups", nearest),
                ("Nearest lookups on radius-field worlds", field_lookups), ("Deterministic math", deterministic_math),
                ("Verifier", verifier), ("Follow: a walking player", follow),
                ("Service under load", service_load),
                ("The warm answer's copy", warm_answer),
                ("HTTP tiles against GetPoints", http_tiles),
                ("Tiles through nginx's cache", nginx_tiles),
                ("The wire encodings", wire_encodings),
                ("Soak: mixed load, resources flat", soak))
    head = f"""# Performance

<!-- Generated by scripts/make-performance-page.sh from one run; edit the renderer
     (scripts/performance/render_page.py), not this page. -->

The current figures, all from one run of `scripts/make-performance-page.sh`:
commit {run.get('commit', '?')}, {run.get('date', '?')}, on {run.get('cpu', '?')}
({run.get('cores', '?')} cores, shared with other work; load average
{run.get('load_before', '?')} before the run and {run.get('load_after', '?')} after). Absolute
figures move with the machine and its load: each is given beside a baseline measured in the
same run, and the ratio is what we track. The same benchmark measures 20M nearest lookups a
second on an Intel Xeon and 8M on an AMD EPYC, so name the CPU with any figure you quote.

Release build (`-O3 -DNDEBUG -ffp-contract=off`), Google Benchmark medians of
{run.get('repetitions', '?')} repetitions where it repeats. To regenerate this page:

    scripts/make-performance-page.sh            # builds into build-bench, runs, rewrites this page

How each figure got where it is (what was tried, what paid and what did not) is in the
history of this page and the commit messages: `git log -p docs/performance.md`.
"""
    if "--apart" in sys.argv:
        # render_page.py RESULTS --apart TITLE PAGE [REASON]: PAGE with that section replaced.
        at = sys.argv.index("--apart")
        title, page_path = sys.argv[at + 1], sys.argv[at + 2]
        reason = sys.argv[at + 3] if len(sys.argv) > at + 3 else ""
        sys.stdout.write(splice_apart(sections, run, title, page_path, reason))
        return
    rendered = [(title, render(run)) for title, render in sections]
    sys.stdout.write(head + "".join(f"\n## {title}\n\n{text}" for title, text in rendered))
    missing = [title for title, text in rendered if text == MISSING]
    if missing:
        sys.stderr.write(f"render_page: not measured: {', '.join(missing)}\n")
        sys.exit(1)


if __name__ == "__main__":
    main()
