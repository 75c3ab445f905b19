#!/usr/bin/env bash
# End-to-end checks of the `scallop` command line: exit codes, output formats,
# and that `scallop plane` gives the same bits whatever the tiling, the thread
# count or the process. Usage: tests/cli_test.sh path/to/scallop
set -euo pipefail

scallop=${1:?usage: cli_test.sh path/to/scallop}
# shellcheck source=shell_checks.sh
source "$(dirname "$0")/shell_checks.sh"

# check DESCRIPTION COMMAND...: passes when the command succeeds.
check() {
  local what=$1
  shift
  if "$@"; then pass; else fail "$what"; fi
}

# run_scallop ARGS...: `run` on scallop.
run_scallop() { run "$scallop" "$@"; }

# expect_exit CODE ARGS...: scallop ARGS must exit with CODE.
expect_exit() {
  local want=$1
  shift
  run_scallop "$@"
  if [[ $status == "$want" ]]; then
    pass
  else
    fail "scallop $*: exit $status, want $want: $(head -c 300 "$work/err")"
  fi
}

# expect_bad_argument FIELD ARGS...: exit 2 and a message on stderr naming FIELD.
expect_bad_argument() {
  local field=$1
  shift
  expect_exit 2 "$@"
  check "scallop $*: stderr names '$field'" grep -qF -- "$field" "$work/err"
}

# rows FILE ARGS...: the CSV rows (no header) of `scallop plane ARGS`, sorted, in FILE.
rows() {
  local file=$1
  shift
  run_scallop plane "$@"
  if [[ $status != 0 ]]; then fail "scallop plane $*: exit $status: $(head -c 300 "$work/err")"; fi
  tail -n +2 "$work/out" | sort >"$file"
}

# --- Exit codes and messages ------------------------------------------------

expect_exit 0 generate --domain 0,0,20,20
check "generate CSV header is x,y" test "$(head -n 1 "$work/out")" = "x,y"
# Small in area but long and thin: its grids would not fit in memory (was a crash).
expect_bad_argument "scallop generate: domain" generate --domain 0,0,4e9,0.00001
# A seed out of 0..2^64-1 is refused, not wrapped or saturated.
expect_bad_argument "scallop generate: --seed" generate --domain 0,0,20,20 --seed -1
expect_bad_argument "scallop generate: --seed" generate --domain 0,0,20,20 --seed 18446744073709551616
expect_exit 0 plane --rect -5,-5,5,5
check "plane CSV header is id,x,y" test "$(head -n 1 "$work/out")" = "id,x,y"
check "plane prints points" test "$(wc -l <"$work/out")" -gt 50
expect_exit 0 verify --rect -5,-5,5,5

for command in plane verify; do
  expect_bad_argument "scallop $command: --rect" $command --rect nan,0,10,10
  expect_bad_argument "scallop $command: --rect" $command --rect 10,0,0,10
  expect_bad_argument "scallop $command: world.algorithm" $command --rect 0,0,10,10 --algorithm a4
  expect_bad_argument "scallop $command: world.density" \
    $command --rect 0,0,10,10 --algorithm a1 --density 2.5
  expect_bad_argument "scallop $command: world.min_distance" \
    $command --rect 0,0,10,10 --min-distance 0
  # 2^32 d is 4294967296 for d = 1.
  expect_bad_argument "scallop $command: rect.x0" $command --rect 5e9,0,5000000010,10
  expect_bad_argument "scallop $command: --seed" $command --rect 0,0,10,10 --seed -1
  expect_bad_argument "scallop $command: --threads" $command --rect 0,0,10,10 --threads 0
  expect_bad_argument "--rect" $command
done
# verify's 2 d halo crosses the limit that plane's rectangle stays within.
expect_exit 0 plane --rect 4294967290,0,4294967295,10
expect_bad_argument "halo" verify --rect 4294967290,0,4294967295,10

# --- Determinism: one rectangle = its 2x2 tiling, separate processes -------

# A 48 d square cut off the seams (every 16 d): every tile straddles some.
whole=-24,-24,24,24
tiles=("-24,-24,5,-3" "5,-24,24,-3" "-24,-3,5,24" "5,-3,24,24")
for algorithm in a1 a2 a3; do
  world=(--algorithm "$algorithm" --seed 7)
  if [[ $algorithm == a2 ]]; then world+=(--density 1.5); fi
  rows "$work/whole" "${world[@]}" --threads 2 --rect "$whole"
  rows "$work/whole1" "${world[@]}" --threads 1 --rect "$whole"
  : >"$work/tiled"
  for tile in "${tiles[@]}"; do
    rows "$work/tile" "${world[@]}" --threads 1 --rect "$tile"
    cat "$work/tile" >>"$work/tiled"
  done
  sort -o "$work/tiled" "$work/tiled"
  check "$algorithm: the whole has points" test -s "$work/whole"
  check "$algorithm: tiles share no id" test -z "$(cut -d, -f1 "$work/tiled" | sort | uniq -d)"
  check "$algorithm: tiles (1 thread) = whole (2 threads)" cmp -s "$work/tiled" "$work/whole"
  check "$algorithm: whole, 1 thread = 2 threads" cmp -s "$work/whole1" "$work/whole"
