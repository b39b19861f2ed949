#!/usr/bin/env python3
"""Renders the reference EXR of every scene in tests/scenes/ with Mitsuba 3.

Usage: python3 tests/scenes/make_refs.py [--spp N] [--variant V] [NAME ...]

Each scene's `$spp` default is replaced by --spp (default 8192). The variant defaults
to llvm_ad_rgb when DRJIT_LIBLLVM_PATH is set, else scalar_rgb; both give the same
expectation. Scenes that use a BSDF lightlab does not have yet are rendered too: their
test is skipped until the BSDF lands. Output: tests/scenes/refs/NAME.exr with R, G, B (the
mean of 8 independent passes, seeds 0-7) and variance.R/G/B (the variance of that mean,
from the spread of the passes), float32. The meshes and textures the scenes use come from
make_meshes.py and are committed.

The references in the repository: Mitsuba 3.9.1, llvm_ad_rgb, 8192 spp
(DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so from Debian's libllvm19).
"""
import argparse
import os
import sys

import mitsuba as mi

# Independent passes per reference (for its variance).
PASSES = 8

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", type=int, default=8192)
    ap.add_argument("--variant", default=None)
    ap.add_argument("names", nargs="*")
    a = ap.parse_args()
    variant = a.variant or ("llvm_ad_rgb" if os.environ.get("DRJIT_LIBLLVM_PATH") else "scalar_rgb")
    mi.set_variant(variant)
    os.makedirs(os.path.join(HERE, "refs"), exist_ok=True)
    names = a.names or sorted(f[:-4] for f in os.listdir(HERE) if f.endswith(".xml"))
    for name in names:
        path = os.path.join(HERE, name + ".xml")
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
