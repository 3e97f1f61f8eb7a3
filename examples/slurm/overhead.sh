#!/bin/bash
# What a tile task costs beyond its share of the render: renders a frame
# whole, then as TILES tiles one process after another (as an array's tasks
# would, one core each), and prints per-task figures from --stats and the
# wall clock. Usage: overhead.sh [voxtrace] (default: voxtrace on PATH).
set -euo pipefail
VOXTRACE=${1:-voxtrace}
TILES=${TILES:-4x4}
SCENE_ARGS=${SCENE_ARGS:---size 250 --seed 7 --width 1920 --height 1080}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
stat() { sed -n "s/^$1: //p" "$2"; }
calc() { awk -v OFMT=%.3f "BEGIN { print $1 }"; } # float arithmetic without bc
now() { date +%s%N; }

# shellcheck disable=SC2086 # SCENE_ARGS is a list of flags
run() { "$VOXTRACE" $SCENE_ARGS --threads 1 --stats "$@" 2>"$dir/stats"; }

t0=$(now); run --out "$dir/full.png"; t1=$(now)
printf 'whole frame: wall %.0f ms, build %.0f ms, render %.0f ms, encode %.0f ms\n' \
  "$(((t1 - t0) / 1000000))" "$(stat build_ms "$dir/stats")" "$(stat render_ms "$dir/stats")" "$(stat encode_ms "$dir/stats")"

count=$(( ${TILES%x*} * ${TILES#*x} ))
walls=0 builds=0 renders=0 encodes=0
for ((i = 0; i < count; i++)); do
  t0=$(now); run --tiles "$TILES" --tile-index "$i" --out "$dir/tile-%t.png"; t1=$(now)
  walls=$(calc "$walls + ($t1 - $t0) / 1000000")
  builds=$(calc "$builds + $(stat build_ms "$dir/stats")")
  renders=$(calc "$renders + $(stat render_ms "$dir/stats")")
  encodes=$(calc "$encodes + $(stat encode_ms "$dir/stats")")
done
"$VOXTRACE" stitch "$dir"/tile-*.png --out "$dir/stitched.png"
cmp "$dir/stitched.png" "$dir/full.png"
per() { calc "($1) / $count"; }
printf '%d tiles, per task: wall %.0f ms = build %.0f + render %.0f + encode %.0f + start and the rest %.0f ms\n' \
  "$count" "$(per "$walls")" "$(per "$builds")" "$(per "$renders")" "$(per "$encodes")" \
  "$(per "$walls - $builds - $renders - $encodes")"
printf 'all tiles: render %.0f ms in sum, overhead (wall - render) %.0f ms in sum; the stitched frame is the whole frame'"'"'s file\n' \
  "$renders" "$(calc "$walls - $renders")"
