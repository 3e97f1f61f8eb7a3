#!/usr/bin/env bash
# Intel Embree against voxtrace on the same terrain and the same primary
# rays, one thread (issue 39's anchor). Opt-in, not part of `cargo test`:
#
#   benches/embree/run.sh [SIZE] [ROUNDS]      (defaults: 250, 5)
#
# Needs Debian's Embree 3 (`apt-get install libembree-dev`) and a C
# compiler. Writes the mesh, rays and voxtrace's hits with
# `voxtrace-report embree-input` into target/embree/SIZE, then runs
# Embree's three ways and `voxtrace --threads 1` (default look, then
# --flat) in turn, ROUNDS times (A B A B: the machine's drift hits both),
# and prints each one's median (also into target/embree/SIZE/table.md,
# which `voxtrace-report speed` adds to its tables). Embree's time is tracing only; voxtrace's
# is its whole frame (`render_ms`: rays, walks, shading, pixels).
set -euo pipefail
cd "$(dirname "$0")/../.."
size=${1:-250}
rounds=${2:-5}
dir=target/embree/$size

if [ ! -e /usr/include/embree3/rtcore.h ]; then
  echo "Embree 3 is not installed: apt-get install libembree-dev" >&2
  exit 2
fi
cargo build --release -q -p voxtrace-cli -p voxtrace-report
mkdir -p "$dir"
cc -O2 -Wall -o "$dir/trace" benches/embree/trace.c -lembree3
target/release/voxtrace-report embree-input --size "$size" --out-dir "$dir" >/dev/null

voxtrace_ms() {
  target/release/voxtrace --size "$size" --seed 1 --threads 1 --stats "$@" --out "$dir/frame.png" 2>&1 \
    | awk -F': ' '$1 == "render_ms" { print $2 }'
}

embree=$dir/embree.txt
: >"$embree"
lit=() flat=()
for _ in $(seq "$rounds"); do
  "$dir/trace" "$dir" 1 >>"$embree"
  lit+=("$(voxtrace_ms)")
  flat+=("$(voxtrace_ms --flat)")
done

table=$dir/table.md
exec > >(tee "$table")

median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
rays=$(head -c 8 "$dir/rays.bin" | od -An -tu4 | awk '{ print $1 * $2 }')
triangles=$(head -c 8 "$dir/mesh.bin" | od -An -tu4 | awk '{ print $2 }')
echo "size $size, seed 1, the paper's camera, 1920x1080 ($rays rays), $triangles triangles, one thread, $rounds rounds, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo
echo "| tracer | median ms | rays/s per core | hits differing from voxtrace |"
echo "|---|---|---|---|"
for way in "rtcIntersect1" "rtcIntersect8 (4x2 tiles)" "rtcIntersect16 (4x4 tiles)"; do
  ms=$(median $(grep -F "| $way |" "$embree" | awk -F'|' '{ print $3 }'))
  differ=$(grep -F "| $way |" "$embree" | tail -1 | awk -F'|' '{ print $5 }' | sed 's/^ //; s/ $//')
  echo "| Embree $way, tracing only | $ms | $(awk -v r="$rays" -v m="$ms" 'BEGIN { printf "%.2f M", r / m / 1e3 }') | $differ |"
done
for look in lit flat; do
  if [ "$look" = lit ]; then ms=$(median "${lit[@]}"); name="voxtrace --threads 1, whole frame"; else ms=$(median "${flat[@]}"); name="voxtrace --threads 1 --flat, whole frame"; fi
  echo "| $name | $ms | $(awk -v r="$rays" -v m="$ms" 'BEGIN { printf "%.2f M", r / m / 1e3 }') | (the reference) |"
done
