#!/usr/bin/python3
"""Scale benchmark (issue 28, item 4): time and peak memory of the main
command against input size, with least-squares growth exponents.

Generates the ellipsoid (radii 1, 0.7, 0.5) at about two sizes per decade
with bench/make_ellipsoid.py (octahedron 8 * 4^L and icosahedron 20 * 4^L
faces) into a temp dir, runs

    curvetet MESH -o OUT.msh --report R.json     (defaults: P = 4, eps 1 %)

under `/usr/bin/time -v` for each, and records wall time, user + sys CPU
time, peak RSS (time's "Maximum resident set size"), the report's per-stage
`timings_s` and the output tet count. Real models given on the command line
are run the same way (plotted, not fitted). A run that fails (nonzero exit,
timeout, killed for memory) is recorded with its exit code and reason and
the benchmark moves on.

Writes a JSON list of records and a log-log plot (time and peak memory
against input faces, fitted exponents in the legend). The exponents are
fitted (least squares on log-log) over the ellipsoids with >= --fit-min
faces (default 8192) on CPU time, wall time, peak RSS and on the stages
'shell', 'coarsen' and 'curved optimization' (report timings, wall clock),
and again over the large sizes only (>= --fit-min2, default 81920). Each
record also carries the coarsening's steps parsed from curvetet's log
(`coarsen_steps`: first collapse pass, later collapse passes, smoothing,
refits).
The plot is drawn as SVG by hand (no matplotlib needed) and rasterized to
PNG through librsvg/cairo (ctypes); without them the SVG is written instead.

usage:
  bench/scale.py [--max-faces N] [--faces N,N,...] [--timeout S]
                 [--json OUT.json] [--png OUT.png] [--resume]
                 [--curvetet PATH] [--threads N] [--keep DIR] [MODEL.off ...]
  bench/scale.py --plot-only RESULTS.json [--png OUT.png]

The binary is copied into the work dir first, so a rebuild of the tree
during the benchmark does not change it mid-series (its sha256 is recorded).

Session 31 (docs/scale.md), default threads, then a single-thread series
appended to the same JSON (runs named *_threads1):
  /usr/bin/python3 bench/scale.py --max-faces 1400000 \\
      --json bench/scale_session31.json --png docs/img/scale.png \\
      ../shared/data/good/cheese_genus133.off \\
      ../shared/data/good/armadillo_cgal.off ../shared/data/good/nefertiti.off
  /usr/bin/python3 bench/scale.py --resume --threads 1 --min-faces 8192 \\
      --max-faces 1400000 --json bench/scale_session31.json --png docs/img/scale.png
  /usr/bin/python3 bench/scale.py --plot-only bench/scale_session31.json --png docs/img/scale.png
"""
import argparse
import ctypes
import ctypes.util
import datetime
import hashlib
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import make_ellipsoid  # noqa: E402

REPO = os.path.dirname(HERE)
STAGES = ["shell", "coarsen", "curved optimization"]
FIT_KEYS = [  # (record key or ("stage", name), label)
    ("cpu_s", "CPU (user+sys)"),
    ("wall_s", "wall"),
    (("stage", "shell"), "stage shell"),
    (("stage", "coarsen"), "stage coarsen"),
    (("stage", "curved optimization"), "stage curved optimization"),
    ("peak_rss_mib", "peak RSS"),
]


# ----------------------------------------------------------------- sizes
def ellipsoid_sizes(min_faces, max_faces):
    """(faces, base, level) of both bases within [min_faces, max_faces]."""
    out = []
    for base in make_ellipsoid.BASES:
        level = 0
        while True:
            n = make_ellipsoid.face_count(level, base)
            if n > max_faces:
                break
            if n >= min_faces:
                out.append((n, base, level))
            level += 1
    return sorted(out)


# ----------------------------------------------------------------- running
def wall_seconds(hms):
    s = 0.0
    for p in hms.split(":"):
        s = 60 * s + float(p)
    return s


