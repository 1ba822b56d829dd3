#!/bin/bash
# Reproduces docs/results/roi: `occlude propose` on a-bite-3shape and b-open-3shape with the
# region of interest on and off, at the examples' bounds ("default") and at narrower ones
# ("narrow": translations +-1 mm, b-open's tz kept at [-2, 1], rotations +-2 deg).
# Usage (from the repository root, after building): docs/results/roi/run.sh [WORK_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../../.." && pwd)
work=${1:-/tmp/occlude-roi}
data=$(cd "$root/../shared/data" && pwd)
mkdir -p "$work"
for c in a-bite-3shape b-open-3shape; do
  for b in default narrow; do
    for roi in true false; do
      f="$work/$c-$b-roi-$roi.toml"
      sed "s#\.\./\.\./shared/data#$data#; s#^folder = .*#folder = \"$work/out-$c-$b-$roi\"#" \
        "$root/examples/$c.toml" > "$f"
      sed -i "s#^\[accuracy\]#[accuracy]\nregion_of_interest = $roi#" "$f"
      if [ "$b" = narrow ]; then
        sed -i 's#^tx_mm = .*#tx_mm = [-1.0, 1.0]#; s#^ty_mm = .*#ty_mm = [-1.0, 1.0]#; s#^rx_deg = .*#rx_deg = [-2.0, 2.0]#; s#^ry_deg = .*#ry_deg = [-2.0, 2.0]#; s#^rz_deg = .*#rz_deg = [-2.0, 2.0]#' "$f"
        if [ "$c" = a-bite-3shape ]; then sed -i 's#^tz_mm = .*#tz_mm = [-1.0, 1.0]#' "$f";
        else sed -i 's#^tz_mm = .*#tx_mm = [-1.0, 1.0]\nty_mm = [-1.0, 1.0]\ntz_mm = [-2.0, 1.0]#' "$f"; fi
      fi
      /usr/bin/time -v "$root/build/bin/occlude" propose "$f" > "$work/$c-$b-roi-$roi.stdout" 2> "$work/$c-$b-roi-$roi.stderr"
    done
  done
done
cd "$work" && python3 "$root/docs/results/roi/compare.py"
