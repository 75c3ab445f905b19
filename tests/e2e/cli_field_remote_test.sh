#!/usr/bin/env bash
# End-to-end checks of radius-field worlds through the CLI and a real scallopd: a YAML config
# loads a raster (made here) and names a raster world and a noise world; `scallop points`,
# `stream`, `follow` and `info` serve them by name with the r column; `nearest` and `noise`
# answer a noise world through the server as locally; an inline noise world
# equals `scallop plane`'s; bad fields exit 1 (server) or 2 (client) naming the field; configs
# with a missing, colour or unknown raster, or a bad field, stop scallopd naming the key.
# Usage: cli_field_remote_test.sh path/to/scallop path/to/scallopd
set -euo pipefail

scallop=${1:?usage: cli_field_remote_test.sh path/to/scallop path/to/scallopd}
scallopd=${2:?usage: cli_field_remote_test.sh path/to/scallop path/to/scallopd}
# shellcheck source=../shell_checks.sh
source "$(dirname "$0")/../shell_checks.sh"
make_png() { python3 "$(dirname "$0")/../make_gray_png.py" "$@"; }

make_png "$work/hills.png" masked 10 8
cat >"$work/config.yaml" <<'YAML'
listen: 127.0.0.1:0
rasters:
  hills: hills.png
worlds:
  valley: {seed: 3, radius_field: {raster: {raster_name: hills, origin_x: -20, origin_y: -16, pixel_size: 4, r_min: 1, r_max: 2}}}
  dunes: {seed: 4, radius_field: {noise: {r_min: 1, r_max: 3, frequency: 0.02, noise_seed: 6}}}
YAML
start_scallopd server --config "$work/config.yaml"
server_pid=$started_pid
server=$address

rect=-20,-16,20,16
run "$scallop" points --server "$server" --world valley --rect "$rect"
expect_status 0 "points of a raster world"
cp "$work/out" "$work/valley.csv"
if [ "$(head -n 1 "$work/out")" = "id,x,y,r" ]; then pass; else fail "points header: $(head -n 1 "$work/out")"; fi
if [ "$(wc -l <"$work/out")" -gt 50 ]; then pass; else fail "points of valley: too few"; fi
# Column 0 of the raster (x in [-20, -16)) is masked.
if awk -F, 'NR > 1 && ($2 < -16 || $4 < 1 || $4 > 2) { bad = 1 } END { exit bad }' "$work/out"
then pass; else fail "a point in the mask or R outside [1, 2]"; fi
run "$scallop" points --server "$server" --world valley --rect "$rect" --page-size 29
if cmp -s "$work/out" "$work/valley.csv"; then pass; else fail "paged points differ"; fi
run "$scallop" stream --server "$server" --world valley --rect "$rect"
expect_status 0 "stream of a raster world"
if cmp -s "$work/out" "$work/valley.csv"; then pass; else fail "stream CSV differs from points"; fi
run "$scallop" points --server "$server" --seed 3 --radius-raster hills --raster-origin -20,-16 \
  --raster-pixel 4 --radius-range 1,2 --rect "$rect"
if cmp -s "$work/out" "$work/valley.csv"; then pass; else fail "inline raster world differs from named"; fi
run "$scallop" points --server "$server" --world valley --rect "$rect" --format svg
if grep -q '<circle' "$work/out"; then pass; else fail "svg of a field world"; fi

# An inline noise world equals the local plane's, r column included.
noise=(--seed 5 --radius-noise 1,3,0.02 --radius-noise-seed 2)
run "$scallop" plane "${noise[@]}" --rect "$rect"
cp "$work/out" "$work/plane.csv"
run "$scallop" points --server "$server" "${noise[@]}" --rect "$rect"
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "served noise world differs from plane"; fi
printf '%s\n' -20,-16,0,0 -10,-16,10,0 >"$work/path.txt"
run "$scallop" follow --server "$server" --world dunes --path "$work/path.txt"
expect_status 0 "follow of a noise world"
if [ "$(head -n 1 "$work/out")" = "id,x,y,r" ]; then pass; else fail "follow header: $(head -n 1 "$work/out")"; fi
# scallop nearest and noise on a field world: through the server the same bytes as locally.
printf '%s\n' x,y 0.5,0.5 -13,2 7.25,-9.5 -15.5,4 >"$work/positions.csv"
run "$scallop" nearest "${noise[@]}" --input "$work/positions.csv"
expect_status 0 "nearest on a noise world"
cp "$work/out" "$work/nearest.csv"
run "$scallop" nearest --server "$server" "${noise[@]}" --input "$work/positions.csv"
if [ "$(wc -l <"$work/out")" -eq 5 ] && cmp -s "$work/out" "$work/nearest.csv"; then pass; else
  fail "served nearest differs from local: $(cat "$work/out")"; fi
