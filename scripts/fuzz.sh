#!/usr/bin/env bash
# Fuzzes the readers of untrusted files with libFuzzer (issue 27): OFF, OBJ,
# STL, PLY, MSH, the features JSON and the map file, each for SECONDS
# (default 60), under AddressSanitizer and UndefinedBehaviorSanitizer.
# Seeds come from ../shared/data and, when the Release build exists, from a
# main-job output (MSH and map). Findings are written to build-fuzz/findings/
# and make the script fail.
# With RUNS, each harness runs exactly RUNS inputs from seed 1 instead of
# for SECONDS (what CI does: the same verdict on every run of one commit).
# Usage: scripts/fuzz.sh [SECONDS] [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
limit=(-max_total_time="$seconds")
[ -n "${2:-}" ] && limit=(-runs="$2" -seed=1)
bash scripts/install-deps.sh fuzz
if [ ! -f build-fuzz/build.ninja ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCURVETET_FUZZ=ON \
    -DCURVETET_BUILD_TESTS=OFF -DCURVETET_BUILD_BENCH=OFF >/dev/null
fi
readers=(off obj stl ply msh features map)
cmake --build build-fuzz -j "$(nproc)" --target "${readers[@]/#/fuzz_}"

data=../shared/data
seeds=build-fuzz/seeds
rm -rf "$seeds" && mkdir -p "$seeds"/{off,obj,stl,ply,msh,features,map} build-fuzz/findings
# Small models only: libFuzzer mutates whole inputs.
find "$data" -name '*.off' -size -64k -exec cp {} "$seeds/off/" \;
find "$data" -name '*.json' -exec cp {} "$seeds/features/" \;
/usr/bin/python3 - "$data/good/thingi10k_85770.off" "$seeds" <<'PY'
import struct, sys
lines = [l.split() for l in open(sys.argv[1]) if l.strip() and not l.startswith('#')]
nv, nf = int(lines[1][0]), int(lines[1][1])
V = [tuple(map(float, l[:3])) for l in lines[2:2 + nv]]
F = [tuple(map(int, l[1:4])) for l in lines[2 + nv:2 + nv + nf]]
out = sys.argv[2]
with open(out + "/obj/seed.obj", "w") as f:
    f.writelines("v %r %r %r\n" % v for v in V); f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in F)
with open(out + "/ply/seed.ply", "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
            "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (nv, nf))
    f.writelines("%r %r %r\n" % v for v in V); f.writelines("3 %d %d %d\n" % t for t in F)
with open(out + "/stl/seed.stl", "w") as f:
    f.write("solid seed\n")
    for t in F:
        f.write("facet normal 0 0 0\nouter loop\n" + "".join("vertex %r %r %r\n" % V[i] for i in t) + "endloop\nendfacet\n")
    f.write("endsolid seed\n")
with open(out + "/stl/seed_binary.stl", "wb") as f:
    f.write(b"\0" * 80 + struct.pack("<I", len(F)))
    for t in F:
        f.write(struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *V[i]) for i in t) + b"\0\0")
PY
if [ -x build/app/curvetet ]; then
  tmp=$(mktemp -d)
  build/app/curvetet -q "$data/good/thingi10k_85770.off" --order 2 -o "$seeds/msh/seed.msh" --map "$seeds/map/seed.map" \
    --report "$tmp/report.json" || true
  build/app/curvetet -q "$data/good/thingi10k_85770.off" --order 3 --binary -o "$seeds/msh/seed_binary.msh" || true
  rm -rf "$tmp"
fi

failed=0
for r in "${readers[@]}"; do
  echo "fuzzing the $r reader (${limit[*]})"
  mkdir -p "build-fuzz/corpus/$r"
  if ! build-fuzz/fuzz/fuzz_$r "build-fuzz/corpus/$r" "$seeds/$r" "${limit[@]}" -max_len=65536 \
      -rss_limit_mb=4096 -artifact_prefix="build-fuzz/findings/$r-" -print_final_stats=1 >"build-fuzz/fuzz_$r.log" 2>&1; then
    echo "FINDING in the $r reader: see build-fuzz/fuzz_$r.log and build-fuzz/findings/"
    tail -30 "build-fuzz/fuzz_$r.log"
    failed=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "build-fuzz/fuzz_$r.log" | tr '\n' ' '; echo
  fi
done
exit $failed