done

# --- Verify across seams, every algorithm ----------------------------------

for algorithm in a1 a2 a3; do
  expect_exit 0 verify --algorithm "$algorithm" --seed 3 --rect -20,-20,20,20
  check "verify $algorithm: reports pass" grep -qE '^result +pass$' "$work/out"
  check "verify $algorithm: judges pairs across seams" \
    grep -qE '^pairs across seams +[1-9][0-9]*$' "$work/out"
  expect_exit 0 verify --algorithm "$algorithm" --seed 3 --rect -20,-20,20,20 --json
  check "verify $algorithm --json: passed" grep -qF '"passed":true' "$work/out"
done
# Far from the origin and with an awkward d, where rounding eats into the margin.
expect_exit 0 verify --min-distance 0.37 --seed 42 --rect 1000000,-1000015,1000012,-999999

# --- Formats ---------------------------------------------------------------

# grep finds nothing in broken output: `|| true` lets the check report it, not set -e.
rows "$work/csv" --rect 0,0,30,20
expect_exit 0 plane --rect 0,0,30,20 --format json
count=$(grep -oE '"count":[0-9]+' "$work/out" | cut -d: -f2 || true)
check "plane JSON count = CSV rows" test "$count" = "$(wc -l <"$work/csv")"
expect_exit 0 plane --rect 0,0,30,20 --format none
check "plane --format none prints nothing" test ! -s "$work/out"

rows "$work/csv" --rect -20,-20,20,20
expect_exit 0 plane --rect -20,-20,20,20 --format svg --seams
check "SVG starts with <svg" grep -q '^<svg ' <(head -n 1 "$work/out")
check "SVG ends with </svg>" test "$(tail -n 1 "$work/out")" = "</svg>"
check "SVG --seams draws lines" grep -q '<line ' "$work/out"
circles=$(grep -c '<circle ' "$work/out" || true)
check "SVG draws every point" test "$circles" = "$(wc -l <"$work/csv")"
expect_exit 0 plane --rect -20,-20,20,20 --format svg
check "SVG without --seams has no lines" test "$(grep -c '<line ' "$work/out" || true)" = 0

# --- Analyze: spectra of files, samplers and worlds ------------------------

expect_exit 0 analyze --domain 0,0,20,20 --torus --algorithm a3,dart --sets 2 --json
check "analyze --json: two series" test "$(grep -o '"name":' "$work/out" | wc -l)" = 2
check "analyze --json: A3 rho near 0.86" grep -qE '"rho":\{"mean":0\.8[4-8]' "$work/out"
run_scallop plane --rect -10,-10,10,10
cp "$work/out" "$work/plane.csv"
expect_exit 0 analyze --input "$work/plane.csv" --rect -8,-8,8,8 --png "$work/p.png" \
  --plot "$work/p.svg"
check "analyze --png writes a PNG" test "$(head -c 4 "$work/p.png" | tail -c 3)" = PNG
check "analyze --plot writes an SVG" grep -q '^<svg ' "$work/p.svg"
check "analyze of a file drops points outside --rect" grep -q 'outside the window' "$work/out"
run_scallop plane --rect -10,-10,10,10 --format json
cp "$work/out" "$work/plane.json"
expect_exit 0 analyze --input "$work/plane.json" --input "$work/plane.csv" --json
check "analyze --input twice: two sets" grep -qF '"sets":2' "$work/out"
expect_exit 0 analyze --rect 12,4,20,12 --rect 4,4,12,12 --label seam,interior --sets 3
check "analyze of worlds: labelled series" grep -q '^interior (world)' "$work/out"
expect_exit 2 analyze --rect 0,0,10,20
expect_exit 2 analyze --domain 0,0,10,10 --algorithm nope
expect_exit 2 analyze --input "$work/missing.csv"
expect_exit 2 analyze --input "$work/plane.csv" --domain 0,0,10,10
expect_exit 2 analyze --domain 0,0,10,10 --max-frequency 257
expect_exit 2 analyze --domain 0,0,10,10 --sets 0
expect_exit 2 analyze --domain 0,0,10,10 --plot "$work/p.png"
expect_exit 2 analyze --rect 0,0,10,10 --label one,two
expect_exit 2 analyze
expect_exit 1 analyze --domain 0,0,10,10 --png "$work/no/such/dir/p.png"

# --- scallop nearest and scallop noise (issue 5) -----------------------------

# Header, one row per position, stdin = --input; blank, comment and header lines skipped.
printf 'x,y\n0.5,0.25\n\n# a comment\n16,3\n-1e6,2.5\n' >"$work/positions"
expect_exit 0 nearest --seed 7 --input "$work/positions"
cp "$work/out" "$work/nearest.csv"
check "nearest: CSV header" test "$(head -n 1 "$work/nearest.csv")" = "x,y,id,f1,f2,nearest_x,nearest_y"
check "nearest: one row per position" test "$(wc -l <"$work/nearest.csv")" = 4
"$scallop" nearest --seed 7 <"$work/positions" >"$work/stdin.csv"
check "nearest: stdin = --input" cmp -s "$work/nearest.csv" "$work/stdin.csv"

