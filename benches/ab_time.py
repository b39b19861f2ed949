#!/usr/bin/env python3
"""Two lightlab builds timed against each other, interleaved (the machine drifts over
minutes, so both see the same drift): whole-process wall time of the same commands,
medians.

    python3 benches/ab_time.py OLD_BINARY NEW_BINARY [--runs N] [-- RENDER ARGS ...]

Without render arguments it times the README quick-start (`render -o out.png`) and
`render tests/scenes/cbox_diffuse.xml --spp 1024 -o out.exr`.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


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
    args = ap.parse_args(argv)
    out = tempfile.mkdtemp(prefix="lightlab-ab-")
    cases = [extra] if extra else [
        ["render", "-o", os.path.join(out, "a.png")],
        ["render", os.path.join(ROOT, "tests/scenes/cbox_diffuse.xml"), "--spp", "1024",
         "-o", os.path.join(out, "c.exr")],
    ]
    for case in cases:
        times = {"old": [], "new": []}
        for exe in (args.old, args.new):  # warm-up
            subprocess.run([exe] + case, capture_output=True, check=True)
        for _ in range(args.runs):
            for name, exe in (("old", args.old), ("new", args.new)):
                start = time.perf_counter()
                subprocess.run([exe] + case, capture_output=True, check=True)
                times[name].append(time.perf_counter() - start)
        old, new = statistics.median(times["old"]), statistics.median(times["new"])
        print(f"{' '.join(case)}: old {old:.3f} s, new {new:.3f} s (medians of {args.runs}), "
              f"new is {old / new:.2f}x as fast")


if __name__ == "__main__":
    main()
