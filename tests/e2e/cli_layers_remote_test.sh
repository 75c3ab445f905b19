#!/usr/bin/env bash
# End-to-end checks of layered worlds (issue 19) through the CLI and a real scallopd: a YAML
# config names a forest (trees, bushes, noise-spaced rocks, a road masked in the rocks by a
# raster made here); `scallop points`, `stream`, `follow`, `verify` and `nearest` serve it by
# name and inline; the same world given inline with --layer prints byte for byte what
# `scallop plane`, `verify` and `nearest` print locally (CSV id,x,y,layer, pages, filters,
# SVG); a --world-file with raster fields is sent naming the server's rasters and prints what
# the same file prints locally; bad layer and raster names exit 1 naming the field (server) or 2
# (client).
# Usage: cli_layers_remote_test.sh path/to/scallop path/to/scallopd
set -euo pipefail

scallop=${1:?usage: cli_layers_remote_test.sh path/to/scallop path/to/scallopd}
scallopd=${2:?usage: cli_layers_remote_test.sh path/to/scallop path/to/scallopd}
# shellcheck source=../shell_checks.sh
source "$(dirname "$0")/../shell_checks.sh"
make_png() { python3 "$(dirname "$0")/../make_gray_png.py" "$@"; }

make_png "$work/road.png" road 60 40
cat >"$work/config.yaml" <<'YAML'
listen: 127.0.0.1:0
rasters:
  road: road.png
  road.png: road.png  # named as its file, so one --world-file serves local runs and the server
worlds:
  forest:
    seed: 7
    layers:
      - {name: trees, min_distance: 8}
      - {name: bushes, min_distance: 3}
      - {name: rocks, radius_field: {raster: {raster_name: road, origin_x: -30, origin_y: -20, pixel_size: 1, r_min: 1.5, r_max: 1.5}}}
    exclusions:
      - {first: rocks, second: trees, distance: 2.5}
  grove:
    seed: 9
    layers:
      - {name: oaks, min_distance: 6}
      - {name: ferns, radius_field: {noise: {r_min: 1.5, r_max: 3, frequency: 0.02, noise_seed: 4}}}
YAML
start_scallopd server --config "$work/config.yaml"
server_pid=$started_pid
server=$address

rect=-30,-20,30,20
# The named world with a raster layer: served, each layer's name in the CSV, the road empty.
run "$scallop" points --server "$server" --world forest --rect "$rect"
expect_status 0 "points of a layered world"
cp "$work/out" "$work/forest.csv"
if [ "$(head -n 1 "$work/out")" = "id,x,y,layer,r" ]; then pass; else
  fail "points header: $(head -n 1 "$work/out")"; fi
for layer in trees bushes rocks; do
  if grep -q ",$layer," "$work/out"; then pass; else fail "no $layer in the forest"; fi
done
run "$scallop" points --server "$server" --world forest --rect "$rect" --page-size 17
if cmp -s "$work/out" "$work/forest.csv"; then pass; else fail "paged forest differs"; fi
run "$scallop" points --server "$server" --world forest --rect "$rect" --encoding exact
if cmp -s "$work/out" "$work/forest.csv"; then pass; else fail "exact-encoded forest differs"; fi
run "$scallop" stream --server "$server" --world forest --rect "$rect"
if cmp -s "$work/out" "$work/forest.csv"; then pass; else fail "streamed forest differs"; fi
# A filter is the unfiltered answer filtered.
run "$scallop" points --server "$server" --world forest --rect "$rect" --layers rocks,trees \
  --page-size 11
grep -v ',bushes,' "$work/forest.csv" >"$work/filtered.csv"
if cmp -s "$work/out" "$work/filtered.csv"; then pass; else fail "filtered pages differ"; fi
run "$scallop" stream --server "$server" --world forest --rect "$rect" --layers trees,rocks
if cmp -s "$work/out" "$work/filtered.csv"; then pass; else fail "filtered stream differs"; fi
run "$scallop" verify --server "$server" --world forest --rect -20,-10,20,10
expect_status 0 "verify of the forest"
if grep -q '^layer rocks: ' "$work/out" && grep -q '^pairs across layers' "$work/out"; then pass
else fail "verify output: $(cat "$work/out")"; fi