# Against brute force in awk (doubles, the same dx*dx + dy*dy, %.17g): random
# positions, one on a seam and one on a point, over the points of `scallop
# plane` within 4 d. Ties between distinct points do not occur at random.
rows "$work/points" --seed 7 --rect -8,-8,40,24
point=$(head -n 1 "$work/points")
{
  echo "16,${point##*,}"
  echo "${point#*,}"
  awk 'BEGIN { srand(11); for (k = 0; k < 25; ++k) printf "%.17g,%.17g\n", rand() * 32 - 4, rand() * 16 - 4 }'
} >"$work/random_positions"
expect_exit 0 nearest --seed 7 --input "$work/random_positions"
tail -n +2 "$work/out" | cut -d, -f1-4 >"$work/fast"
awk -F, 'NR == FNR { id[NR] = $1; x[NR] = $2; y[NR] = $3; n = NR; next }
  { best = -1; for (k = 1; k <= n; ++k) { dx = $1 - x[k]; dy = $2 - y[k]; s = dx * dx + dy * dy;
      if (best < 0 || s < best) { best = s; who = id[k] } }
    printf "%.17g,%.17g,%s,%.17g\n", $1, $2, who, sqrt(best) }' \
  "$work/points" "$work/random_positions" >"$work/slow"
check "nearest = awk brute force (id, F1)" cmp -s "$work/fast" "$work/slow"
check "nearest: on a point, F1 = 0 and its id" \
  test "$(sed -n 3p "$work/out" | cut -d, -f3,4)" = "${point%%,*},0"

printf '1,2\nfoo\n' >"$work/bad_positions"
expect_bad_argument "input line 2" nearest --input "$work/bad_positions"
printf '0,0\n1e20,0\n' >"$work/far_positions"
expect_bad_argument "positions[1].x" nearest --input "$work/far_positions"
expect_bad_argument "--input" nearest --input "$work/no/such/file"
expect_bad_argument "--threads" nearest --threads 0 --input "$work/positions"
expect_bad_argument "world.min_distance" nearest --min-distance -1 --input "$work/positions"

# noise: a PNG of the asked size for every channel.
for channel in f1 f2 f2-f1 id cell; do
  expect_exit 0 noise --seed 7 --rect -8,-4,24,12 --size 64x32 --channel "$channel" --png "$work/$channel.png"
  check "noise $channel: PNG signature" test "$(head -c 4 "$work/$channel.png" | tail -c 3)" = PNG
  # IHDR width and height, big-endian at bytes 16..23.
  check "noise $channel: 64x32" test "$(od -An -tu1 -j16 -N8 "$work/$channel.png" | tr -s ' ')" = " 0 0 0 64 0 0 0 32"
done
check "noise: channels differ" bash -c "! cmp -s '$work/f1.png' '$work/f2.png'"
expect_bad_argument "--channel" noise --rect 0,0,8,8 --size 8x8 --channel f3 --png "$work/x.png"
expect_bad_argument "--size" noise --rect 0,0,8,8 --size 8x9 --png "$work/x.png"
expect_bad_argument "--size" noise --rect 0,0,8,8 --size 0x0 --png "$work/x.png"
expect_bad_argument "last sample" noise --rect 4294967000,0,4294967592,296 --size 2x1 --png "$work/x.png"
expect_bad_argument "PNG" noise --rect 0,0,8,8 --size 8x8 --png "$work/no/such/dir/x.png"
expect_exit 2 noise --rect 0,0,8,8 --size 8x8

# --- Radius fields: options, columns, pictures and errors -----------------

make_png() { python3 "$(dirname "$0")/make_gray_png.py" "$@"; }
# in_range FILE COLUMN LOW HIGH: every row's COLUMN (after the header) lies in [LOW, HIGH].
in_range() {
  awk -F, -v c="$2" -v lo="$3" -v hi="$4" 'NR > 1 && ($c < lo || $c > hi) { bad = 1 }
    END { exit bad }' "$1"
}

expect_exit 0 generate --radius-noise 1,4,0.02 --domain 0,0,40,40 --seed 5
check "generate noise: CSV header is x,y,r" test "$(head -n 1 "$work/out")" = "x,y,r"
check "generate noise: points" test "$(wc -l <"$work/out")" -gt 50
check "generate noise: r within [1, 4]" in_range "$work/out" 3 1 4
cp "$work/out" "$work/noise.csv"
expect_exit 0 generate --radius-noise 1,4,0.02 --domain 0,0,40,40 --seed 5 --radius-noise-seed 6
check "generate noise: --radius-noise-seed changes the field" \
  bash -c "! cmp -s '$work/out' '$work/noise.csv'"
