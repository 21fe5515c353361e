#!/usr/bin/env python3
"""Fit the scaling exponent of Google Benchmark results (stdlib only).

Reads the JSON written by `bench_franklin --benchmark_format=json` (or
--benchmark_out=FILE --benchmark_out_format=json), one or more files or stdin,
and prints Markdown:
  1. per family, the least-squares slope of log(time) against log(N):
     1 means linear, as Franklin 1980 claims; 2 quadratic;
  2. per run, wall time and time per face (time / N).

A run's N is the `N:<value>` part of its name (bench_franklin names runs
`squares/D:5/N:1000`); its family is the name without that part. Pass
`--param D` to fit against another `NAME:value` part instead (for instance
time against depth complexity in the `squares_depth` runs).

    ./bench_franklin --benchmark_format=json > out.json
    python3 fit_exponent.py out.json
"""

import argparse
import json
import math
import sys

TO_SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def load_runs(streams, param, clock="real_time"):
    """Returns {family: {x: [seconds, ...]}} plus counters, in input order."""
    prefix = param + ":"
    families = {}
    counters = {}
    for stream in streams:
        for b in json.load(stream).get("benchmarks", []):
            # Skip aggregates (mean, BigO, RMS...) and failed runs.
            if b.get("run_type", "iteration") != "iteration" or b.get("error_occurred"):
                continue
            parts = b.get("run_name", b["name"]).split("/")
            found = [q for q in parts if q.startswith(prefix)]
            if not found:
                continue
            x = float(found[0][len(prefix):])
            # Family: the name without the N part and without timing-mode suffixes.
            family = "/".join(q for q in parts if q != found[0] and q not in
                              ("real_time", "process_time", "manual_time"))
            seconds = b[clock] * TO_SECONDS[b.get("time_unit", "ns")]
            families.setdefault(family, {}).setdefault(x, []).append(seconds)
            counters[(family, x)] = {k: b[k] for k in ("segments", "regions", "faces") if k in b}
    return families, counters


def fit_slope(points):
    """Least-squares slope and R^2 of log(t) on log(x); None with < 2 distinct x."""
    pts = [(math.log(x), math.log(t)) for x, t in points if x > 0 and t > 0]
    if len({p[0] for p in pts}) < 2:
        return None, None
    n = len(pts)
    mx = sum(p[0] for p in pts) / n
    my = sum(p[1] for p in pts) / n
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    sxy = sum((p[0] - mx) * (p[1] - my) for p in pts)
    syy = sum((p[1] - my) ** 2 for p in pts)
    slope = sxy / sxx
    r2 = (sxy * sxy) / (sxx * syy) if syy > 0 else 1.0
    return slope, r2


def fmt_x(x):
    return str(int(x)) if x == int(x) else repr(x)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="*", help="benchmark JSON files (default: stdin)")
    ap.add_argument("--param", default="N", help="name part to fit against (default: N)")
    ap.add_argument("--cpu", action="store_true",
                    help="fit the process CPU time instead of wall time (steadier on a shared machine)")
    args = ap.parse_args()

    streams = [open(f, encoding="utf-8") for f in args.files] or [sys.stdin]
    families, counters = load_runs(streams, args.param, "cpu_time" if args.cpu else "real_time")
    if not families:
        sys.exit(f"fit_exponent: no runs with a '{args.param}:<value>' part in their name")

    p = args.param
    print(f"## Scaling: slope of log(time) against log({p})\n")
    print(f"| family | runs | {p} range | slope | R² |")
    print("|---|---:|---|---:|---:|")
    for family, runs in families.items():
        # Repetitions of one run are averaged before fitting.
        points = [(x, sum(ts) / len(ts)) for x, ts in sorted(runs.items())]
        slope, r2 = fit_slope(points)
        if slope is None:
            continue
        xs = [x for x, _ in points]
        print(f"| {family} | {len(points)} | {fmt_x(xs[0])} – {fmt_x(xs[-1])} "
              f"| {slope:.3f} | {r2:.4f} |")

    print("\n## Time per face\n")
    print(f"| family | {p} | time (ms) | µs / face | segments | regions |")
    print("|---|---:|---:|---:|---:|---:|")
    for family, runs in families.items():
        for x, ts in sorted(runs.items()):
            t = sum(ts) / len(ts)
            c = counters.get((family, x), {})
            # Faces from the counter when present, else N itself.
            faces = c.get("faces", x if p == "N" else None)
            per_face = f"{t * 1e6 / faces:.3f}" if faces else "–"
            seg = f"{int(c['segments'])}" if "segments" in c else "–"
            reg = f"{int(c['regions'])}" if "regions" in c else "–"
            print(f"| {family} | {fmt_x(x)} | {t * 1e3:.3f} | {per_face} | {seg} | {reg} |")


if __name__ == "__main__":
    main()