# --world-file with raster fields through --server: each raster_name names the server's raster
# (as in its config); here the name is also the PNG's path next to the file, so the same file
# runs locally, and the answers are byte for byte the local ones and the named forest's.
cat >"$work/forest.yaml" <<'YAML'
seed: 7
layers:
  - {name: trees, min_distance: 8}
  - {name: bushes, min_distance: 3}
  - {name: rocks, radius_field: {raster: {raster_name: road.png, origin_x: -30, origin_y: -20, pixel_size: 1, r_min: 1.5, r_max: 1.5}}}
exclusions:
  - {first: rocks, second: trees, distance: 2.5}
YAML
run "$scallop" plane --world-file "$work/forest.yaml" --rect "$rect"
expect_status 0 "plane of the forest file"
cp "$work/out" "$work/file-local.csv"
if cmp -s "$work/file-local.csv" "$work/forest.csv"; then pass; else
  fail "the forest file differs from the named forest"; fi
run "$scallop" points --server "$server" --world-file "$work/forest.yaml" --rect "$rect" \
  --page-size 29
expect_status 0 "points of the forest file"
if cmp -s "$work/out" "$work/file-local.csv"; then pass; else fail "served forest file differs"; fi
run "$scallop" stream --server "$server" --world-file "$work/forest.yaml" --rect "$rect" \
  --layers trees,rocks
if cmp -s "$work/out" "$work/filtered.csv"; then pass; else fail "streamed forest file differs"; fi
# verify: the same report (its first line names the world, a served raster by the server's name).
run "$scallop" verify --world-file "$work/forest.yaml" --rect -20,-10,20,10
tail -n +2 "$work/out" >"$work/file-verify.txt"
run "$scallop" verify --server "$server" --world-file "$work/forest.yaml" --rect -20,-10,20,10
expect_status 0 "verify of the forest file"
if tail -n +2 "$work/out" | cmp -s - "$work/file-verify.txt"; then pass; else
  fail "served verify of the forest file differs: $(cat "$work/out")"; fi
# A one-layer world's own raster field, likewise.
printf '%s\n' 'seed: 3' 'radius_field: {raster: {raster_name: road.png, origin_x: -30, origin_y: -20,' \
  '                          pixel_size: 1, r_min: 1.5, r_max: 1.5}}' >"$work/masked.yaml"
run "$scallop" plane --world-file "$work/masked.yaml" --rect "$rect"
cp "$work/out" "$work/masked.csv"
run "$scallop" points --server "$server" --world-file "$work/masked.yaml" --rect "$rect"
if [ "$(head -n 1 "$work/out")" = "id,x,y,r" ] && cmp -s "$work/out" "$work/masked.csv"; then pass
else fail "served masked world file differs"; fi
# A raster the server has not loaded: INVALID_ARGUMENT naming the field, exit 1.
sed 's/raster_name: road.png/raster_name: nowhere.png/' "$work/forest.yaml" >"$work/unknown.yaml"
run "$scallop" points --server "$server" --world-file "$work/unknown.yaml" --rect "$rect"
expect_status 1 "a world file naming a raster the server has not"
if grep -q 'INVALID_ARGUMENT: world.layers\[2\].radius_field.raster.raster_name: no raster' \
  "$work/err"; then pass; else fail "unknown raster message: $(cat "$work/err")"; fi
# A key the schema has not is the client's to refuse (exit 2), raster or not.
sed 's/pixel_size/pixel_sise/' "$work/forest.yaml" >"$work/typo.yaml"
run "$scallop" points --server "$server" --world-file "$work/typo.yaml" --rect "$rect"
expect_status 2 "a typo in a world file with rasters"
if grep -q "layers\[2\].radius_field.raster: unknown key 'pixel_sise'" "$work/err"; then pass; else
  fail "typo message: $(cat "$work/err")"; fi

