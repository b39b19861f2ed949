#!/usr/bin/env python3
"""Renders the reference EXR of every scene in tests/scenes/ with Mitsuba 3.

Usage: python3 tests/scenes/make_refs.py [--spp N] [--variant V] [NAME ...]

Each scene's `$spp` default is replaced by --spp (default 8192). The variant defaults
to llvm_ad_rgb when DRJIT_LIBLLVM_PATH is set, else scalar_rgb; both give the same
expectation. Scenes that use a BSDF lightlab does not have yet are rendered too: their
test is skipped until the BSDF lands. Output: tests/scenes/refs/NAME.exr (RGB, float32).
"""
import argparse
import os
import sys

import mitsuba as mi

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
        # Seed 0 for a reproducible reference.
        image = mi.render(scene, spp=a.spp, seed=0)
        out = os.path.join(HERE, "refs", name + ".exr")
        mi.Bitmap(image).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False).write(out)
        print(f"{name}: {variant}, {a.spp} spp -> {out}", file=sys.stderr)


if __name__ == "__main__":
    main()