expect_exit 0 generate --radius-noise 1,4,0.02 --domain 0,0,40,40 --seed 5 --format svg
circles=$(grep -c '<circle ' "$work/out" || true)
check "generate noise SVG: a disk per point" test "$circles" = "$(($(wc -l <"$work/noise.csv") - 1))"
half=$(sed -n 2p "$work/noise.csv" | awk -F, '{ printf "%.6g", $3 / 2 }')
drawn=$(grep -m1 -oE 'r="[^"]+"' "$work/out" | head -n 1 | sed -E 's/r="([^"]+)"/\1/' |
  awk '{ printf "%.6g", $1 }')
check "generate noise SVG: the first disk is R/2 ($drawn vs $half)" test "$drawn" = "$half"
expect_exit 0 generate --radius-noise 1,4,0.02 --domain 0,0,20,20 --format none --stats
check "generate noise --stats: names the field" grep -q '^field noise$' "$work/err"

# A raster whose column 0 is masked: 6 x 4 pixels of side 5 from (-10, 0).
make_png "$work/masked.png" masked 6 4
raster=(--radius-raster "$work/masked.png" --raster-origin -10,0 --raster-pixel 5 --radius-range 1,2)
expect_exit 0 generate "${raster[@]}" --domain -10,0,20,20 --seed 2
check "generate raster: CSV header is x,y,r" test "$(head -n 1 "$work/out")" = "x,y,r"
check "generate raster: r within [1, 2]" in_range "$work/out" 3 1 2
check "generate raster: no point in the masked column x < -5" in_range "$work/out" 1 -5 20
check "generate raster: points beside the mask" \
  awk -F, 'NR > 1 && $1 < 0 { found = 1 } END { exit !found }' "$work/out"
make_png "$work/ramp16.png" ramp16 4 4
expect_exit 0 generate --radius-raster "$work/ramp16.png" --raster-pixel 10 --radius-range 1,2 \
  --domain 0,0,40,40
check "generate 16-bit raster: r within [1, 2]" in_range "$work/out" 3 1 2

expect_exit 0 plane --radius-noise 1,4,0.02 --rect -10,-10,10,10
check "plane noise: CSV header is id,x,y,r" test "$(head -n 1 "$work/out")" = "id,x,y,r"
check "plane noise: r within [1, 4]" in_range "$work/out" 4 1 4
expect_exit 0 plane --radius-noise 1,4,0.02 --rect -10,-10,10,10 --format json
check "plane noise JSON: has r" grep -qF '"r":[' "$work/out"
expect_exit 0 plane "${raster[@]}" --rect -10,0,20,20
check "plane raster: CSV header is id,x,y,r" test "$(head -n 1 "$work/out")" = "id,x,y,r"

# verify judges a field world by the max rule, masks included.
expect_exit 0 verify --radius-noise 1,3,0.02 --seed 4 --rect -20,-20,20,20
check "verify noise world: field conflicts 0" grep -qE '^field conflicts +0 ' "$work/out"
check "verify noise world: pass" grep -qE '^result +pass$' "$work/out"
expect_exit 0 verify "${raster[@]}" --rect -10,0,20,20 --json
check "verify raster world --json: field passed" grep -qF '"passed":true,"points_masked":0' "$work/out"

# analyze with a field: rho per band of R, conflicts against R, the points over the field.
expect_exit 0 analyze --radius-noise 1,4,0.02 --domain 0,0,60,60 --sets 2 --bands 3 --json \
  --png "$work/field.png"
check "analyze field: no conflict" grep -qF '"conflicts":0' "$work/out"
check "analyze field: 3 bands" test "$(grep -oF '"nearest_ratio_mean"' "$work/out" | wc -l)" = 4
check "analyze field: rho near maximal packing" \
  python3 -c "import json,sys; r=json.load(open('$work/out'))['all']['rho']; sys.exit(not 0.75 < r < 0.95)"
check "analyze field --png: a PNG" test "$(head -c 4 "$work/field.png" | tail -c 3)" = PNG
# The spectrum normalised by local R, per band: blue noise in every band (little power below
# 0.5 / R, a peak above 1 near 1 / R), and a plot of it; uniform random points (a planted
# fault: no spacing at all) are white at low frequencies instead.
spectrum_is_blue() {
  python3 - "$work/out" "$1" <<'PYTHON'
import json, sys
doc = json.load(open(sys.argv[1]))
blue = sys.argv[2] == "blue"
judged = 0
for band in doc["bands"] + [doc["all"]]:
    s = band["spectrum"]
    if s["points"] < 300:
        continue
    judged += 1
    low, peak = s["low_frequency_power"], s["peak"]
    ok = -0.15 < low < 0.4 and peak["power"] > 1.5 and 0.8 < peak["frequency_per_r"] < 1.3
    if ok != blue:
        sys.exit(f"band {band['r']}: low {low}, peak {peak}")
sys.exit(0 if judged >= 2 else "too few bands judged")
PYTHON
}
expect_exit 0 analyze --radius-noise 1,4,0.02 --domain 0,0,120,120 --sets 2 --bands 3 --json \
  --plot "$work/field.svg"