# Inline with --layer: byte for byte the local commands' output.
grove=(--seed 9 --layer oaks=6 --layer ferns=noise:1.5,3,0.02,3,4)
run "$scallop" plane "${grove[@]}" --rect "$rect"
cp "$work/out" "$work/plane.csv"
run "$scallop" points --server "$server" "${grove[@]}" --rect "$rect" --page-size 23
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "served inline grove differs from plane"; fi
run "$scallop" points --server "$server" --world grove --rect "$rect"
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "named grove differs from plane"; fi
run "$scallop" stream --server "$server" "${grove[@]}" --rect "$rect" --encoding quantised \
  --format none
expect_status 0 "quantised stream of the grove"
for format in json svg; do
  run "$scallop" plane "${grove[@]}" --rect "$rect" --layers ferns --format "$format" --seams
  cp "$work/out" "$work/plane.$format"
  run "$scallop" points --server "$server" "${grove[@]}" --rect "$rect" --layers ferns \
    --format "$format" --seams
  if cmp -s "$work/out" "$work/plane.$format"; then pass; else fail "served $format differs"; fi
done
forest=(--seed 7 --layer trees=8 --layer bushes=3 --layer rocks=1.5 --exclusion rocks,trees=2.5)
for command in "verify --rect -24,-16,24,16" "verify --rect -24,-16,24,16 --json"; do
  # shellcheck disable=SC2086
  run "$scallop" $command "${forest[@]}"
  cp "$work/out" "$work/local.txt"
  # shellcheck disable=SC2086
  run "$scallop" $command --server "$server" "${forest[@]}"
  if cmp -s "$work/out" "$work/local.txt"; then pass; else
    fail "served '$command' differs: $(diff "$work/out" "$work/local.txt" | head -5)"; fi
done
printf '%s\n' x,y 0.5,0.5 -13,2 7.25,-9.5 -15.5,4 >"$work/positions.csv"
for layer in trees bushes rocks; do
  run "$scallop" nearest "${forest[@]}" --layers "$layer" --input "$work/positions.csv"
  expect_status 0 "nearest of $layer"
  cp "$work/out" "$work/nearest.csv"
  run "$scallop" nearest --server "$server" "${forest[@]}" --layers "$layer" \
    --input "$work/positions.csv"
  if [ "$(wc -l <"$work/out")" -eq 5 ] && cmp -s "$work/out" "$work/nearest.csv"; then pass; else
    fail "served nearest of $layer differs: $(cat "$work/out")"; fi
done
# Follow: the union of what it sends is the plane's points in the union of its viewports.
printf '%s\n' -30,-20,0,0 -20,-20,10,0 >"$work/path.txt"
run "$scallop" follow --server "$server" "${forest[@]}" --path "$work/path.txt"
expect_status 0 "follow of the forest"
sort "$work/out" >"$work/followed.csv"
run "$scallop" plane "${forest[@]}" --rect -30,-20,10,0
sort "$work/out" >"$work/expected.csv"
if cmp -s "$work/followed.csv" "$work/expected.csv"; then pass; else fail "followed forest differs"; fi

# Bad names: the server names the field (exit 1); the client what it can check (2).
run "$scallop" points --server "$server" --world forest --rect "$rect" --layers ferns
expect_status 1 "unknown layer in a filter"
if grep -q "INVALID_ARGUMENT: layers: no layer named 'ferns'" "$work/err"; then pass; else
  fail "unknown layer message: $(cat "$work/err")"; fi
run "$scallop" nearest --server "$server" --world forest --input "$work/positions.csv"
expect_status 1 "nearest of a layered world without a layer"
if grep -q "INVALID_ARGUMENT: layer: required" "$work/err"; then pass; else fail "$(cat "$work/err")"; fi
run "$scallop" points --server "$server" --seed 1 --layer a=1 --layer a=2 --rect 0,0,4,4
expect_status 2 "repeated layer name, judged by the client"
if grep -q 'world.layers\[1\].name' "$work/err"; then pass; else fail "$(cat "$work/err")"; fi
run "$scallop" points --server "$server" --seed 1 --rect 0,0,4,4 --layers trees
expect_status 1 "a filter on a world without layers"
if grep -q 'layers: the world has no layers' "$work/err"; then pass; else fail "$(cat "$work/err")"; fi

report cli_layers_remote_test
