#!/usr/bin/env python3
"""Two lightlab builds timed against each other, interleaved (the machine drifts over
minutes, so both see the same drift): whole-process times of the same commands.

    python3 benches/ab_time.py OLD_BINARY NEW_BINARY [--runs N] [--cpu] [-- RENDER ARGS ...]

Without render arguments it times the README quick-start (`render -o out.png`) and
`render tests/scenes/cbox_diffuse.xml --spp 1024 -o out.exr`.

Each round runs both builds, the first round old then new, the next new then old, and so
on, so that neither always runs right after the other. It prints each build's tenth
percentile, quartile and median, and old ÷ new of each (above 1: new is faster). On a
noisy shared machine the low quantiles are the steadier figures: interference only ever
adds time. `--cpu` times user + system CPU of the process (and its threads) instead of
wall time; that leaves out waiting for a core another process holds.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
QUANTILES = (("q10", 0.10), ("q25", 0.25), ("median", 0.50))


def quantile(xs, f):
    """The f-quantile of xs, interpolated linearly between order statistics."""
    s = sorted(xs)
    pos = f * (len(s) - 1)
    lo = int(pos)
    hi = min(lo + 1, len(s) - 1)
    return s[lo] + (s[hi] - s[lo]) * (pos - lo)


def timed(cmd, cpu):
    """Seconds one run of cmd took: wall time, or user + system CPU time."""
    with tempfile.TemporaryFile() as err:
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
        proc.returncode = os.waitstatus_to_exitcode(status)
        if proc.returncode != 0:
            err.seek(0)
            sys.exit(f"{' '.join(cmd)} failed:\n{err.read().decode(errors='replace')}")
    return usage.ru_utime + usage.ru_stime if cpu else wall


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        i = argv.index("--")
        argv, extra = argv[:i], argv[i + 1:]
    ap = argparse.ArgumentParser()
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--runs", type=int, default=11)
    ap.add_argument("--cpu", action="store_true",
                    help="time user + system CPU instead of wall time")
    args = ap.parse_args(argv)
    if args.runs < 1:
        ap.error("--runs must be at least 1")
    out = tempfile.mkdtemp(prefix="lightlab-ab-")
    cases = [extra] if extra else [
        ["render", "-o", os.path.join(out, "a.png")],
        ["render", os.path.join(ROOT, "tests/scenes/cbox_diffuse.xml"), "--spp", "1024",
         "-o", os.path.join(out, "c.exr")],
    ]
    builds = (("old", args.old), ("new", args.new))
    what = "CPU" if args.cpu else "wall"
    for case in cases:
        times = {"old": [], "new": []}
        for _, exe in builds:  # warm-up
            timed([exe] + case, args.cpu)
        for r in range(args.runs):
            for name, exe in builds if r % 2 == 0 else builds[::-1]:
                times[name].append(timed([exe] + case, args.cpu))
        print(f"{' '.join(case)} ({what} time, {args.runs} runs each):")
        for label, f in QUANTILES:
            old, new = quantile(times["old"], f), quantile(times["new"], f)
            print(f"  {label:>6}: old {old:.3f} s, new {new:.3f} s, old / new {old / new:.2f}")


if __name__ == "__main__":
    main()
