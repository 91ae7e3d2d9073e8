#!/usr/bin/env bash
# End-to-end harness: runs the curvetet main command on models and prints a
# Markdown table of wall time, peak memory (max resident set size from
# /usr/bin/time, package `time`) and exit code per model.
# Usage: bench/e2e.sh [--verify] [--peer] [--args "EXTRA CURVETET ARGS"] [MESH...]
#   --verify  also write the map and check every output independently:
#             Gmsh's Jacobians and input->boundary distance
#             (tests/pipeline/gmsh_pipeline_check.py) and the map's largest
#             input-vertex displacement (report "map"), both x bbox diagonal
#   --peer    also run Gmsh's own curved meshing of the same model
#             (bench/gmsh_curving.py, order 4, no optimizer): time, tets,
#             elements Gmsh itself finds invalid
#   CURVETET_BIN=program to run (default ./build/app/curvetet)
#   E2E_TIMEOUT=seconds per model (default 1800; exit 124 = timed out)
#   E2E_EPSILON=relative epsilon for --verify (default 0.01, the CLI default)
#   default meshes: every ../shared/data/good/*.off, smallest first.
# Each mesh is written to a temporary directory (kept: its path is printed
# last). Extra columns come from each run's report (--report): input faces,
# output tets, boundary faces and quality (max/mean AMIPS, min scaled
# Jacobian).
set -euo pipefail
cd "$(dirname "$0")/.."
extra="" verify=0 peer=0
while [ $# -gt 0 ]; do
  case "$1" in
    --args) extra="$2"; shift 2 ;;
    --verify) verify=1; shift ;;
    --peer) peer=1; shift ;;
    *) break ;;
  esac
done
meshes=("$@")
if [ ${#meshes[@]} -eq 0 ]; then
  mapfile -t meshes < <(ls -S -r ../shared/data/good/*.off)
fi
bin=${CURVETET_BIN:-./build/app/curvetet}
[ -x "$bin" ] || bash scripts/build.sh curvetet_cli >/dev/null
eps=${E2E_EPSILON:-0.01}
out=$(mktemp -d)
header="| model | input faces | tets | boundary faces | max AMIPS | mean AMIPS | min scaled Jacobian | wall s | peak MiB | exit |"
rule="|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
if [ $verify = 1 ]; then
  header+=" Gmsh check | input→boundary (Gmsh) | map max |"
  rule+="---|---:|---:|"
fi
if [ $peer = 1 ]; then
  header+=" Gmsh curving s | Gmsh tets | Gmsh invalid |"
  rule+="---:|---:|---:|"
fi
echo "$header"
echo "$rule"
for m in "${meshes[@]}"; do
  name=$(basename "$m" .off)
  map_arg=()
  [ $verify = 1 ] && map_arg=(--map "$out/$name.map")
  set +e
  /usr/bin/time -f "%e %M" -o "$out/time" timeout "${E2E_TIMEOUT:-1800}" "$bin" -q "$m" -o "$out/$name.msh" \
    --report "$out/$name.json" "${map_arg[@]}" $extra >/dev/null 2>"$out/$name.log"
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
  line="| $name | $row | $wall | $((kib / 1024)) | $code |"
  if [ $verify = 1 ]; then
    if [ $code = 0 ]; then
      set +e
      /usr/bin/python3 tests/pipeline/gmsh_pipeline_check.py "$out/$name.msh" "$m" "$eps" >"$out/$name.gmsh_check" 2>&1
      gcode=$?
      set -e
      gdist=$(sed -n 's/^distance: .* max \([0-9.e+-]*\), .*/\1/p' "$out/$name.gmsh_check")
      mapmax=$(/usr/bin/python3 -c 'import json,sys; print("%.4g" % json.load(open(sys.argv[1]))["map"]["vertex_to_boundary_max"])' \
        "$out/$name.json" 2>/dev/null || echo "?")
      [ $gcode = 0 ] && gres="ok" || gres="FAIL ($(grep -c '^FAIL' "$out/$name.gmsh_check"))"
      line+=" $gres | ${gdist:-?} | $mapmax |"
    else
      line+=" - | - | - |"
    fi
  fi
  if [ $peer = 1 ]; then
    pj=$(/usr/bin/python3 bench/gmsh_curving.py "$m" --order 4 --timeout "${E2E_PEER_TIMEOUT:-600}" 2>/dev/null | tail -1)
    line+=$(/usr/bin/python3 -c '
import json, sys
try:
    r = json.loads(sys.argv[1])
except Exception:
    print(" ? | ? | ? |"); sys.exit()
if not r.get("finished"):
    # seconds are set only when the time limit stopped it; otherwise Gmsh failed
    print(" >%s | - | - |" % r["seconds"] if "seconds" in r else " failed | - | - |")
else:
    print(" %s | %s | %s |" % (r["seconds"], r["tets"], r["invalid"]))' "$pj")
  fi
  echo "$line"
done
echo
echo "meshes, reports and logs: $out"
