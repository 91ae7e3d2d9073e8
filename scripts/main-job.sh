#!/usr/bin/env bash
# The main job on the bundled model: install, build, run; output under out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh build
bash scripts/build.sh curvetet_cli
mkdir -p out
./build/app/curvetet examples/spot.off --report out/spot.report.json
echo "report: out/spot.report.json"
