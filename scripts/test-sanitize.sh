#!/usr/bin/env bash
# Builds everything with AddressSanitizer and UndefinedBehaviorSanitizer
# (g++, -DCURVETET_SANITIZE=ON, under build-sanitize/) and runs the whole test
# suite there (issue 27). A sanitizer report fails the test that triggers it.
# Takes about 4x the plain suite's time on 2 cores, so CI does not run it.
# Usage: scripts/test-sanitize.sh [ctest arguments, e.g. -L io]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh test
if [ ! -f build-sanitize/build.ninja ]; then
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCURVETET_SANITIZE=ON \
    -DCURVETET_BUILD_BENCH=OFF >/dev/null
fi
cmake --build build-sanitize -j "$(nproc)"
# TBB's worker threads are leak-checked too; every finding aborts the test.
export ASAN_OPTIONS=abort_on_error=1:detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" --timeout 3600 "$@"
