#!/usr/bin/env bash
# The main job on the bundled model: install, build, run; output under out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh build
bash scripts/build.sh curvetet_cli
mkdir -p out
./build/app/curvetet examples/spot.off -o out/spot.msh --vtu out/spot.vtu --report out/spot.report.json
./build/app/curvetet check out/spot.msh --input examples/spot.off
echo "wrote out/spot.msh (Gmsh 4.1, order 4), out/spot.vtu (ParaView), out/spot.report.json"
