#!/usr/bin/python3
"""Element quality of curvetet's output, measured by the independent validator.

Usage: /usr/bin/python3 bench/quality_table.py [--bin BIN] [--models A.off B.off ...]
           [--features] [--json OUT.json] [--keep DIR] [--timeout SECONDS]

For every model (default: /work/shared/data/good/*.off, smallest file first) runs
  (a) the main job  BIN MODEL.off -o OUT.msh --order 4 --epsilon 0.01 --report OUT.json
      (wall clock), and with --features also the same plus --features
      MODEL.features.json for the models that have one;
  (b) the linear fill  BIN tetrahedralize MODEL.off -o TET.msh --report TET.json;
  (c) /work/shared/tools/validate.py on every output (--input MODEL.off --eps 0.01).
Prints a Markdown table (validator figures: AMIPS of a regular tet = 3, scaled
Jacobian of a regular tet = 1, distances relative to the input's bbox diagonal)
and writes every report and validator JSON to --json. A failed or timed-out run
is recorded in its row, never fatal. Run one instance at a time: the wall clock
is only meaningful on an otherwise quiet machine.
"""
import argparse
import glob
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

DATA = "/work/shared/data/good"
VALIDATE = ["/usr/bin/python3", "/work/shared/tools/validate.py"]


def run(cmd, timeout, log):
    """Run cmd (own process group), return (exit code or 'timeout', wall seconds, stdout)."""
    t0 = time.time()
    with open(log, "w") as err:
        p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=err, text=True, start_new_session=True)
        try:
            out, _ = p.communicate(timeout=timeout)
            rc = p.returncode
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            out, _ = p.communicate()
            rc = "timeout"
    return rc, round(time.time() - t0, 2), out


def load(path):
    try:
        return json.load(open(path))
    except (OSError, ValueError):
        return None


def validate(msh, model, a, log):
    if not os.path.exists(msh):
        return {"exit": "no output"}
    rc, sec, out = run(VALIDATE + [msh, "--input", model, "--eps", "0.01"], a.timeout, log)
    try:
        v = json.loads(out)
    except ValueError:
        v = {}
    v.update(exit=rc, seconds=sec)
    return v


def job(name, cmd, model, a):
    base = os.path.join(a.keep, name)
    cmd = cmd + ["-o", base + ".msh", "--report", base + ".report.json"]
    rc, sec, _ = run(cmd, a.timeout, base + ".log")
    print(f"  {name}: exit {rc}, {sec} s", file=sys.stderr, flush=True)
    r = {"cmd": cmd, "exit": rc, "seconds": sec, "report": load(base + ".report.json")}
    r["validate"] = validate(base + ".msh", model, a, base + ".validate.log")
    print(f"  {name}: validator exit {r['validate']['exit']}", file=sys.stderr, flush=True)
    return r


def fmt(x, spec):
    return "-" if x is None else format(x, spec)


def figures(v):
    q, d = v.get("quality", {}), v.get("distance", {})
    return dict(tets=v.get("n_tets"), bfaces=v.get("topology", {}).get("n_boundary_faces"),
                amax=q.get("amips_curved_max"), amean=q.get("amips_curved_mean"),
                sj=q.get("scaled_jacobian_curved_min"), in2out=d.get("in2out_all_max_rel"),
                out2in=d.get("out2in_max_rel"), gmsh=v.get("valid_gmsh"), ok=v.get("pass_all"))


def optimizer_seconds_per_1000_tets(report):
    """The curved optimization's time per 1000 tets it started from (report)."""
    opt = (report or {}).get("curved_optimization", {})
    if not opt.get("tets_before") or "seconds" not in opt:
        return "-"
    return f"{1000 * opt['seconds'] / opt['tets_before']:.2f}"


def row(name, feat, r, tet):
    m, t = figures(r["validate"]), figures(tet["validate"])
    verdict = {True: "yes", False: "NO", None: "-"}
    return (f"| {name} | {feat} | {fmt(m['tets'], 'd')} | {fmt(m['bfaces'], 'd')} | {fmt(m['amax'], '.4g')} | "
            f"{fmt(m['amean'], '.4g')} | {fmt(m['sj'], '.3g')} | {fmt(m['in2out'], '.2e')} / "
            f"{fmt(m['out2in'], '.2e')} | {r['seconds']:.1f} | {optimizer_seconds_per_1000_tets(r['report'])} | {r['exit']} | {verdict[m['gmsh']]} / "
            f"{verdict[m['ok']]} | {fmt(t['tets'], 'd') if tet['exit'] == 0 else 'exit ' + str(tet['exit'])} | {fmt(t['amax'], '.4g')} | {fmt(t['sj'], '.3g')} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="./build/app/curvetet")
    ap.add_argument("--models", nargs="+")
    ap.add_argument("--features", action="store_true", help="also run MODEL.features.json variants")
    ap.add_argument("--json", help="write all figures here")
    ap.add_argument("--keep", help="output directory (default: a temporary one)")
    ap.add_argument("--timeout", type=float, default=1200, help="seconds per run")
    a = ap.parse_args()
    a.bin = os.path.abspath(a.bin)
    a.keep = a.keep or tempfile.mkdtemp(prefix="quality_table.")
    os.makedirs(a.keep, exist_ok=True)
    models = a.models or sorted(glob.glob(os.path.join(DATA, "*.off")), key=os.path.getsize)
    T0 = time.time()
    meta = {"bin": a.bin, "started": time.strftime("%Y-%m-%d %H:%M:%S %Z"), "loadavg_start": os.getloadavg(),
            "cpus": os.cpu_count(), "order": 4, "epsilon": 0.01, "outputs": a.keep}
    results, rows = {}, []
    for model in models:
        model = os.path.abspath(model)
        name = os.path.basename(model)[:-4]
        print(f"{name}", file=sys.stderr, flush=True)
        main_cmd = [a.bin, model, "--order", "4", "--epsilon", "0.01"]
        res = {"model": model, "plain": job(name, main_cmd, model, a)}
        res["tetrahedralize"] = job(name + ".tet", [a.bin, "tetrahedralize", model], model, a)
        rows.append(row(name, "no", res["plain"], res["tetrahedralize"]))
        feat = model[:-4] + ".features.json"
        if a.features and os.path.exists(feat):
            res["features"] = job(name + ".features", main_cmd + ["--features", feat], model, a)
            rows.append(row(name, "yes", res["features"], res["tetrahedralize"]))
        results[name] = res
        if a.json:  # after every model, so an interrupted sweep keeps what it measured
            meta.update(total_seconds=round(time.time() - T0, 1), loadavg_end=os.getloadavg())
            json.dump({"meta": meta, "models": results}, open(a.json, "w"), indent=1)
    print("| model | features | tets | boundary faces | max AMIPS | mean AMIPS | min scaled J | "
          "Hausdorff/diag in→out / out→in | seconds | optimizer s / 1000 tets | exit | Gmsh valid / validator pass | "
          "tetrahedralize: tets | tetrahedralize: max AMIPS | tetrahedralize: min scaled J |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|")
    print("\n".join(rows))
    print(f"\ntotal {time.time() - T0:.0f} s, outputs in {a.keep}", file=sys.stderr)


if __name__ == "__main__":
    main()
