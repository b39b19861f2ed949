#!/usr/bin/env python3
"""Times lightlab and Mitsuba 3 (scalar_rgb and llvm_ad_rgb) on the same XML files at the
same spp: the median of 3 runs of the render alone (scene loading excluded; Mitsuba's
llvm_ad_rgb time includes its JIT compilation, which a first run pays in full and later
runs partly reuse from its kernel cache).

Usage: python3 benches/mitsuba_compare.py [--spp N] [--runs R] [SCENE.xml ...]
Needs a release build of lightlab (cargo build --release; set CARGO_TARGET_DIR if you
use one) and DRJIT_LIBLLVM_PATH for llvm_ad_rgb (e.g. the libLLVM-19.so of Debian's
libllvm19). Both renderers use every core.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_SCENES = ["cbox_diffuse", "gaussian_stratified", "mesh_obj", "mesh_ply_serialized"]

MITSUBA = r"""
import sys, time, mitsuba as mi
mi.set_variant(sys.argv[1])
scene = mi.load_file(sys.argv[2], **({"spp": int(sys.argv[3])} if sys.argv[4] == "1" else {}))
t = time.perf_counter()
img = mi.render(scene, spp=int(sys.argv[3]))
import drjit as dr
dr.eval(img); dr.sync_thread()
print(time.perf_counter() - t)
"""


def lightlab_time(exe, scene, spp):
    out = os.path.join(tempfile.gettempdir(), "mitsuba_compare.exr")
    r = subprocess.run([exe, "render", scene, "--spp", str(spp), "-o", out],
                       capture_output=True, text=True, check=True)
    return float(re.search(r" in ([0-9.]+) s", r.stderr).group(1))


def mitsuba_time(variant, scene, spp):
    declares = 'name="spp"' in open(scene).read()
    r = subprocess.run([sys.executable, "-c", MITSUBA, variant, scene, str(spp), "1" if declares else "0"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return None
    return float(r.stdout.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("scenes", nargs="*")
    a = ap.parse_args()
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    exe = os.path.join(target, "release", "lightlab")
    scenes = a.scenes or [os.path.join(ROOT, "tests", "scenes", n + ".xml") for n in DEFAULT_SCENES]
    variants = ["scalar_rgb"] + (["llvm_ad_rgb"] if os.environ.get("DRJIT_LIBLLVM_PATH") else [])
    print(f"| scene | spp | lightlab s | " + " | ".join(f"Mitsuba {v} s" for v in variants) + " |")
    print("|---|---|---|" + "---|" * len(variants))
    for scene in scenes:
        row = [statistics.median(lightlab_time(exe, scene, a.spp) for _ in range(a.runs))]
        for v in variants:
            ts = [mitsuba_time(v, scene, a.spp) for _ in range(a.runs)]
            row.append(statistics.median(ts) if None not in ts else float("nan"))
        name = os.path.basename(scene)
        print(f"| {name} | {a.spp} | " + " | ".join(f"{t:.3f}" for t in row) + " |", flush=True)


if __name__ == "__main__":
    main()
