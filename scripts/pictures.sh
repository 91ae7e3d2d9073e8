#!/usr/bin/env bash
# Regenerates the README pictures (docs/img/*.png) headlessly: runs the main
# job on the bundled model with --vtu and a JSON --map, carries the boundary
# node coordinates to the input vertices through the map (`curvetet
# transfer`: the images φ(v) on the curved boundary), then renders with
# matplotlib's Agg backend (scripts/pictures.py); the animation example's
# twist (`curvetet deform`) too.
# Usage: scripts/pictures.sh [MODEL.off] [EPSILON]
set -euo pipefail
cd "$(dirname "$0")/.."
model=${1:-examples/spot.off}
epsilon=${2:-0.01}
bash scripts/install-deps.sh docs
bash scripts/build.sh curvetet_cli
work=out/pictures
mkdir -p "$work" docs/img
./build/app/curvetet -q "$model" -o "$work/mesh.msh" --vtu "$work/mesh.vtu" --map "$work/map.json" --epsilon "$epsilon"
/usr/bin/python3 - "$work/map.json" "$work/nodes.csv" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
with open(sys.argv[2], "w") as f:
    f.write("px,py,pz\n")
    for p in m["boundary"]["nodes"]:
        f.write("%.17g,%.17g,%.17g\n" % tuple(p))
PY
./build/app/curvetet -q transfer "$work/map.json" "$work/nodes.csv" -o "$work/images.csv" --to input
./build/app/curvetet -q deform "$work/map.json" -o "$work/twisted.off" --coarse-output "$work/twisted_coarse.off" --twist 60
/usr/bin/python3 scripts/pictures.py "$work/map.json" "$work/mesh.vtu" "$work/images.csv" docs/img \
  --deformed "$work/twisted.off" "$work/twisted_coarse.off"
