#!/usr/bin/env python3
"""Noise and cost of lightlab's strategies without a reference image: for each set of
extra flags, the relMSE between renders of two different seeds (`lightlab diff`; about
twice the relative variance of one render, free of any bias a reference would add) and
the CPU time of a render (1 thread), medians over `--pairs` seed pairs.

    python3 benches/noise.py SCENE [--spp 256] [--pairs 3] [--exe PATH] FLAGS [FLAGS ...]

Each FLAGS is one quoted string of render flags ("" for the defaults), e.g.
    python3 benches/noise.py tests/scenes/cbox_diffuse.xml "" "--diffuse-bsdf-samples 0"
The product relMSE·t compares strategies at equal time (lower is better).
"""
import argparse
import os
import re
import resource
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cpu_seconds(command):
    """Runs `command` and returns the CPU time (user + system) it took."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(command, capture_output=True, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("flags", nargs="+", help='render flags per strategy, one quoted string each ("" = defaults)')
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--pairs", type=int, default=3)
    ap.add_argument("--exe", default=os.path.join(ROOT, "target", "release", "lightlab"))
    args = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="noise_")
    images = [os.path.join(tmp, "a.exr"), os.path.join(tmp, "b.exr")]
    for flags in args.flags:
        errors, times = [], []
        for k in range(args.pairs):
            for image, seed in zip(images, (2 * k + 11, 2 * k + 12)):
                times.append(cpu_seconds([args.exe, "render", args.scene, "--spp", str(args.spp), "--seed",
                                          str(seed), "--threads", "1", *flags.split(), "-o", image]))
            out = subprocess.run([args.exe, "diff", *images], capture_output=True, text=True, check=True).stdout
            errors.append(float(re.search(r"relmse: (\S+)", out).group(1)))
        e, t = statistics.median(errors), statistics.median(times)
        print(f"{flags or 'defaults':32s} relMSE between seeds {e:.3e}  CPU {t:.3f} s  product {e * t:.3e}", flush=True)


if __name__ == "__main__":
    main()
