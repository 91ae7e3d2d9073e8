#!/usr/bin/env bash
# End-to-end harness: runs the curvetet main command on models and prints a
# Markdown table of wall time, peak memory (max resident set size from
# /usr/bin/time, package `time`) and exit code per model.
# Usage: bench/e2e.sh [--args "EXTRA CURVETET ARGS"] [MESH...]
#   E2E_TIMEOUT=seconds per model (default 1800; exit 124 = timed out)
#   default meshes: every ../shared/data/good/*.off, smallest first.
# Each mesh is written to a temporary directory (kept: its path is printed
# last). Extra columns come from each run's report (--report): input faces, output
# tets, boundary faces and quality (max/mean AMIPS, min scaled Jacobian; when
# the run writes a mesh).
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
echo "| model | input faces | tets | boundary faces | max AMIPS | mean AMIPS | min scaled Jacobian | wall s | peak MiB | exit |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for m in "${meshes[@]}"; do
  name=$(basename "$m" .off)
  set +e
  /usr/bin/time -f "%e %M" -o "$out/time" timeout "${E2E_TIMEOUT:-1800}" "$bin" -q "$m" -o "$out/$name.msh" --report "$out/$name.json" $extra >/dev/null 2>"$out/$name.log"
  code=$?
  set -e
  read -r wall kib < <(tail -1 "$out/time")
  row=$(/usr/bin/python3 - "$out/$name.json" <<'PY' 2>/dev/null || echo "? | - | - | - | - | -"
import json, sys
r = json.load(open(sys.argv[1]))
v = r.get("verification", {})
q = v.get("quality", {})
fmt = lambda x: "-" if x is None else ("%.4g" % x if isinstance(x, float) else str(x))
print(" | ".join(fmt(x) for x in (r["input"]["faces"], v.get("tets"), v.get("boundary_triangles"),
                                     q.get("max_amips"), q.get("mean_amips"), q.get("min_scaled_jacobian"))))
PY
)
  echo "| $name | $row | $wall | $((kib / 1024)) | $code |"
done
echo
echo "meshes, reports and logs: $out"
