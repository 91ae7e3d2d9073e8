#!/usr/bin/env bash
# curvetet against the reference implementation's figures on this machine
# (issue 28): runs the main job several times on one model and prints wall
# and CPU time per run, their ratios to the reference's, and the validator's
# figures of the last output (quality and the two-sided distance, so a
# speed-up that costs quality or epsilon shows).
#
# Usage: bench/vs_reference.sh [--runs N] [--epsilon E] [--threads T]
#                              [--ref-wall S] [--ref-cpu S] [MESH]
#   defaults: 3 runs, epsilon 0.01, all threads, bunny_libigl.off, and the
#   reference implementation's bunny figures at epsilon 1 % (246.5 s wall,
#   260 s CPU, its own output conversion included; measured 2026-12 on the
#   2-core project machine). The reference code is not needed.
#   CURVETET_BIN=program to run (default ./build/app/curvetet)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=3 eps=0.01 threads=0 ref_wall=246.5 ref_cpu=260
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --epsilon) eps="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --ref-wall) ref_wall="$2"; shift 2 ;;
    --ref-cpu) ref_cpu="$2"; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) break ;;
  esac
done
mesh=${1:-../shared/data/good/bunny_libigl.off}
bin=${CURVETET_BIN:-./build/app/curvetet}
[ -x "$bin" ] || bash scripts/build.sh curvetet_cli >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "model $(basename "$mesh"), epsilon $eps, threads ${threads/#0/all}, $runs runs; reference: $ref_wall s wall, $ref_cpu s CPU"
echo "| run | wall s | CPU s | wall ratio | CPU ratio | tets | boundary faces |"
echo "|---:|---:|---:|---:|---:|---:|---:|"
walls=() cpus=()
for i in $(seq 1 "$runs"); do
  /usr/bin/time -f "%e %U %S" -o "$out/time" "$bin" "$mesh" -o "$out/out.msh" --epsilon "$eps" --threads "$threads" \
    --report "$out/report.json" >/dev/null 2>"$out/log" || { cat "$out/log" >&2; exit 1; }
  read -r wall user sys <"$out/time"
  cpu=$(/usr/bin/python3 -c "print(f'{$user + $sys:.2f}')")
  counts=$(/usr/bin/python3 -c "
import json; r = json.load(open('$out/report.json'))['verification']
print(r['tets'], r['boundary_triangles'])")
  walls+=("$wall") cpus+=("$cpu")
  /usr/bin/python3 -c "
w, c = $wall, $cpu
t, b = '$counts'.split()
print(f'| $i | {w:.2f} | {c:.2f} | {$ref_wall / w:.1f}x | {$ref_cpu / c:.1f}x | {t} | {b} |')"
done
walls_csv=$(IFS=,; echo "${walls[*]}") cpus_csv=$(IFS=,; echo "${cpus[*]}")
/usr/bin/python3 -c "
import statistics as s
w = s.median([$walls_csv]); c = s.median([$cpus_csv])
print(f'median: {w:.2f} s wall ({$ref_wall / w:.1f}x), {c:.2f} s CPU ({$ref_cpu / c:.1f}x)')"
echo "validator on the last output (max AMIPS / mean AMIPS / min scaled Jacobian / distance both ways, / diagonal):"
/usr/bin/python3 ../shared/tools/validate.py "$out/out.msh" --input "$mesh" --eps "$eps" >"$out/v.json" 2>/dev/null || true
/usr/bin/python3 -c "
import json; v = json.load(open('$out/v.json'))
q, d = v['quality'], v['distance']
print(f\"  {q['amips_curved_max']:.2f} / {q['amips_curved_mean']:.2f} / {q['scaled_jacobian_curved_min']:.4g} / \"
      f\"{max(d['in2out_all_max_rel'], d['out2in_max_rel']):.4g}\", 'pass' if v.get('pass_all') else 'FAIL')
raise SystemExit(0 if v.get('pass_all') else 1)"
