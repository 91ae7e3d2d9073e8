#!/usr/bin/env bash
# End-to-end harness: runs the curvetet main command on models and prints a
# Markdown table of wall time, peak memory and exit code per model.
# Usage: bench/e2e.sh [--args "EXTRA CURVETET ARGS"] [MESH...]
#   default meshes: every ../shared/data/good/*.off, smallest first.
# Extra columns come from each run's report (--report): faces of the input.
set -euo pipefail
cd "$(dirname "$0")/.."
extra=""
if [ "${1:-}" = "--args" ]; then extra="$2"; shift 2; fi
meshes=("$@")
if [ ${#meshes[@]} -eq 0 ]; then
  mapfile -t meshes < <(ls -S -r ../shared/data/good/*.off)
fi
bin=./build/app/curvetet
[ -x "$bin" ] || bash scripts/build.sh curvetet_cli >/dev/null
out=$(mktemp -d)
echo "| model | input faces | wall s | peak MiB | exit |"
echo "|---|---:|---:|---:|---:|"
for m in "${meshes[@]}"; do
  name=$(basename "$m" .off)
  set +e
  /usr/bin/time -f "%e %M" -o "$out/time" "$bin" -q "$m" --report "$out/$name.json" $extra >/dev/null 2>"$out/$name.log"
  code=$?
  set -e
  read -r wall kib < <(tail -1 "$out/time")
  faces=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['input']['faces'])" "$out/$name.json" 2>/dev/null || echo "?")
  echo "| $name | $faces | $wall | $((kib / 1024)) | $code |"
done