check "analyze field: each band's spectrum is blue noise" spectrum_is_blue blue
check "analyze field --plot: an SVG with the bands" grep -qF 'R in [' "$work/field.svg"
awk 'BEGIN { srand(24); print "x,y"; for (k = 0; k < 4000; ++k) print rand() * 120 "," rand() * 120 }' \
  >"$work/uniform.csv"
expect_exit 0 analyze --radius-noise 1,4,0.02 --input "$work/uniform.csv" --rect 0,0,120,120 --json
check "analyze field: uniform points are not blue" spectrum_is_blue white
# Seed 11 has a pair at exactly the spacing whose |p - q| / max(R) rounds to 1 - 2^-53 (seed 2
# had one before the field sampler of generator version 4): the rule's own expression
# (dx^2 + dy^2 < m^2) allows it, and analyze must count no conflict.
expect_exit 0 analyze --radius-noise 1,4,0.02 --domain 0,0,200,200 --seed 11 --bands 1 --json
check "analyze field: a pair at exactly the spacing is no conflict" \
  python3 -c "import json,sys; d=json.load(open('$work/out')); sys.exit(not (d['conflicts'] == 0 and d['smallest_pair_ratio'] < 1))"
# A file of x,y,r rows with a conflict planted: two points 0.5 apart where R >= 1.
printf 'x,y,r\n10,10,1\n10.5,10,1\n30,30,1\n' >"$work/planted.csv"
expect_exit 0 analyze --radius-noise 1,4,0.02 --input "$work/planted.csv" --rect 0,0,40,40 --json
check "analyze field --input: the planted conflict is found" grep -qF '"conflicts":1' "$work/out"
expect_exit 0 analyze --radius-noise 1,4,0.02 --input "$work/noise.csv" --rect 0,0,40,40 --json
check "analyze field --input: generate's x,y,r file has no conflict" grep -qF '"conflicts":0' "$work/out"
expect_bad_argument "--bands" analyze --radius-noise 1,4,0.02 --domain 0,0,20,20 --bands 0
# The field Bridson baseline on a --domain: no conflict, fewer points than the field sampler
# (it is not maximal), and its flatter spectrum: quiet below 0.5 / R but a peak of 1.2 to 2
# (the field sampler's passes 2); not on the plane.
expect_exit 0 analyze --radius-noise 1,4,0.02 --domain 0,0,120,120 --sets 2 --bands 3 --json \
  --algorithm bridson
check "analyze field bridson: no conflict" grep -qF '"conflicts":0' "$work/out"
check "analyze field bridson: sparser than a3" \
  python3 -c "import json,sys; r=json.load(open('$work/out'))['all']['rho']; sys.exit(not 0.6 < r < 0.8)"
check "analyze field bridson: Bridson's spectrum" \
  python3 -c "import json,sys; s=json.load(open('$work/out'))['all']['spectrum']; sys.exit(not (s['low_frequency_power'] < 0.4 and 1.2 < s['peak']['power'] < 2))"
expect_bad_argument "--algorithm" analyze --radius-noise 1,4,0.02 --rect 0,0,20,20 --algorithm bridson

# Bad fields: exit 2, the option named (and the core's field where it judged).
expect_bad_argument "--radius-noise: field.frequency" generate --radius-noise 1,4,0.5
expect_bad_argument "--radius-noise: field.r_min" generate --radius-noise 0,4,0.02
expect_bad_argument "--radius-noise: field.r_min" generate --radius-noise -1,4,0.02
expect_bad_argument "--radius-noise: values must be finite" generate --radius-noise nan,4,0.02
expect_bad_argument "--radius-noise: field.r_max" generate --radius-noise 1,101,0.0001
expect_bad_argument "--radius-noise: field.r_max" generate --radius-noise 2,1,0.01
expect_bad_argument "--radius-noise: field.octaves" generate --radius-noise 1,2,0.01,9
expect_bad_argument "--radius-noise: expected" generate --radius-noise 1,2
expect_bad_argument "--radius-noise-seed" generate --radius-noise 1,2,0.01 --radius-noise-seed x
expect_bad_argument "--algorithm" generate --radius-noise 1,2,0.01 --algorithm a1
expect_bad_argument "--torus" generate --radius-noise 1,2,0.01 --torus
expect_bad_argument "--radius-raster: raster.path" generate --radius-raster "$work/none.png" --radius-range 1,2
printf 'not a png' >"$work/text.png"
expect_bad_argument "--radius-raster: raster.path" generate --radius-raster "$work/text.png" --radius-range 1,2
make_png "$work/rgb.png" rgb 4 4
expect_bad_argument "--radius-raster: raster:" generate --radius-raster "$work/rgb.png" --radius-range 1,2
make_png "$work/wide.png" ramp 20000 1
expect_bad_argument "16384" generate --radius-raster "$work/wide.png" --radius-range 1,2
# Steps of 4 levels in 254 of a range of 1: 0.0157 a pixel, too steep at 0.02 a pixel.
expect_bad_argument "--raster-pixel: raster.pixel_size" \
  generate --radius-raster "$work/masked.png" --raster-pixel 0.02 --radius-range 1,2
