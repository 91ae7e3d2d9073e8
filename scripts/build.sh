#!/usr/bin/env bash
# Configures (once) and builds curvetet in Release under build/.
# Usage: build.sh [targets...]   (default: everything)
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build/build.ninja ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build build -j "$(nproc)" ${1:+--target "$@"}
