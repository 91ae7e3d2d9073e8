#!/usr/bin/env bash
# Installs curvetet's Debian 12 packages. Idempotent and fast when they are
# already there (no apt-get call at all). Usage: install-deps.sh [build|test|bench|docs|fuzz]
set -euo pipefail
build_pkgs=(cmake ninja-build g++ libcgal-dev libeigen3-dev libgmp-dev libmpfr-dev libtbb-dev
            libspdlog-dev libfmt-dev libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev)
test_pkgs=(gmsh python3-gmsh python3-meshio python3-numpy python3-dolfinx)
bench_pkgs=(tetgen time)
docs_pkgs=(python3-numpy python3-matplotlib)  # scripts/pictures.sh
fuzz_pkgs=(clang libclang-rt-14-dev)          # scripts/fuzz.sh, scripts/test-sanitize.sh

pkgs=("${build_pkgs[@]}")
case "${1:-build}" in
  build) ;;
  test) pkgs+=("${test_pkgs[@]}") ;;
  bench) pkgs+=("${test_pkgs[@]}" "${bench_pkgs[@]}") ;;
  docs) pkgs+=("${docs_pkgs[@]}") ;;
  fuzz) pkgs+=("${fuzz_pkgs[@]}") ;;
  *) echo "usage: $0 [build|test|bench|docs|fuzz]" >&2; exit 2 ;;
esac

missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
