#!/usr/bin/env bash
# Makes the spectral figures of docs/quality.md with `scallop analyze`, and
# prints the numbers the text quotes. About 12 minutes of one core, most of it
# Mitchell's best candidate (O(N^2) per set). Usage, from the repository root
# after a Release build: scripts/make-quality-figures.sh [path/to/scallop]
set -euo pipefail

scallop=${1:-build/client/scallop}
images=docs/images
mkdir -p "$images"

# The paper's setup: 100 sets of about 2000 points. A 50 d x 50 d torus holds
# 1750 (dart throwing) to 2130 (A3) points; frequencies up to 2 cycles per d.
square=(--domain 0,0,50,50 --torus --sets 100 --max-frequency 100)

echo "== Figure 4: radial power of A1, A2 and A3"
"$scallop" analyze "${square[@]}" --algorithm a1,a2,a3 \
  --png "$images/periodogram-a1-a2-a3.png" --plot "$images/radial-a1-a2-a3.svg"

echo "== Figure 5: dart throwing (exhaustive), best candidate and A3"
"$scallop" analyze "${square[@]}" --algorithm dart,best-candidate,a3 --dart-exhaustive \
  --png "$images/periodogram-dart-best-a3.png" --plot "$images/radial-dart-best-a3.svg"

# Seams: 8 d windows of worlds (d = 1, regions 16 d) inside region (0, 0),
# across the seam x = 16 and on the corner at the origin; one window of each
# per world, 400 worlds (seeds 1..400).
for algorithm in a3 a1; do
  echo "== Seams, $algorithm worlds"
  "$scallop" analyze --algorithm "$algorithm" --sets 400 \
    --rect 4,4,12,12 --rect 12,4,20,12 --rect -4,-4,4,4 --label interior,seam,corner \
    --png "$images/periodogram-seams-$algorithm.png" --plot "$images/radial-seams-$algorithm.svg"
done
# Layered worlds: the forest's layers one after another (the plane's window and a bounded
# square) against Wei's joint multi-class darts, and each spacing alone by A3 and by dart
# throwing; 16 sets of a 256 x 256 square.
forest=(--seed 1 --layer trees=8 --layer bushes=3 --layer rocks=1.5 --sets 16)
echo "== Layers, the plane's window"
"$scallop" analyze "${forest[@]}" --rect 0,0,256,256
for algorithm in a3 wei; do
  echo "== Layers on a bounded square, $algorithm"
  "$scallop" analyze "${forest[@]}" --domain 0,0,256,256 --algorithm "$algorithm"
done
for d in 8 3 1.5; do
  echo "== One class of spacing $d, A3 and dart throwing"
  "$scallop" analyze --seed 1 --sets 16 --domain 0,0,256,256 --min-distance "$d" --algorithm a3,dart
done
ls -l "$images"