run "$scallop" noise "${noise[@]}" --rect -16,-8,16,8 --size 64x32 --channel f1 --png "$work/local.png"
expect_status 0 "noise image of a noise world"
run "$scallop" noise --server "$server" "${noise[@]}" --rect -16,-8,16,8 --size 64x32 --channel f1 \
  --png "$work/remote.png"
if cmp -s "$work/local.png" "$work/remote.png"; then pass; else fail "served noise image differs"; fi
run "$scallop" verify --server "$server" --world valley --rect "$rect"
expect_status 0 "verify of a raster world by name"
if grep -qE '^points in masks +0$' "$work/out"; then pass; else fail "verify output: $(cat "$work/out")"; fi
run "$scallop" info --server "$server" --world valley
if grep -q '^raster *hills: 10 x 8, 8 bit' "$work/out" && grep -q 'radius field *raster' "$work/out"
then pass; else fail "info lacks the raster or the field: $(cat "$work/out")"; fi

# Bad fields: the server names the message's field (exit 1); the client what it can check (2).
run "$scallop" points --server "$server" --seed 1 --radius-raster nope --radius-range 1,2 --rect 0,0,4,4
expect_status 1 "unknown raster"
if grep -q 'INVALID_ARGUMENT: world.radius_field.raster.raster_name' "$work/err"; then pass; else
  fail "unknown raster message: $(cat "$work/err")"; fi
run "$scallop" points --server "$server" --seed 1 --radius-raster hills --raster-pixel 0.01 \
  --radius-range 1,2 --rect 0,0,4,4
if grep -q 'world.radius_field.raster.pixel_size' "$work/err"; then pass; else
  fail "steep raster message: $(cat "$work/err")"; fi
run "$scallop" points --server "$server" --seed 1 --radius-noise 1,4,1 --rect 0,0,4,4
expect_status 2 "steep noise, judged by the client"
if grep -q -- '--radius-noise: field.frequency' "$work/err"; then pass; else fail "$(cat "$work/err")"; fi
run "$scallop" points --server "$server" --world valley --radius-noise 1,4,0.01 --rect 0,0,4,4
expect_status 2 "--world with a field"

# Configs that cannot be served stop scallopd (exit 2) naming the key.
bad_config() {
  local what=$1 key=$2
  printf '%s\n' "listen: 127.0.0.1:0" "$3" >"$work/bad.yaml"
  run "$scallopd" --config "$work/bad.yaml"
  expect_status 2 "$what"
  if grep -qF -- "$key" "$work/err"; then pass; else fail "$what: stderr lacks '$key': $(cat "$work/err")"; fi
}
bad_config "missing raster" "rasters.hills: raster.path" "rasters: {hills: none.png}"
make_png "$work/rgb.png" rgb 4 4
bad_config "colour raster" "rasters.hills: raster:" "rasters: {hills: $work/rgb.png}"
bad_config "unknown raster" "worlds.w.radius_field.raster.raster_name" \
  "worlds: {w: {radius_field: {raster: {raster_name: x, pixel_size: 4, r_min: 1, r_max: 2}}}}"
bad_config "steep noise" "worlds.w.radius_field.noise.frequency" \
  "worlds: {w: {radius_field: {noise: {r_min: 1, r_max: 4, frequency: 1}}}}"
bad_config "typo in a field" "worlds.w.radius_field.noise: unknown key 'frequence'" \
  "worlds: {w: {radius_field: {noise: {r_min: 1, r_max: 4, frequence: 1}}}}"
bad_config "field world on a1" "world.algorithm" \
  "worlds: {w: {algorithm: a1, radius_field: {noise: {r_min: 1, r_max: 2, frequency: 0.01}}}}"
# A layered world's bad layer stops it too, named (cli_layers_remote_test.sh serves good ones).
bad_config "layer with a bad spacing" "worlds.w: world.layers[1].min_distance" \
  "worlds: {w: {layers: [{name: trees, min_distance: 8}, {name: rocks, min_distance: -1}]}}"

report cli_field_remote_test
