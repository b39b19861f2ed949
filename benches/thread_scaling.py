#!/usr/bin/env python3
"""1 -> 2 threads on every scene of tests/scenes/ (issue 13 asks for >= 1.9x), for one
or more lightlab builds, interleaved: each round runs every build at --threads 1 and 2
on the scene before the next round starts, so all see the same drift of the machine.

    python3 benches/thread_scaling.py BINARY [BINARY ...] [--runs N] [--spp N] [SCENE ...]

The time is the render's own (scene loading and image writing excluded), taken from the
Msamples/s that `render` prints (three significant digits, where its seconds have two
decimals). Prints, per scene and build, the medians at 1 and 2 threads, their ratio,
and the median CPU use of the 2-thread process (CPU time over wall time, at most 200 %:
what it lacks is time a thread waited). On a shared VM the speed-up also moves with the
host's load; the CPU use does not.
"""
import argparse
import glob
import os
import re
import statistics
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RATE = re.compile(r"(\d+)x(\d+) at (\d+) spp in [0-9.]+ s \(([0-9.]+) Msamples/s\)")


def render_seconds(exe, scene, spp, threads, out):
    """The render's own time in seconds (from the pixel count, spp and Msamples/s), and
    the whole process's CPU time over its wall time."""
    start = time.perf_counter()
    proc = subprocess.Popen(
        [exe, "render", scene, "--spp", str(spp), "--threads", str(threads), "-o", out],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    text = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    if status != 0:
        raise SystemExit(f"{exe} failed on {scene}:\n{text}")
    m = RATE.search(text)
    if not m:
        raise SystemExit(f"no timing line in the output of {exe} on {scene}")
    w, h, n, rate = int(m[1]), int(m[2]), int(m[3]), float(m[4])
    return w * h * n / (rate * 1e6), (usage.ru_utime + usage.ru_stime) / wall


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binaries", nargs="+", help="lightlab builds, then optional scenes")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--spp", type=int, default=1024)
    args = ap.parse_args()
    exes = [b for b in args.binaries if not b.endswith(".xml")]
    scenes = [b for b in args.binaries if b.endswith(".xml")] or sorted(
        glob.glob(os.path.join(ROOT, "tests/scenes/*.xml")))
    out = os.path.join(tempfile.mkdtemp(prefix="lightlab-scaling-"), "s.exr")
    print("| scene | build | 1 thread s | 2 threads s | speed-up | CPU use at 2 |\n"
          "|---|---|---|---|---|---|")
    for scene in scenes:
        times = {(e, t): [] for e in exes for t in (1, 2)}
        use = {e: [] for e in exes}
        for _ in range(args.runs):
            for exe in exes:
                for t in (1, 2):
                    seconds, cpu = render_seconds(exe, scene, args.spp, t, out)
                    times[(exe, t)].append(seconds)
                    if t == 2:
                        use[exe].append(cpu)
        for exe in exes:
            t1 = statistics.median(times[(exe, 1)])
            t2 = statistics.median(times[(exe, 2)])
            print(f"| `{os.path.basename(scene)}` | {exe} | {t1:.3f} | {t2:.3f} | "
                  f"{t1 / t2:.2f} | {100 * statistics.median(use[exe]):.0f} % |", flush=True)


if __name__ == "__main__":
    main()