expect_bad_argument "--radius-range: field.r_min" \
  generate --radius-raster "$work/masked.png" --raster-pixel 5 --radius-range 0,2
expect_bad_argument "--raster-origin" generate "${raster[@]/-10,0/x,0}"
expect_exit 2 generate --radius-noise 1,2,0.01 --min-distance 2
expect_exit 2 generate --radius-noise 1,2,0.01 --radius-raster "$work/masked.png" --radius-range 1,2
expect_exit 2 generate --radius-raster "$work/masked.png"
expect_exit 2 generate --radius-range 1,2
for command in plane verify; do
  expect_bad_argument "--radius-noise: field.frequency" $command --rect 0,0,8,8 --radius-noise 1,4,0.5
  expect_bad_argument "--algorithm" $command --rect 0,0,8,8 --radius-noise 1,2,0.01 --algorithm a2
done

# --- Layered worlds (issue 19) ----------------------------------------------
forest=(--seed 7 --layer trees=8 --layer bushes=3 --layer rocks=1.5)
expect_exit 0 plane "${forest[@]}" --rect -20,-20,20,20
check "plane layers: CSV header is id,x,y,layer" test "$(head -n 1 "$work/out")" = "id,x,y,layer"
check "plane layers: every layer present" \
  test "$(tail -n +2 "$work/out" | cut -d, -f4 | sort -u | tr '\n' ' ')" = "bushes rocks trees "
cp "$work/out" "$work/forest.csv"
expect_exit 0 plane "${forest[@]}" --rect -20,-20,20,20 --layers rocks,trees
check "plane --layers: the unfiltered rows of those layers" \
  test "$(tail -n +2 "$work/out" | sort)" = "$(grep -v ',bushes$' "$work/forest.csv" | tail -n +2 | sort)"
# generate: the same layers sampled on a bounded rectangle alone (SampleLayers).
expect_exit 0 generate "${forest[@]}" --domain 0,0,30,30 --stats
check "generate layers: CSV header is x,y,layer" test "$(head -n 1 "$work/out")" = "x,y,layer"
check "generate layers: --stats counts the layers" grep -qE '^layers 3$' "$work/err"
cp "$work/out" "$work/bounded-forest.csv"
check "generate layers: every pair keeps d in its layer and D across (brute force)" python3 -c "
import csv, itertools, math, sys
d = {'trees': 8, 'bushes': 3, 'rocks': 1.5}
def D(a, b):  # the default matrix: (sum of 1/r^2 over the layers up to the later)^-1/2
    upto = {'trees': ['trees'], 'bushes': ['trees', 'bushes'], 'rocks': list(d)}
    later = max(a, b, key=lambda n: list(d).index(n))
    return sum(d[n] ** -2 for n in upto[later]) ** -0.5
rows = [(float(r['x']), float(r['y']), r['layer']) for r in csv.DictReader(open('$work/bounded-forest.csv'))]
assert {r[2] for r in rows} == set(d), 'a layer is missing'
assert all(0 <= x < 30 and 0 <= y < 30 for x, y, _ in rows), 'a point outside the domain'
for (x, y, a), (u, v, b) in itertools.combinations(rows, 2):
    rule = d[a] if a == b else D(a, b)
    if (x - u) ** 2 + (y - v) ** 2 < rule ** 2 * (1 - 1e-12):
        sys.exit(f'{a} at ({x}, {y}) and {b} at ({u}, {v}) closer than {rule}')
"
expect_exit 0 generate "${forest[@]}" --domain 0,0,30,30 --layers rocks
check "generate --layers: the unfiltered rows of that layer" \
  test "$(tail -n +2 "$work/out")" = "$(grep ',rocks$' "$work/bounded-forest.csv")"
expect_exit 0 generate "${forest[@]}" --layer ferns=noise:1,2,0.02 --domain 0,0,20,20
check "generate field layer: CSV header is x,y,layer,r" test "$(head -n 1 "$work/out")" = "x,y,layer,r"
expect_bad_argument "--algorithm: layers are sampled by a3 only" generate "${forest[@]}" --algorithm a2
expect_bad_argument "--torus: layers are sampled on rectangles only" generate "${forest[@]}" --torus
expect_bad_argument "--layers: needs --layer" generate --layers rocks
expect_bad_argument "world.layers[1].name" generate --layer trees=8 --layer trees=3
# generate --world-file: the file's world sampled on the domain alone, as its flags give it.
printf 'seed: 7\nlayers:\n  - {name: trees, min_distance: 8}\n  - {name: bushes, min_distance: 3}\n  - {name: rocks, min_distance: 1.5}\n' \
  >"$work/bounded-forest.yaml"
