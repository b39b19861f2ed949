#!/usr/bin/env python3
"""lightlab against Mitsuba 3 on the same XML files at the same spp, measured in one run on
one machine: the ratio of samples per second, as issue 13 asks for.

    python3 benches/mitsuba_compare.py [--spp N] [--runs R] [--threads T] [--scalar] [--builtins]
                                       [--lightlab EXE] [SCENE.xml ...]

With no scene it takes every scene of tests/scenes/. --builtins adds (or, with no scene
given, takes instead) each built-in scene written out as XML (`lightlab export`, its
sampler set to `independent`) that Mitsuba 3 can read: those with Phong materials
(Mitsuba 0.6's plugin, which Mitsuba 3 lacks) are listed as skipped. It installs what it
needs itself: a virtual environment in target/bench-venv with mitsuba, embreex and numpy
(PyPI), and it points DRJIT_LIBLLVM_PATH at Debian's libLLVM-19.so (`apt-get install
libllvm19`) so that Mitsuba's vectorised llvm_ad_rgb variant runs. It builds lightlab in release mode first,
unless --lightlab names the binary to time (another build, to compare two against the same peer).

What is timed, per scene and configuration, interleaved over R rounds (the machine drifts
over minutes, so every configuration sees the same drift), reported as medians:
- lightlab, whole process (`lightlab render … -o out.exr`: start-up, scene loading, render,
  writing), with its default strategies, and with Mitsuba's own strategies
  (`--light-sampling area --light-select uniform --sampler independent
  --no-envmap-compensation`);
- Mitsuba `llvm_ad_rgb` (and `scalar_rgb` with --scalar): `mi.load_file` + `mi.render` +
  evaluation, measured inside a Python process whose Mitsuba import is not counted, after
  one warm-up render of the same scene so the JIT kernel cache is warm.
Ratios are Mitsuba's time over lightlab's: above 1, lightlab renders more samples per
second.
"""
import argparse
import glob
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VENV = os.path.join(ROOT, "target", "bench-venv")
LLVM_CANDIDATES = [
    "/usr/lib/x86_64-linux-gnu/libLLVM-19.so",
    "/usr/lib/aarch64-linux-gnu/libLLVM-19.so",
    "/usr/lib/llvm-19/lib/libLLVM.so",
]
MITSUBA_STRATEGIES = ["--light-sampling", "area", "--light-select", "uniform", "--sampler", "independent",
                      "--no-envmap-compensation"]

# Loads and renders one scene `runs` times after a warm-up; prints one time per line.
MITSUBA = r"""
import sys, time
import mitsuba as mi
import drjit as dr
variant, scene_file, spp, runs = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
mi.set_variant(variant)
def once():
    t = time.perf_counter()
    scene = mi.load_file(scene_file, spp=spp) if 'name="spp"' in open(scene_file).read() else mi.load_file(scene_file)
    img = mi.render(scene, spp=spp)
    dr.eval(img)
    dr.sync_thread()
    return time.perf_counter() - t
once()  # warm-up: fills the kernel cache
for _ in range(runs):
    print(once(), flush=True)
"""


def ensure_venv(script=__file__):
    """Re-runs `script` inside target/bench-venv, creating the venv if needed."""
    if os.path.realpath(sys.prefix) == os.path.realpath(VENV):
        return
    python = os.path.join(VENV, "bin", "python")
    if not os.path.exists(python):
        print(f"creating {VENV} (mitsuba, embreex, numpy)", file=sys.stderr)
        subprocess.run([sys.executable, "-m", "venv", VENV], check=True)
        subprocess.run([python, "-m", "pip", "install", "-q", "mitsuba", "embreex", "numpy"], check=True)
    os.execv(python, [python, os.path.abspath(script)] + sys.argv[1:])


def llvm_environment():
    env = dict(os.environ)
    if "DRJIT_LIBLLVM_PATH" not in env:
        found = next((p for p in LLVM_CANDIDATES if os.path.exists(p)), None)
        if found:
            env["DRJIT_LIBLLVM_PATH"] = found
    return env


def lightlab_times(exe, scene, spp, threads, extra, runs):
    out = os.path.join(tempfile.gettempdir(), "mitsuba_compare.exr")
    cmd = [exe, "render", scene, "--spp", str(spp), "--threads", str(threads), "-o", out] + extra
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        subprocess.run(cmd, capture_output=True, check=True)
        times.append(time.perf_counter() - t)
    return times


