#!/usr/bin/env bash
# Compares two `voxtrace` binaries frame by frame: for each frame of the
# grid below, runs the baseline and the new binary in turn (A B A B ...),
# keeps the best of RUNS `render_ms` and `build_ms` each (from `--stats`),
# and checks that the two PNGs are byte-identical.
#
#   git worktree add ../base REV
#   (cd ../base && CARGO_TARGET_DIR=../base-target cargo build --release -p voxtrace-cli)
#   cargo build --release -p voxtrace-cli
#   benches/compare.sh ../base-target/release/voxtrace target/release/voxtrace [RUNS]
#
# Prints a markdown table. The frames are the speed issue's: 1920x1080,
# 2 threads, seed 1, the paper's camera.
set -euo pipefail

base=${1:?usage: compare.sh BASE_BINARY NEW_BINARY [RUNS]}
new=${2:?usage: compare.sh BASE_BINARY NEW_BINARY [RUNS]}
runs=${3:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# One `key: value` line of --stats output.
stat() { sed -n "s/^$1: //p" <<<"$2"; }
min() { awk -v a="$1" -v b="$2" 'BEGIN { print (a < b ? a : b) }'; }

row() {
  local label=$1
  shift
  local base_render=inf new_render=inf base_build=inf new_build=inf out bytes=""
  for _ in $(seq "$runs"); do
    out=$("$base" "$@" --stats --out "$tmp/base.png" 2>&1)
    base_render=$(min "$base_render" "$(stat render_ms "$out")")
    base_build=$(min "$base_build" "$(stat build_ms "$out")")
    out=$("$new" "$@" --stats --out "$tmp/new.png" 2>&1)
    new_render=$(min "$new_render" "$(stat render_ms "$out")")
    new_build=$(min "$new_build" "$(stat build_ms "$out")")
    bytes=$(stat storage_bytes "$out")
  done
  local same=identical
  cmp -s "$tmp/base.png" "$tmp/new.png" || same=DIFFERENT
  awk -v l="$label" -v br="$base_render" -v nr="$new_render" -v bb="$base_build" \
    -v nb="$new_build" -v by="$bytes" -v s="$same" 'BEGIN {
      printf "| %s | %.1f | %.1f | %.2fx | %.0f | %.0f | %s | %s |\n", l, br, nr, br / nr, bb, nb, by, s
    }'
}

common=(--seed 1 --threads 2 --width 1920 --height 1080)
echo "| frame | base render ms | new render ms | speedup | base build ms | new build ms | storage bytes | PNG |"
echo "|---|---|---|---|---|---|---|---|"
for size in 50 100 250; do
  row "octree $size" --backend octree --size "$size" "${common[@]}"
done
row "octree 2048" --backend octree --size 2048 "${common[@]}"
for size in 50 100 250; do
  row "dense $size" --backend dense --size "$size" "${common[@]}"
done
row "octree 250 --shadows --ao 4" --backend octree --size 250 --shadows --ao 4 "${common[@]}"
row "octree 250 --flat" --backend octree --size 250 --flat "${common[@]}"