expect_exit 0 generate --world-file "$work/bounded-forest.yaml" --domain 0,0,30,30
check "generate --world-file, layered: the flags' points" cmp -s "$work/out" "$work/bounded-forest.csv"
printf 'seed: 9\nmin_distance: 2\nalgorithm: a2\ndensity: 1.5\n' >"$work/plain.yaml"
expect_exit 0 generate --world-file "$work/plain.yaml" --domain 0,0,30,30
cp "$work/out" "$work/plain-file.csv"
expect_exit 0 generate --seed 9 --min-distance 2 --algorithm a2 --density 1.5 --domain 0,0,30,30
check "generate --world-file, plain: the flags' points" cmp -s "$work/out" "$work/plain-file.csv"
expect_bad_argument "--torus: --world-file" generate --world-file "$work/bounded-forest.yaml" \
  --domain 0,0,30,30 --torus
expect_bad_argument "--layers: --world-file" generate --world-file "$work/plain.yaml" --layers a
expect_exit 2 generate --world-file "$work/plain.yaml" --seed 3
expect_exit 0 plane "${forest[@]}" --layer ferns=noise:1,2,0.02 --rect -10,-10,10,10
check "plane field layer: CSV header is id,x,y,layer,r" \
  test "$(head -n 1 "$work/out")" = "id,x,y,layer,r"
expect_exit 0 plane "${forest[@]}" --rect -20,-20,20,20 --format svg
check "plane layers SVG: a legend" grep -qF '>bushes</text>' "$work/out"
check "plane layers SVG: each layer its colour, disks of half its spacing" python3 -c "
import re, sys
groups = re.findall(r'<g fill=\"(#[0-9a-f]+)\"[^>]*>(.*?)</g>', open('$work/out').read(), re.S)
radii = [sorted(set(re.findall(r' r=\"([0-9.]+)\"', body))) for _, body in groups]
sys.exit(len({fill for fill, _ in groups}) != 3 or radii != [['4'], ['1.5'], ['0.75']])"
# Tiles and threads: the same rows as one query.
rows "$work/whole" "${forest[@]}" --rect -20,-20,20,20 --threads 1
rows "$work/left" "${forest[@]}" --rect -20,-20,3,20 --threads 3
rows "$work/right" "${forest[@]}" --rect 3,-20,20,20
check "plane layers: two tiles equal the whole" \
  test "$(sort "$work/left" "$work/right")" = "$(cat "$work/whole")"
# One layer is the plain world: the same id,x,y rows.
rows "$work/plain" --seed 7 --min-distance 2 --rect -10,-10,10,10
rows "$work/one" --seed 7 --layer only=2 --rect -10,-10,10,10
check "plane one layer: the plain world's rows" \
  test "$(cut -d, -f1-3 "$work/one")" = "$(cat "$work/plain")"
expect_exit 0 verify "${forest[@]}" --exclusion rocks,trees=2.5 --rect -15,-15,15,15
check "verify layers: pass" grep -qE '^result +pass$' "$work/out"
check "verify layers: pairs across layers judged" grep -qE '^pairs across layers +[1-9]' "$work/out"
expect_exit 0 verify "${forest[@]}" --rect -15,-15,15,15 --json
check "verify layers --json: layered passed" grep -qF '"cross_conflicts":0' "$work/out"
expect_exit 0 analyze "${forest[@]}" --rect 0,0,60,60 --sets 2 --json --png "$work/layers.png"
check "analyze layers: each layer and the union" \
  python3 -c "import json,sys; a=json.load(open('$work/out')); sys.exit([l['name'] for l in a['layers']] != ['trees','bushes','rocks','union'])"
check "analyze layers: no pair across layers closer than D" \
  python3 -c "import json,sys; a=json.load(open('$work/out')); sys.exit(any(sum(c['neighbours_per_point'][:20]) for c in a['cross']))"
check "analyze layers: 6 cross histograms" \
  python3 -c "import json,sys; a=json.load(open('$work/out')); sys.exit(len(a['cross']) != 6)"
check "analyze layers --png: a PNG" test "$(head -c 4 "$work/layers.png" | tail -c 3)" = PNG
# On a --domain alone: the ordered layers (a3) and Wei's joint darts (wei), which keep D too
# and, being dart throwing, stop short of the ordered layers' counts.
for algorithm in a3 wei; do
  expect_exit 0 analyze "${forest[@]}" --domain 0,0,60,60 --algorithm $algorithm --sets 2 --json
  cp "$work/out" "$work/bounded-$algorithm.json"
  check "analyze layers --domain ($algorithm): no pair across layers closer than D" \
    python3 -c "import json,sys; a=json.load(open('$work/out')); sys.exit(any(sum(c['neighbours_per_point'][:20]) for c in a['cross']) or [l['name'] for l in a['layers']] != ['trees','bushes','rocks','union'])"
done
check "analyze layers --domain: wei fills less than the ordered layers" \
  python3 -c "import json,sys; u=lambda n: json.load(open('$work/bounded-'+n+'.json'))['layers'][3]['mean_points']; sys.exit(not 0.5 * u('a3') < u('wei') < u('a3'))"
