#!/usr/bin/env python3
"""Renders the reference EXR of every scene in tests/scenes/ with Mitsuba 3.

Usage: python3 tests/scenes/make_refs.py [--spp N] [--variant V] [NAME ...]
       python3 tests/scenes/make_refs.py --builtins [--spp N] [--variant V] [--lightlab EXE]

Each scene's `$spp` default is replaced by --spp (default 8192). The variant defaults
to llvm_ad_rgb when DRJIT_LIBLLVM_PATH is set, else scalar_rgb; both give the same
expectation. Scenes that use a BSDF lightlab does not have yet are rendered too: their
test is skipped until the BSDF lands. Output: tests/scenes/refs/NAME.exr with R, G, B (the
mean of 8 independent passes, seeds 0-7) and variance.R/G/B (the variance of that mean,
from the spread of the passes), float32. The meshes and textures the scenes use come from
make_meshes.py and are committed.

With --builtins it makes refs/builtin_NAME.exr instead, for the built-in scenes of
tests/xml_scenes.rs's BUILTIN_CASES: each is written out by `lightlab export` (the binary
given by --lightlab, default target/release/lightlab: run `cargo build --release`
first), its film set to the test's size and its sampler to `independent` (see
exported_builtin), and rendered as above.

The references in the repository: Mitsuba 3.9.1, llvm_ad_rgb, 8192 spp
(DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so from Debian's libllvm19).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import mitsuba as mi

# Independent passes per reference (for its variance).
PASSES = 8

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# The built-in scenes Mitsuba 3 can read once exported, with the size of their references:
# the same list as tests/xml_scenes.rs's BUILTIN_CASES (keep them in step).
BUILTINS = {"sphere-near-plane": (96, 64), "materials": (96, 64)}


def exported_builtin(exe, name, size, folder):
    """Writes builtin:NAME as XML into `folder` with its film set to `size` and the
    independent sampler; returns the path.

    The reference is rendered with Mitsuba's independent sampler: its `ldsampler` (the
    export's name for lightlab's default Sobol) leaves a structured error that more
    samples do not remove where the integrand is steep in both the film position and the
    light sample (5-15 % in the pixels at the foot of sphere-near-plane's grazing
    rectangle at 16384 spp, with every seed; the independent sampler and lightlab agree
    there with Lambert's analytic irradiance integrated over each pixel)."""
    path = os.path.join(folder, name + ".xml")
    width, height = size
    subprocess.run([exe, "export", "builtin:" + name, "-o", path, "--width", str(width),
                    "--height", str(height), "--sampler", "independent"], check=True, capture_output=True)
    return path


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", type=int, default=8192)
    ap.add_argument("--variant", default=None)
    ap.add_argument("--builtins", action="store_true")
    ap.add_argument("--lightlab", default=os.path.join(ROOT, "target", "release", "lightlab"))
    ap.add_argument("names", nargs="*")
    a = ap.parse_args()
    variant = a.variant or ("llvm_ad_rgb" if os.environ.get("DRJIT_LIBLLVM_PATH") else "scalar_rgb")
    mi.set_variant(variant)
    os.makedirs(os.path.join(HERE, "refs"), exist_ok=True)
    if a.builtins and a.names:
        ap.error("--builtins makes every built-in reference; give no NAME with it")
    if a.builtins:
        folder = tempfile.mkdtemp(prefix="lightlab-refs-")
        jobs = [("builtin_" + n, exported_builtin(a.lightlab, n, size, folder)) for n, size in BUILTINS.items()]
    else:
        names = a.names or sorted(f[:-4] for f in os.listdir(HERE) if f.endswith(".xml"))
        jobs = [(name, os.path.join(HERE, name + ".xml")) for name in names]
    for name, path in jobs:
        with open(path) as f:
            declares_spp = 'name="spp"' in f.read()
        scene = mi.load_file(path, spp=a.spp) if declares_spp else mi.load_file(path)
        # PASSES independent renders (seeds 0..PASSES-1): their mean is the reference and
        # their spread the variance of that mean, stored per pixel so the test can add
        # the reference's own noise to its error bars.
        passes = [mi.TensorXf(mi.render(scene, spp=a.spp // PASSES, seed=k)) for k in range(PASSES)]
        mean = sum(passes[1:], passes[0]) / PASSES
        m2 = sum(((p - mean) * (p - mean) for p in passes[1:]), (passes[0] - mean) * (passes[0] - mean))
        var = m2 / (PASSES * (PASSES - 1))
        h, w, c = mean.shape
        mv, vv = list(mean.array), list(var.array)
        both = []
        for i in range(h * w):
            both += mv[i * c:i * c + 3] + vv[i * c:i * c + 3]
        bitmap = mi.Bitmap(mi.TensorXf(both, (h, w, 6)), mi.Bitmap.PixelFormat.MultiChannel,
                           channel_names=["R", "G", "B", "variance.R", "variance.G", "variance.B"])
        out = os.path.join(HERE, "refs", name + ".exr")
        bitmap.write(out)
        print(f"{name}: {variant}, {a.spp} spp -> {out}", file=sys.stderr)


if __name__ == "__main__":
    main()
