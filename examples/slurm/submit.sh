#!/bin/bash
# Submits the tile array and the stitch job that runs once every tile has
# succeeded; prints the two job ids. Options go to the array's sbatch
# (for example --array=0-3 with TILES=2x2, or --cpus-per-task=8).
# Settings come from the environment: VOXTRACE, TILES, OUT_DIR, FRAME,
# SCENE_ARGS (see tiles.sbatch and stitch.sbatch).
set -euo pipefail
here=$(dirname "$0")
array=$(sbatch --parsable "$@" "$here/tiles.sbatch")
array=${array%%;*} # --parsable prints id[;cluster]
stitch=$(sbatch --parsable --dependency=afterok:"$array" --kill-on-invalid-dep=yes "$here/stitch.sbatch")
echo "$array"
echo "${stitch%%;*}"