TIME_V_FIELDS = [  # (key, pattern, conversion)
    ("user_s", r"User time \(seconds\): ([\d.]+)", float),
    ("sys_s", r"System time \(seconds\): ([\d.]+)", float),
    ("peak_rss_mib", r"Maximum resident set size \(kbytes\): (\d+)", lambda k: int(k) / 1024.0),
    ("time_wall_s", r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", wall_seconds),
    ("exit_status", r"Exit status: (-?\d+)", int),
    ("signal", r"Command terminated by signal (\d+)", int),
]


def parse_time_v(text):
    """Fields of GNU time -v output."""
    out = {}
    for key, pattern, convert in TIME_V_FIELDS:
        m = re.search(pattern, text)
        if m:
            out[key] = convert(m.group(1))
    return out


STEP_RE = re.compile(r"coarsen round (\d+) (\w+): (\d+) -> (\d+) faces, (\d+)/(\d+) accepted, ([\d.]+) s")


def coarsen_steps(log_text):
    """The coarsening's steps from curvetet's info log (wall seconds): the first
    collapse pass on the dense input, the later collapse passes on the coarse
    surface, smoothing, refits, the rest (flips, splits)."""
    steps = [(m.group(2), int(m.group(6)), float(m.group(7))) for m in STEP_RE.finditer(log_text)]
    if not steps:
        return None
    out = {"steps": len(steps), "first_collapse_s": steps[0][2], "first_collapse_attempts": steps[0][1],
           "later_collapse_s": 0.0, "later_collapse_attempts": 0, "smooth_s": 0.0, "refit_s": 0.0, "other_s": 0.0}
    for kind, attempts, sec in steps[1:]:
        if kind == "collapse":
            out["later_collapse_s"] += sec
            out["later_collapse_attempts"] += attempts
        elif kind in ("smooth", "refit"):
            out[kind + "_s"] += sec
        else:
            out["other_s"] += sec
    return {k: round(v, 3) if isinstance(v, float) else v for k, v in out.items()}


def loadavg():
    try:
        return [float(x) for x in open("/proc/loadavg").read().split()[:3]]
    except OSError:
        return None


def mesh_counts(path):
    """(vertices, faces) read from an OFF header or counted in an OBJ; (None, None)
    for other formats (the run's report gives the face count then)."""
    try:
        if path.lower().endswith(".obj"):
            nv = nf = 0
            with open(path, errors="replace") as f:
                for line in f:
                    nv += line.startswith("v ")
                    nf += line.startswith("f ")
            return nv, nf
        with open(path, errors="replace") as f:
            head = f.readline().strip()
            if not head.startswith("OFF"):
                return None, None
            line = head[3:].strip() if len(head) > 3 else f.readline()
            while not line.strip() or line.lstrip().startswith("#"):
                line = f.readline()
            nv, nf = (int(x) for x in line.split()[:2])
        return nv, nf
    except (OSError, ValueError):
        return None, None


def run_one(curvetet, mesh, workdir, name, timeout, threads, keep_output):
    out_msh = os.path.join(workdir, name + ".msh")
    report = os.path.join(workdir, name + ".report.json")
    timefile = os.path.join(workdir, name + ".time")
    logfile = os.path.join(workdir, name + ".log")
    for p in (out_msh, report, timefile):
        if os.path.exists(p):
            os.remove(p)
    cmd = [curvetet, mesh, "-o", out_msh, "--report", report]
    if threads is not None:
        cmd += ["--threads", str(threads)]
    rec = {"command": " ".join(["curvetet", os.path.basename(mesh), "-o", "OUT.msh", "--report", "R.json"]
                               + (["--threads", str(threads)] if threads is not None else [])),
           "loadavg_before": loadavg()}
    t0 = time.monotonic()
    timed_out = False
    with open(logfile, "w") as log:
        proc = subprocess.Popen(["/usr/bin/time", "-v", "-o", timefile] + cmd,
                                stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        try:
            rc = proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
            os.killpg(proc.pid, signal.SIGKILL)  # our own session: time and curvetet
            rc = proc.wait()
    rec["wall_measured_s"] = time.monotonic() - t0
    rec["loadavg_after"] = loadavg()
    tv = parse_time_v(open(timefile).read()) if os.path.exists(timefile) else {}
    rec["user_s"] = tv.get("user_s")
    rec["sys_s"] = tv.get("sys_s")
    rec["cpu_s"] = (tv["user_s"] + tv["sys_s"]) if "user_s" in tv and "sys_s" in tv else None
    rec["peak_rss_mib"] = tv.get("peak_rss_mib")
    rec["wall_s"] = tv.get("time_wall_s", rec["wall_measured_s"])
    rec["exit_code"] = rc
    if timed_out:
        rec["reason"] = f"timeout after {timeout} s (killed)"
        rec["exit_code"] = None
    elif rc != 0:
        sig = tv.get("signal")
        if sig is None and rc < 0:
            sig = -rc
        tail = open(logfile, errors="replace").read()[-2000:]
        if sig == signal.SIGKILL or "bad_alloc" in tail or "out of memory" in tail.lower():
            rec["reason"] = f"out of memory? (signal {sig}, exit {rc})" if sig else f"out of memory (exit {rc})"
        elif sig:
            rec["reason"] = f"killed by signal {sig}"
        else:
            last = [ln for ln in tail.splitlines() if ln.strip()]
            rec["reason"] = f"exit {rc}: " + (last[-1][:300] if last else "")
    else:
        rec["reason"] = None
    rec["coarsen_steps"] = coarsen_steps(open(logfile, errors="replace").read())
    if os.path.exists(report):
        try:
            r = json.load(open(report))
            rec["timings_s"] = r.get("timings_s")
            rec["output_tets"] = r.get("verification", {}).get("tets",
                                      r.get("curved_optimization", {}).get("tets_after"))
            rec["boundary_triangles"] = r.get("assembly", {}).get("boundary_triangles")
            rec["coarse_faces"] = r.get("coarsen", {}).get("faces_after")
            rec["optimization_rounds"] = r.get("curved_optimization", {}).get("rounds")
            rec["descent_iterations"] = r.get("curved_optimization", {}).get("descent", {}).get("iterations")
            rec["report_exit_code"] = r.get("input", {}).get("exit_code")
            rec["report_faces"] = r.get("input", {}).get("faces")
        except (ValueError, OSError) as e:
            rec["report_error"] = str(e)
    if not keep_output and os.path.exists(out_msh):
        os.remove(out_msh)
    return rec


def machine_info(curvetet):
    info = {"nproc": os.cpu_count(), "date": datetime.datetime.now().isoformat(timespec="seconds")}
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                info["cpu"] = line.split(":", 1)[1].strip()
                break
        for line in open("/proc/meminfo"):
            if line.startswith("MemTotal"):
                info["mem_total_mib"] = int(line.split()[1]) // 1024
                break
    except OSError:
        pass
    try:
        info["git_head"] = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"],
                                          capture_output=True, text=True).stdout.strip()
        info["binary"] = curvetet
        info["binary_mtime"] = datetime.datetime.fromtimestamp(os.path.getmtime(curvetet)).isoformat(timespec="seconds")
        with open(curvetet, "rb") as f:
            info["binary_sha256"] = hashlib.sha256(f.read()).hexdigest()
        info["version"] = subprocess.run([curvetet, "--version"], capture_output=True, text=True).stdout.strip()
    except OSError:
        pass
    return info


# ----------------------------------------------------------------- fitting
def value(rec, key):
    if isinstance(key, tuple):
        v = (rec.get("timings_s") or {}).get(key[1])
    else:
        v = rec.get(key)
    return v if isinstance(v, (int, float)) and v > 0 else None


def fit_loglog(xs, ys):
    """Least-squares y = c x^k on log-log; returns (k, c, r2, standard error of k)."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    n = len(lx)
    mx, my = sum(lx) / n, sum(ly) / n
    sxx = sum((a - mx) ** 2 for a in lx)
    sxy = sum((a - mx) * (b - my) for a, b in zip(lx, ly))
    k = sxy / sxx
    c = math.exp(my - k * mx)
    ss_res = sum((b - (my + k * (a - mx))) ** 2 for a, b in zip(lx, ly))
    ss_tot = sum((b - my) ** 2 for b in ly)
    se = math.sqrt(ss_res / (n - 2) / sxx) if n > 2 else float("nan")
    return k, c, (1 - ss_res / ss_tot) if ss_tot > 0 else 1.0, se


def fitted_records(records, fit_min):
    return sorted((r for r in records if r.get("kind") == "ellipsoid" and r.get("exit_code") == 0
                   and r["faces"] >= fit_min), key=lambda r: r["faces"])


def fits(records, fit_min):
    recs = fitted_records(records, fit_min)
    out = {}
    for key, label in FIT_KEYS:
        pts = [(r["faces"], value(r, key)) for r in recs if value(r, key)]
        if len(pts) >= 2:
            k, c, r2, se = fit_loglog([p[0] for p in pts], [p[1] for p in pts])
            out[label] = {"exponent": k, "stderr": se, "coefficient": c, "r2": r2, "points": len(pts),
                          "faces_min": pts[0][0], "faces_max": pts[-1][0]}
    if len(recs) >= 2:  # what n log n would give over the same sizes
        xs = [r["faces"] for r in recs]
        out["n log n reference"] = {"exponent": fit_loglog(xs, [x * math.log(x) for x in xs])[0],
                                    "points": len(xs), "faces_min": xs[0], "faces_max": xs[-1]}
    return out


def local_exponents(records, key):
    recs = sorted((r for r in records if r.get("kind") == "ellipsoid" and r.get("exit_code") == 0
                   and value(r, key)), key=lambda r: r["faces"])
    return [(a["faces"], b["faces"], math.log(value(b, key) / value(a, key)) / math.log(b["faces"] / a["faces"]))
            for a, b in zip(recs, recs[1:])]


# ----------------------------------------------------------------- plotting
def svg_plot(records, fit_min, fit_min2, title):
    """Two log-log panels (time, peak memory) against input faces, as SVG text."""
    W, H = 1200, 700
    panels = [(70, 50, 560, 420), (700, 50, 440, 420)]  # x, y, w, h
    series_t = [("cpu_s", "CPU (user+sys)", "#000000", "circle"),
                ("wall_s", "wall", "#888888", "square"),
                (("stage", "shell"), "stage shell", "#1f77b4", "triangle"),
                (("stage", "coarsen"), "stage coarsen", "#d62728", "diamond"),
                (("stage", "curved optimization"), "stage curved optimization", "#2ca02c", "triangle_down")]
    series_m = [("peak_rss_mib", "peak RSS", "#9467bd", "circle")]
    fr = fits(records, fit_min)
    fr2 = fits(records, fit_min2) if fit_min2 else {}
    ok = [r for r in records if r.get("exit_code") == 0]
    ell = sorted((r for r in ok if r.get("kind") == "ellipsoid"), key=lambda r: r["faces"])
    models = [r for r in ok if r.get("kind") == "model"]
    failed = [r for r in records if r.get("exit_code") != 0]
    allx = [r["faces"] for r in records] or [1000, 10000]
    xlo = 10 ** math.floor(math.log10(min(allx)))
    xhi = 10 ** (math.log10(max(allx)) + 0.15)

    def yrange(series):
        ys = [value(r, s[0]) for r in ok for s in series if value(r, s[0])] or [1, 10]
        return 10 ** math.floor(math.log10(min(ys))), 10 ** math.ceil(math.log10(max(ys)))

    def esc(s):
        return s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" '
           f'font-family="DejaVu Sans, sans-serif" font-size="13">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<text x="{W / 2}" y="24" text-anchor="middle" font-size="16">{esc(title)}</text>']

    def marker(shape, x, y, color, hollow=False):
        fill = "white" if hollow else color
        st = f'fill="{fill}" stroke="{color}" stroke-width="1.5"'
        if shape == "circle":
            return f'<circle cx="{x:.1f}" cy="{y:.1f}" r="4.5" {st}/>'
        if shape == "square":
            return f'<rect x="{x - 4:.1f}" y="{y - 4:.1f}" width="8" height="8" {st}/>'
        if shape == "diamond":
            return f'<polygon points="{x:.1f},{y - 5.5:.1f} {x + 5.5:.1f},{y:.1f} {x:.1f},{y + 5.5:.1f} {x - 5.5:.1f},{y:.1f}" {st}/>'
        if shape == "triangle":
            return f'<polygon points="{x:.1f},{y - 5.5:.1f} {x + 5:.1f},{y + 4:.1f} {x - 5:.1f},{y + 4:.1f}" {st}/>'
        return f'<polygon points="{x:.1f},{y + 5.5:.1f} {x + 5:.1f},{y - 4:.1f} {x - 5:.1f},{y - 4:.1f}" {st}/>'

    def panel(px, py, pw, ph, series, ylabel, legend_xy):
        ylo, yhi = yrange(series)

        def X(x):
            return px + pw * (math.log10(x) - math.log10(xlo)) / (math.log10(xhi) - math.log10(xlo))

        def Y(y):
            return py + ph - ph * (math.log10(y) - math.log10(ylo)) / (math.log10(yhi) - math.log10(ylo))

        o = [f'<rect x="{px}" y="{py}" width="{pw}" height="{ph}" fill="none" stroke="black"/>']
        def decades(lo, hi, last, at, grid, label, tick):
            # Per power of ten: its grid line and label, then ticks at 2..9 times it.
            out = []
            for e in range(round(math.log10(lo)), last + 1):
                out += [grid(at(10 ** e)), label(at(10 ** e), e)]
                out += [tick(at(10 ** e * m)) for m in range(2, 10) if 10 ** e * m < hi]
            return out

        power = '10<tspan dy="-6" font-size="10">{}</tspan></text>'
        o += decades(xlo, xhi, math.floor(math.log10(xhi)), X,
                     lambda x: f'<line x1="{x:.1f}" y1="{py}" x2="{x:.1f}" y2="{py + ph}" stroke="#dddddd"/>',
                     lambda x, e: f'<text x="{x:.1f}" y="{py + ph + 18}" text-anchor="middle">' + power.format(e),
                     lambda x: f'<line x1="{x:.1f}" y1="{py + ph}" x2="{x:.1f}" y2="{py + ph - 4}" stroke="black"/>')
        o += decades(ylo, yhi, round(math.log10(yhi)), Y,
                     lambda y: f'<line x1="{px}" y1="{y:.1f}" x2="{px + pw}" y2="{y:.1f}" stroke="#dddddd"/>',
                     lambda y, e: f'<text x="{px - 6}" y="{y + 4:.1f}" text-anchor="end">' + power.format(e),
                     lambda y: f'<line x1="{px}" y1="{y:.1f}" x2="{px + 4}" y2="{y:.1f}" stroke="black"/>')
        o.append(f'<text x="{px + pw / 2}" y="{py + ph + 40}" text-anchor="middle">input triangles (faces)</text>')
        o.append(f'<text x="{px - 48}" y="{py + ph / 2}" text-anchor="middle" '
                 f'transform="rotate(-90 {px - 48} {py + ph / 2})">{esc(ylabel)}</text>')
        lx, ly = legend_xy
        for i, (key, label, color, shape) in enumerate(series):
            pts = [(r["faces"], value(r, key)) for r in ell if value(r, key)]
            if len(pts) > 1:
                o.append('<polyline fill="none" stroke="{}" stroke-width="1.2" stroke-opacity="0.6" points="{}"/>'.format(
                    color, " ".join(f"{X(a):.1f},{Y(b):.1f}" for a, b in pts)))
            for a, b in pts:
                o.append(marker(shape, X(a), Y(b), color))
            for r in models:
                if value(r, key):
                    o.append(marker(shape, X(r["faces"]), Y(value(r, key)), color, hollow=True))
            f = fr.get(label)
            text = label
            if f:
                x0, x1 = f["faces_min"], f["faces_max"]
                o.append(f'<line x1="{X(x0):.1f}" y1="{Y(f["coefficient"] * x0 ** f["exponent"]):.1f}" '
                         f'x2="{X(x1):.1f}" y2="{Y(f["coefficient"] * x1 ** f["exponent"]):.1f}" '
                         f'stroke="{color}" stroke-width="1" stroke-dasharray="6,4"/>')
                text += f'   fit n^{f["exponent"]:.2f} (≥{fit_min})'
                f2 = fr2.get(label)
                if f2:
                    text += f', n^{f2["exponent"]:.2f} (≥{fit_min2})'
            yy = ly + 18 * i
            o.append(marker(shape, lx + 8, yy - 4, color))
            o.append(f'<text x="{lx + 20}" y="{yy}">{esc(text)}</text>')
        yy = ly + 18 * len(series)
        if models:
            o.append(marker("circle", lx + 8, yy - 4, "#444444", hollow=True))
            o.append(f'<text x="{lx + 20}" y="{yy}">hollow: real models (not fitted)</text>')
            yy += 18
            key = series[0][0]
            for i, r in enumerate(sorted((r for r in models if value(r, key)), key=lambda r: r["faces"])):
                name = os.path.splitext(r["name"])[0]
                dy = -9 if i % 2 == 0 else 17  # alternate above / below the marker
                o.append(f'<text x="{X(r["faces"]):.1f}" y="{Y(value(r, key)) + dy:.1f}" font-size="10" '
                         f'text-anchor="middle" fill="#444444">{esc(name)}</text>')
        o.append(f'<line x1="{lx}" y1="{yy - 4}" x2="{lx + 16}" y2="{yy - 4}" stroke="black" stroke-dasharray="6,4"/>')
        o.append(f'<text x="{lx + 20}" y="{yy}">least squares over the ellipsoids with &#8805; {fit_min} faces</text>')
        for r in failed:
            o.append(f'<text x="{X(r["faces"]):.1f}" y="{py + ph - 8}" text-anchor="middle" fill="red" font-size="11">&#215; failed</text>')
        return o

    (ax, ay, aw, ah), (bx, by, bw, bh) = panels
    out += panel(ax, ay, aw, ah, series_t, "seconds", (ax, ay + ah + 70))
    out += panel(bx, by, bw, bh, series_m, "peak resident memory (MiB)", (bx, by + ah + 70))
    ref = fr.get("n log n reference")
    if ref:
        out.append(f'<text x="{W / 2}" y="{H - 12}" text-anchor="middle" font-size="12">'
                   f'n log n over the same fitted sizes ({ref["faces_min"]} .. {ref["faces_max"]}) would fit as '
                   f'n^{ref["exponent"]:.2f}; linear = n^1.00</text>')
    out.append("</svg>")
    return "\n".join(out)


def rasterize(svg_text, png_path, scale=1.5):
    """SVG -> PNG through librsvg + cairo (ctypes). True on success."""
    try:
        rsvg = ctypes.CDLL(ctypes.util.find_library("rsvg-2") or "librsvg-2.so.2")
        cairo = ctypes.CDLL(ctypes.util.find_library("cairo") or "libcairo.so.2")
    except OSError:
        return False
    vp = ctypes.c_void_p
    rsvg.rsvg_handle_new_from_data.restype = vp
    rsvg.rsvg_handle_new_from_data.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.POINTER(vp)]
    cairo.cairo_image_surface_create.restype = vp
    cairo.cairo_image_surface_create.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_int]
    cairo.cairo_create.restype = vp
    cairo.cairo_create.argtypes = [vp]
    cairo.cairo_scale.argtypes = [vp, ctypes.c_double, ctypes.c_double]
    cairo.cairo_surface_write_to_png.argtypes = [vp, ctypes.c_char_p]
    cairo.cairo_destroy.argtypes = [vp]
    cairo.cairo_surface_destroy.argtypes = [vp]

    class Rect(ctypes.Structure):
        _fields_ = [("x", ctypes.c_double), ("y", ctypes.c_double),
                    ("width", ctypes.c_double), ("height", ctypes.c_double)]

    m = re.search(r'width="(\d+)" height="(\d+)"', svg_text)
    w, h = int(m.group(1)), int(m.group(2))
    data = svg_text.encode()
    err = vp()
    handle = rsvg.rsvg_handle_new_from_data(data, len(data), ctypes.byref(err))
    if not handle:
        return False
    surface = cairo.cairo_image_surface_create(0, int(w * scale), int(h * scale))  # ARGB32
    cr = cairo.cairo_create(surface)
    cairo.cairo_scale(cr, ctypes.c_double(scale), ctypes.c_double(scale))
    rsvg.rsvg_handle_render_document.argtypes = [vp, vp, ctypes.POINTER(Rect), ctypes.POINTER(vp)]
    okr = rsvg.rsvg_handle_render_document(vp(handle), vp(cr), ctypes.byref(Rect(0, 0, w, h)), ctypes.byref(err))
    status = cairo.cairo_surface_write_to_png(surface, png_path.encode()) if okr else -1
    cairo.cairo_destroy(cr)
    cairo.cairo_surface_destroy(surface)
    return okr and status == 0


def write_plot(records, png, fit_min, fit_min2):
    machine = next((r.get("machine") for r in records if r.get("machine")), {}) or {}
    title = (f"curvetet scale, ellipsoid, P = 4, eps 1 %, default threads  ({machine.get('nproc', '?')} cores, "
             f"{machine.get('date', '')[:10]}, {machine.get('git_head', '')})")
    placed = [r for r in series(records).get(None, []) if r.get("faces")]  # no count: not placeable
    svg = svg_plot(placed, fit_min, fit_min2, title)
    os.makedirs(os.path.dirname(os.path.abspath(png)), exist_ok=True)
    if png.endswith(".svg"):
        open(png, "w").write(svg)
        print(f"wrote {png}")
    elif rasterize(svg, png):
        print(f"wrote {png}")
    else:
        alt = os.path.splitext(png)[0] + ".svg"
        open(alt, "w").write(svg)
        print(f"no librsvg/cairo for PNG: wrote {alt}", file=sys.stderr)


# ----------------------------------------------------------------- summary
def fmt(v, nd=2):
    return "" if v is None else f"{v:.{nd}f}"


def series(records):
    """Records grouped by the --threads they ran with (None: curvetet's default, the plotted series)."""
    out = {}
    for r in records:
        out.setdefault(r.get("threads"), []).append(r)
    return out


def summary(records, fit_min, fit_min2):
    lines = ["| input | threads | faces | exit | wall s | CPU s | peak MiB | shell s | coarsen s | curved optimization s | output tets |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in sorted(records, key=lambda r: (r.get("threads") is not None, r.get("kind") != "ellipsoid", r.get("faces") or 0)):
        t = r.get("timings_s") or {}
        lines.append(f"| {r['name']} | {r.get('threads') or 'default'} | {r['faces']} "
                     f"| {r.get('exit_code')}{' (' + r['reason'] + ')' if r.get('reason') else ''} "
                     f"| {fmt(r.get('wall_s'))} | {fmt(r.get('cpu_s'))} | {fmt(r.get('peak_rss_mib'), 1)} "
                     f"| {fmt(t.get('shell'))} | {fmt(t.get('coarsen'))} | {fmt(t.get('curved optimization'))} "
                     f"| {r.get('output_tets', '')} |")
    steps = [r for r in records if r.get("coarsen_steps")]
    if steps:
        lines += ["", "coarsening steps (from the log, wall s):", "",
                  "| input | threads | faces | first collapse s (attempts) | later collapses s (attempts) "
                  "| smooth s | refit s | other s |", "|---|---:|---:|---:|---:|---:|---:|---:|"]
        for r in sorted(steps, key=lambda r: (r.get("threads") is not None, r.get("kind") != "ellipsoid", r["faces"])):
            c = r["coarsen_steps"]
            lines.append(f"| {r['name']} | {r.get('threads') or 'default'} | {r['faces']} "
                         f"| {c['first_collapse_s']:.2f} ({c['first_collapse_attempts']}) "
                         f"| {c['later_collapse_s']:.2f} ({c['later_collapse_attempts']}) | {c['smooth_s']:.2f} "
                         f"| {c['refit_s']:.2f} | {c['other_s']:.2f} |")
    for threads, recs in sorted(series(records).items(), key=lambda kv: (kv[0] is not None, kv[0] or 0)):
        lines += ["", f"threads: {threads or 'default'}"]
        for fm in ([fit_min, fit_min2] if fit_min2 else [fit_min]):
            lines.append("")
            for label, f in fits(recs, fm).items():
                extra = f", r^2 {f['r2']:.3f}" if "r2" in f else ""
                pm = f" +- {f['stderr']:.3f}" if "stderr" in f else ""
                lines.append(f"- {label}: exponent {f['exponent']:.3f}{pm} ({f['points']} sizes, "
                             f"{f['faces_min']}..{f['faces_max']} faces{extra})")
        lines.append("")
        for key, label in FIT_KEYS:
            le = local_exponents(recs, key)
            if le:
                lines.append(f"- local exponents, {label}: " + ", ".join(f"{a}->{b}: {k:.2f}" for a, b, k in le))
    return "\n".join(lines)


# ----------------------------------------------------------------- main
def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("models", nargs="*", help="real models to run too (plotted, not fitted)")
    ap.add_argument("--curvetet", default=os.path.join(REPO, "build", "app", "curvetet"))
    ap.add_argument("--min-faces", type=int, default=2000)
    ap.add_argument("--max-faces", type=int, default=1400000)
    ap.add_argument("--faces", help="comma-separated subset of ellipsoid sizes to run (e.g. 2048,8192)")
    ap.add_argument("--timeout", type=float, default=3600, help="per run, seconds (default 3600)")
    ap.add_argument("--threads", type=int,
                    help="pass --threads N (default: curvetet's default, all cores); such runs are named "
                         "*_threadsN, summarized as their own series and not plotted")
    ap.add_argument("--fit-min", type=int, default=8192, help="fit over ellipsoids with >= this many faces")
    ap.add_argument("--fit-min2", type=int, default=81920,
                    help="second fit, over the large sizes only (0: none); in the legend and summary")
    ap.add_argument("--json", default="scale.json", help="results (list of records)")
    ap.add_argument("--png", default="scale.png", help="plot (.png, or .svg)")
    ap.add_argument("--resume", action="store_true",
                    help="keep the successful records already in --json and skip those inputs")
    ap.add_argument("--keep", help="directory for meshes, outputs and logs (default: a temp dir, removed)")
    ap.add_argument("--plot-only", metavar="JSON", help="re-plot (and summarize) an existing results JSON")
    args = ap.parse_args()

    if args.plot_only:
        records = json.load(open(args.plot_only))
        write_plot(records, args.png, args.fit_min, args.fit_min2)
        print(summary(records, args.fit_min, args.fit_min2))
        return

    if not os.path.exists(args.curvetet):
        sys.exit(f"no curvetet binary at {args.curvetet} (bash scripts/build.sh curvetet_cli)")
    sizes = ellipsoid_sizes(args.min_faces, args.max_faces)
    if args.faces:
        want = {int(x) for x in args.faces.split(",")}
        sizes = [s for s in sizes if s[0] in want]
    records = []
    if args.resume and os.path.exists(args.json):
        records = [r for r in json.load(open(args.json)) if r.get("exit_code") == 0]
    done = {r["name"] for r in records}
    workdir = args.keep or tempfile.mkdtemp(prefix="curvetet_scale_")
    os.makedirs(workdir, exist_ok=True)
    # Run a private copy: a rebuild of build/app/curvetet during the benchmark
    # (another job working in the tree) must not change the binary mid-series.
    binary = os.path.join(workdir, "curvetet.bench")
    shutil.copy2(args.curvetet, binary)
    machine = machine_info(binary)
    machine["binary"] = os.path.abspath(args.curvetet)
    suffix = "" if args.threads is None else f"_threads{args.threads}"
    jobs = [("ellipsoid", f"ellipsoid_{base}{level}_{n}{suffix}", (base, level)) for n, base, level in sizes]
    jobs += [("model", os.path.basename(m) + suffix, os.path.abspath(m)) for m in args.models]
    try:
        for kind, name, src in jobs:
            if name in done:
                print(f"skip {name} (in {args.json})", flush=True)
                continue
            rec = {"name": name, "kind": kind, "threads": args.threads}
            if kind == "ellipsoid":
                base, level = src
                mesh = os.path.join(workdir, name + ".off")
                t0 = time.monotonic()
                make_ellipsoid.write_ellipsoid(level, mesh, base=base)
                rec.update(base=base, level=level, generate_s=round(time.monotonic() - t0, 3))
            else:
                mesh = src
                rec["path"] = os.path.relpath(src, REPO)
            rec["vertices"], rec["faces"] = mesh_counts(mesh)
            if rec["faces"] is not None and rec["faces"] > args.max_faces:
                print(f"skip {name}: {rec['faces']} faces > --max-faces", flush=True)
                continue
            print(f"run {name} ({rec['faces']} faces) ...", flush=True)
            try:
                rec.update(run_one(binary, mesh, workdir, name, args.timeout, args.threads, bool(args.keep)))
            except Exception as e:  # keep going: record it as a failed size
                rec.update(exit_code=None, reason=f"benchmark error: {e!r}")
            rec["machine"] = machine
            if rec["faces"] is None:  # not OFF/OBJ: the report's count, if the run got that far
                rec["faces"] = rec.get("report_faces")
            if kind == "ellipsoid" and not args.keep:
                os.remove(mesh)
            t = rec.get("timings_s") or {}
            print(f"  exit {rec['exit_code']}{' (' + rec['reason'] + ')' if rec.get('reason') else ''}: "
                  f"wall {fmt(rec.get('wall_s'))} s, CPU {fmt(rec.get('cpu_s'))} s, "
                  f"peak {fmt(rec.get('peak_rss_mib'), 1)} MiB, shell {fmt(t.get('shell'))} s, "
                  f"coarsen {fmt(t.get('coarsen'))} s, curved opt {fmt(t.get('curved optimization'))} s, "
                  f"{rec.get('output_tets')} tets", flush=True)
            records.append(rec)
            with open(args.json, "w") as f:  # after every run: a stopped benchmark keeps what it has
                json.dump(records, f, indent=1)
    finally:
        if not args.keep:
            shutil.rmtree(workdir, ignore_errors=True)
    write_plot(records, args.png, args.fit_min, args.fit_min2)
    print(summary(records, args.fit_min, args.fit_min2))


if __name__ == "__main__":
    main()