def mitsuba_times(variant, scene, spp, runs, env):
    r = subprocess.run([sys.executable, "-c", MITSUBA, variant, scene, str(spp), str(runs)],
                       capture_output=True, text=True, env=env)
    if r.returncode != 0:
        print(f"warning: Mitsuba {variant} failed on {scene}: {r.stderr.strip().splitlines()[-1:]}", file=sys.stderr)
        return None
    return [float(x) for x in r.stdout.split()]


def exported_builtins(exe):
    """Writes every built-in scene as XML into a temporary folder, with the independent
    sampler (Mitsuba's `ldsampler`, the export's name for lightlab's Sobol, rounds sample
    counts up and is biased near steep integrands); returns the files Mitsuba 3 can read,
    and prints the others with the reason."""
    folder = tempfile.mkdtemp(prefix="lightlab-builtins-")
    listing = subprocess.run([exe, "scenes"], capture_output=True, text=True, check=True).stdout
    files = []
    for line in listing.splitlines():
        name = line.split()[0].removeprefix("builtin:")
        xml = os.path.join(folder, name + ".xml")
        r = subprocess.run([exe, "export", "builtin:" + name, "-o", xml, "--sampler", "independent"],
                           capture_output=True, text=True)
        notes = [l for l in r.stderr.splitlines() if l.startswith(("note:", "error:"))]
        if r.returncode != 0 or any("Mitsuba 3 will not read this file" in l for l in notes):
            print(f"skipped builtin:{name}: {'; '.join(notes)}", file=sys.stderr)
            continue
        files.append(xml)
    return files


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--scalar", action="store_true", help="also time Mitsuba's scalar_rgb variant")
    ap.add_argument("--builtins", action="store_true",
                    help="add the built-in scenes Mitsuba 3 can read, written out as XML")
    ap.add_argument("--lightlab", metavar="EXE",
                    help="time this lightlab binary instead of building the release one")
    ap.add_argument("scenes", nargs="*")
    a = ap.parse_args()
    ensure_venv()
    env = llvm_environment()
    if a.lightlab:
        exe = os.path.abspath(a.lightlab)
    else:
        subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
        target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
        exe = os.path.join(target, "release", "lightlab")
    if a.builtins:
        scenes = a.scenes + exported_builtins(exe)
    else:
        scenes = a.scenes or sorted(glob.glob(os.path.join(ROOT, "tests", "scenes", "*.xml")))
    variants = (["scalar_rgb"] if a.scalar else []) + (["llvm_ad_rgb"] if "DRJIT_LIBLLVM_PATH" in env else [])
    if "llvm_ad_rgb" not in variants:
        print("warning: no libLLVM-19.so found (apt-get install libllvm19): llvm_ad_rgb skipped", file=sys.stderr)
    configs = [("lightlab", []), ("lightlab (Mitsuba's strategies)", MITSUBA_STRATEGIES)]
    head = ["scene", "spp"] + [f"{c} s" for c, _ in configs] + [f"Mitsuba {v} s" for v in variants]
    head += [f"{v} ÷ {c}" for v in variants for c, _ in configs]
    print(f"{a.runs} interleaved runs, medians, {a.threads} threads; ratio = Mitsuba time / lightlab time")
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for scene in scenes:
        samples = {c: [] for c, _ in configs}
        samples.update({v: [] for v in variants})
        # One round = one run of every configuration, so drift hits all alike.
        for _ in range(a.runs):
            for c, extra in configs:
                samples[c] += lightlab_times(exe, scene, a.spp, a.threads, extra, 1)
            for v in variants:
                t = mitsuba_times(v, scene, a.spp, 1, env)
                samples[v] += t if t else [float("nan")]
        med = {k: statistics.median(v) for k, v in samples.items()}
        row = [os.path.basename(scene), str(a.spp)] + [f"{med[c]:.3f}" for c, _ in configs]
        row += [f"{med[v]:.3f}" for v in variants]
        row += [f"{med[v] / med[c]:.2f}" for v in variants for c, _ in configs]
        print("| " + " | ".join(row) + " |", flush=True)


if __name__ == "__main__":
    main()