expect_bad_argument "--rect: a layered world" analyze "${forest[@]}" --domain 0,0,20,20 --rect 0,0,20,20
expect_bad_argument "--algorithm: layers on a --domain take a3" analyze "${forest[@]}" --domain 0,0,20,20 --algorithm bridson
expect_bad_argument "--algorithm: a layered world is a3's" analyze "${forest[@]}" --rect 0,0,20,20 --algorithm wei
expect_bad_argument "world.layers[1].name: 'trees' is already" plane --layer trees=8 --layer trees=3 --rect 0,0,8,8
expect_bad_argument "world.exclusions[1]: the matrix is not symmetric" plane "${forest[@]}" \
  --exclusion trees,bushes=2 --exclusion bushes,trees=3 --rect 0,0,8,8
expect_bad_argument "world.exclusions[0].distance" plane "${forest[@]}" --exclusion trees,rocks=-1 \
  --rect 0,0,8,8
expect_bad_argument "--exclusion: values must be finite" plane "${forest[@]}" \
  --exclusion trees,rocks=nan --rect 0,0,8,8
expect_bad_argument "--exclusion: expected NAME,NAME=DISTANCE" plane "${forest[@]}" --exclusion trees=2 \
  --rect 0,0,8,8
expect_bad_argument "--layer: expected NAME=SPACING" plane --layer trees --rect 0,0,8,8
expect_bad_argument "--layer ferns: field.frequency" plane --layer ferns=noise:1,4,0.5 --rect 0,0,8,8
expect_bad_argument "--layers: no layer named 'oaks'" plane "${forest[@]}" --layers oaks --rect 0,0,8,8
expect_exit 2 plane --layer trees=8 --min-distance 2 --rect 0,0,8,8
# --world-file: the world as YAML, the schema of a named world in scallopd's config.
cat >"$work/forest.yaml" <<'YAML'
seed: 7
layers:
  - {name: trees, min_distance: 8}
  - {name: bushes, min_distance: 3}
  - {name: rocks, min_distance: 1.5}
exclusions:
  - {first: rocks, second: trees, distance: 2.5}
YAML
rows "$work/from-file" --world-file "$work/forest.yaml" --rect -10,-10,10,10
rows "$work/from-flags" "${forest[@]}" --exclusion rocks,trees=2.5 --rect -10,-10,10,10
check "plane --world-file: the same rows as the flags" cmp -s "$work/from-file" "$work/from-flags"
printf 'seed: 7\nlayers:\n  - {name: a, min_distance: 2}\n  - {name: a, min_distance: 1}\n' \
  >"$work/repeated.yaml"
expect_bad_argument "--world-file $work/repeated.yaml: world.layers[1].name" \
  plane --world-file "$work/repeated.yaml" --rect 0,0,5,5
printf 'seed: 7\nlayrs: []\n' >"$work/typo.yaml"
expect_bad_argument "unknown key 'layrs'" plane --world-file "$work/typo.yaml" --rect 0,0,5,5
expect_exit 2 plane --world-file "$work/forest.yaml" --seed 3 --rect 0,0,5,5
# analyze --world-file: the report the flags give, for a layered, a plain and a field world.
expect_exit 0 analyze --world-file "$work/forest.yaml" --rect 0,0,40,40 --sets 2 --json
cp "$work/out" "$work/analyze-file.json"
expect_exit 0 analyze "${forest[@]}" --exclusion rocks,trees=2.5 --rect 0,0,40,40 --sets 2 --json
check "analyze --world-file, layered: the flags' report" cmp -s "$work/out" "$work/analyze-file.json"
printf 'seed: 5\nmin_distance: 1.5\nalgorithm: a1\ndensity: 1.5\n' >"$work/plain.yaml"
expect_exit 0 analyze --world-file "$work/plain.yaml" --rect 0,0,30,30 --sets 2
cp "$work/out" "$work/analyze-file.txt"
expect_exit 0 analyze --seed 5 --min-distance 1.5 --algorithm a1 --density 1.5 --rect 0,0,30,30 --sets 2
check "analyze --world-file, plain: the flags' report" cmp -s "$work/out" "$work/analyze-file.txt"
printf 'seed: 5\nradius_field: {noise: {r_min: 1, r_max: 4, frequency: 0.02}}\n' >"$work/field.yaml"
expect_exit 0 analyze --world-file "$work/field.yaml" --rect 0,0,40,40 --sets 2 --json
cp "$work/out" "$work/analyze-file.json"
expect_exit 0 analyze --seed 5 --radius-noise 1,4,0.02 --rect 0,0,40,40 --sets 2 --json
check "analyze --world-file, field: the flags' report" cmp -s "$work/out" "$work/analyze-file.json"
expect_exit 2 analyze --world-file "$work/forest.yaml" --seed 3 --rect 0,0,5,5
expect_bad_argument "unknown key 'layrs'" analyze --world-file "$work/typo.yaml" --rect 0,0,5,5

report cli_test
