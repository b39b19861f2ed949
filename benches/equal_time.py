#!/usr/bin/env python3
"""Equal-time error of lightlab against Mitsuba 3 (`llvm_ad_rgb`) on the conformance scenes:
relMSE against the committed 8192-spp Mitsuba references (tests/scenes/refs/) as a function
of time, for both renderers, and the ratio of their relMSE at equal time.

    python3 benches/equal_time.py [--spp 4,16,64,256] [--runs 3] [--lightlab-args "--sampler sobol"]
        [--mitsuba-sampler ldsampler] [SCENE.xml ...]

Each point is the median over `runs` of (time, relMSE) at one spp with a different seed per
run. Time is lightlab's whole process and Mitsuba's `load_file` + `render` with a warm
kernel cache (as benches/mitsuba_compare.py). Both images are judged by the same code
(`lightlab diff`). For an unbiased estimator relMSE·time is a constant (the inverse of its
efficiency, Veach 1997 §2.4), so each renderer's constant is the median of relMSE·t over
its points, and the ratio at equal time is lightlab's constant over Mitsuba's: below 1,
lightlab leaves less error in equal time. The fitted log–log slopes are printed to check
that assumption (≈ −1). The reference's own noise puts a floor under relMSE, so keep the
spp well below 8192.

`--lightlab-args` adds flags to every lightlab render (say `--sampler sobol`, where the scene
file asks for independent samples); `--mitsuba-sampler` renders Mitsuba with another of its
samplers (`ldsampler`, `multijitter`, …) by rewriting the scene's `<sampler type=…>` in a copy
next to it. With a QMC sampler relMSE falls faster than 1/t, so relMSE·t is not constant;
the last column compares the two fitted lines at the time of Mitsuba's middle spp.
"""
import argparse
import glob
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_compare import ROOT, ensure_venv, llvm_environment  # noqa: E402

MITSUBA = r"""
import sys, time
import mitsuba as mi
import drjit as dr
scene_file, spp, seed, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
mi.set_variant("llvm_ad_rgb")
def once():
    t = time.perf_counter()
    scene = mi.load_file(scene_file, spp=spp) if 'name="spp"' in open(scene_file).read() else mi.load_file(scene_file)
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img); dr.sync_thread()
    return time.perf_counter() - t, img
once()
t, img = once()
mi.util.write_bitmap(out, img)
print(t)
"""


def rel_mse(exe, image, reference):
    out = subprocess.run([exe, "diff", image, reference], capture_output=True, text=True, check=True).stdout
    return float(re.search(r"relmse: (\S+)", out).group(1))


def lightlab_point(exe, scene, spp, seed, ref, extra=()):
    out = os.path.join(tempfile.gettempdir(), "equal_time_lightlab.exr")
    t = time.perf_counter()
    subprocess.run([exe, "render", scene, "--spp", str(spp), "--seed", str(seed), *extra, "-o", out],
                   capture_output=True, check=True)
    return time.perf_counter() - t, rel_mse(exe, out, ref)


def mitsuba_point(exe, scene, spp, seed, ref, env):
    out = os.path.join(tempfile.gettempdir(), "equal_time_mitsuba.exr")
    r = subprocess.run([sys.executable, "-c", MITSUBA, scene, str(spp), str(seed), out],
                       capture_output=True, text=True, env=env, check=True)
    return float(r.stdout.split()[-1]), rel_mse(exe, out, ref)


def with_sampler(scene, sampler):
    """A copy of `scene` next to it (so relative paths still resolve) whose sampler is
    `sampler`; the caller removes it."""
    text = open(scene).read()
    changed, n = re.subn(r'<sampler type="[^"]*"', f'<sampler type="{sampler}"', text)
    if n == 0:
        sys.exit(f"{scene}: no <sampler> to replace")
    path = os.path.join(os.path.dirname(scene), f".equal_time_{sampler}_{os.path.basename(scene)}")
    with open(path, "w") as f:
        f.write(changed)
    return path


def fit(points):
    """Least-squares line (intercept, slope) through (log t, log relMSE)."""
    xs = [math.log(t) for t, _ in points]
    ys = [math.log(max(e, 1e-30)) for _, e in points]
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / max(sum((x - mx) ** 2 for x in xs), 1e-30)
    return my - b * mx, b


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spp", default="256,1024")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--lightlab-args", default="", help="extra flags for every lightlab render")
    ap.add_argument("--mitsuba-sampler", default=None, help="Mitsuba sampler to use instead of the scene's")
    ap.add_argument("scenes", nargs="*")
    a = ap.parse_args()
    ensure_venv(__file__)
    env = llvm_environment()
    if "DRJIT_LIBLLVM_PATH" not in env:
        sys.exit("no libLLVM-19.so (apt-get install libllvm19)")
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
    exe = os.path.join(os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target")), "release", "lightlab")
    scenes = a.scenes or sorted(glob.glob(os.path.join(ROOT, "tests", "scenes", "*.xml")))
    spps = [int(s) for s in a.spp.split(",")]
    extra = a.lightlab_args.split()
    print(f"<!-- lightlab {' '.join(extra) or '(scene defaults)'}; Mitsuba {a.mitsuba_sampler or 'scene sampler'} -->")
    print("| scene | lightlab slope | Mitsuba slope | relMSE ratio at equal time (lightlab ÷ Mitsuba) "
          "| same, fitted lines at Mitsuba's middle time |")
    print("|---|---|---|---|---|")
    for scene in scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        ref = os.path.join(ROOT, "tests", "scenes", "refs", name + ".exr")
        curves = {"lightlab": [], "mitsuba": []}
        for spp in spps:
            pts = {"lightlab": [], "mitsuba": []}
            for k in range(a.runs):
                pts["lightlab"].append(lightlab_point(exe, scene, spp, 1000 + k, ref, extra))
                m_scene = with_sampler(scene, a.mitsuba_sampler) if a.mitsuba_sampler else scene
                try:
                    pts["mitsuba"].append(mitsuba_point(exe, m_scene, spp, 1000 + k, ref, env))
                finally:
                    if m_scene != scene:
                        os.remove(m_scene)
            for r, p in pts.items():
                curves[r].append((statistics.median(t for t, _ in p), statistics.median(e for _, e in p)))
        (al, bl), (am, bm) = fit(curves["lightlab"]), fit(curves["mitsuba"])
        work = {r: statistics.median(t * e for t, e in c) for r, c in curves.items()}
        ratio = work["lightlab"] / work["mitsuba"]
        t_mid = math.log(curves["mitsuba"][len(spps) // 2][0])
        fitted = math.exp((al + bl * t_mid) - (am + bm * t_mid))
        print(f"| {name} | {bl:.2f} | {bm:.2f} | {ratio:.2f} | {fitted:.2f} |", flush=True)
        for r, c in curves.items():
            print(f"<!-- {name} {r}: " + ", ".join(f"{s} spp {t:.3f} s {e:.3e}" for s, (t, e) in zip(spps, c)) + " -->")


if __name__ == "__main__":
    main()
