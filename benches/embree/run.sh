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
#
# Secondary rays too: the occlusion rays of `voxtrace --ao 4` (reach 8,
# written with `embree-input --occlusion 4`), traced by Embree with
# rtcOccluded1/8/16 and unbounded with rtcIntersect1/16 (`trace DIR 1
# secondary`), against voxtrace's marginal cost of `--ao 4`: the
# render_ms of `--ao 4` minus the default look's in the same round,
# divided by the `ao_rays` --stats counts (checked equal to the rays
# written). A second table follows the camera rays'.
#
# CARGO_TARGET_DIR, when set, is where the binaries are built and found.
set -euo pipefail
cd "$(dirname "$0")/../.."
size=${1:-250}
rounds=${2:-5}
dir=target/embree/$size

if [ ! -e /usr/include/embree3/rtcore.h ]; then
  echo "Embree 3 is not installed: apt-get install libembree-dev" >&2
  exit 2
fi
bin=${CARGO_TARGET_DIR:-target}/release
cargo build --release -q -p voxtrace-cli -p voxtrace-report
mkdir -p "$dir"
cc -O2 -Wall -o "$dir/trace" benches/embree/trace.c -lembree3 -lm
"$bin/voxtrace-report" embree-input --size "$size" --occlusion 4 --out-dir "$dir" >/dev/null

# `render_ms ao_rays` of one frame.
voxtrace_stats() {
  "$bin/voxtrace" --size "$size" --seed 1 --threads 1 --stats "$@" --out "$dir/frame.png" 2>&1 \
    | awk -F': ' '$1 == "render_ms" { ms = $2 } $1 == "ao_rays" { ao = $2 } END { print ms, ao + 0 }'
}
voxtrace_ms() { voxtrace_stats "$@" | cut -d' ' -f1; }

embree=$dir/embree.txt secondary=$dir/embree-secondary.txt
: >"$embree"
: >"$secondary"
lit=() flat=() ao_extra=() ao_rays=
for _ in $(seq "$rounds"); do
  "$dir/trace" "$dir" 1 >>"$embree"
  flat+=("$(voxtrace_ms --flat)")
  plain=$(voxtrace_ms)
  lit+=("$plain")
  read -r ao_ms ao_rays < <(voxtrace_stats --ao 4)
  ao_extra+=("$(awk -v a="$ao_ms" -v p="$plain" 'BEGIN { printf "%.3f", a - p }')")
  "$dir/trace" "$dir" 1 secondary >>"$secondary"
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

# Secondary rays: the occlusion rays of the camera rays' hits.
read -r written unsent < <(od -An -tu4 -N16 "$dir/occlusion.bin" | awk '{ print $1, $4 }')
if [ "$ao_rays" != "$((written + unsent))" ]; then
  echo "voxtrace --ao 4 traced $ao_rays occlusion rays, embree-input wrote $written (+ $unsent that cannot leave their face)" >&2
  exit 1
fi
echo
echo "secondary rays: the $written occlusion rays of \`voxtrace --ao 4\` (4 a hit, reach 8; voxtrace --stats counts the same $ao_rays), packets of 8 or 16 as they come, $(grep -m1 '^occlusion rays' "$secondary" | sed 's/.*voxtrace: //')"
echo
echo "| tracer | median ms | rays/s per core | answers differing from voxtrace |"
echo "|---|---|---|---|"
for way in "rtcOccluded1 (to the reach)" "rtcOccluded8 (to the reach)" "rtcOccluded16 (to the reach)" \
  "rtcIntersect1 (unbounded)" "rtcIntersect16 (unbounded)"; do
  ms=$(median $(grep -F "| $way |" "$secondary" | awk -F'|' '{ print $3 }'))
  differ=$(grep -F "| $way |" "$secondary" | tail -1 | awk -F'|' '{ print $5 }' | sed 's/^ //; s/ $//')
  echo "| Embree $way, tracing only | $ms | $(awk -v r="$written" -v m="$ms" 'BEGIN { printf "%.2f M", r / m / 1e3 }') | $differ |"
done
ms=$(median "${ao_extra[@]}")
echo "| voxtrace --threads 1 --ao 4, marginal (render_ms minus the default look's) | $ms | $(awk -v r="$ao_rays" -v m="$ms" 'BEGIN { printf "%.2f M (%.0f ns a ray)", r / m / 1e3, m * 1e6 / r }') | (the reference) |"
