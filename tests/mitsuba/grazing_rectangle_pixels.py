#!/usr/bin/env python3
"""Pixels at the foot of sphere-near-plane's grazing rectangle light: Lambert's analytic
irradiance integrated over each pixel, against Mitsuba 3 (ldsampler and independent) and
lightlab, all on the scene `lightlab export` writes (rectangle light only, 96 x 64).

    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so \\
        python3 tests/mitsuba/grazing_rectangle_pixels.py [--spp 16384] [--lightlab EXE]
        (the default EXE is target/release/lightlab: run `cargo build --release` first)

Needs mitsuba and numpy. Prints one row per pixel. The analytic value: 64 x 64 camera rays
per pixel through Mitsuba's own sensor; a ray that meets the floor in front of the
(one-sided) light adds 0.7/pi * L * E_Lambert / L, one that meets the light adds its
radiance (BENCHMARKS.md, session 20).
"""
import argparse
import os
import re
import subprocess
import tempfile

import mitsuba as mi
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PIXELS = [(77, 49), (76, 50), (78, 51), (78, 52), (78, 54), (78, 55)]
SUB = 64


def lambert(x, n, poly):
    """Irradiance factor E/L at x (normal n) from polygon `poly`, clipped to n's side."""
    clipped = []
    for i in range(len(poly)):
        a, b = poly[i], poly[(i + 1) % len(poly)]
        da, db = n @ (a - x), n @ (b - x)
        if da >= 0:
            clipped.append(a)
        if (da >= 0) != (db >= 0):
            clipped.append(a + (b - a) * (da / (da - db)))
    s = 0.0
    for i in range(len(clipped)):
        a = clipped[i] - x
        b = clipped[(i + 1) % len(clipped)] - x
        a, b = a / np.linalg.norm(a), b / np.linalg.norm(b)
        c = np.cross(a, b)
        if np.linalg.norm(c) > 0:
            s += np.arccos(np.clip(a @ b, -1, 1)) * (n @ (c / np.linalg.norm(c)))
    return 0.5 * abs(s)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", type=int, default=16384)
    ap.add_argument("--lightlab", default=os.path.join(ROOT, "target", "release", "lightlab"))
    a = ap.parse_args()
    folder = tempfile.mkdtemp(prefix="lightlab-grazing-")
    files = {}
    for sampler, flag in (("ldsampler", "sobol"), ("independent", "independent")):
        files[sampler] = os.path.join(folder, sampler + ".xml")
        subprocess.run([a.lightlab, "export", "builtin:sphere-near-plane?emitters=rectangle", "-o",
                        files[sampler], "--width", "96", "--height", "64", "--sampler", flag],
                       check=True, capture_output=True)
    text = open(files["independent"]).read()
    # The light: Mitsuba's rectangle [-1, 1]^2 under the exported to_world.
    rows = re.search(r'<shape type="rectangle">\s*<transform name="to_world">\s*<matrix value="[^"]*"/>'
                     r'.*?<shape type="rectangle">\s*<transform name="to_world">\s*<matrix value="([^"]*)"',
                     text, re.S).group(1)
    m = np.array([float(v) for v in rows.split()]).reshape(4, 4)
    corners = [(m @ np.array([x, y, 0.0, 1.0]))[:3] for x, y in [(-1, -1), (1, -1), (1, 1), (-1, 1)]]
    normal = np.cross(corners[1] - corners[0], corners[3] - corners[0])
    normal /= np.linalg.norm(normal)
    radiance = np.mean([float(v) for v in re.search(r'<emitter type="area">\s*<rgb name="radiance" value="([^"]*)"',
                                                    text).group(1).split(",")])
    mi.set_variant("scalar_rgb")
    scene = mi.load_file(files["independent"])
    sensor = scene.sensors()[0]
    analytic = {}
    for px, py in PIXELS:
        total = 0.0
        for i in range(SUB):
            for j in range(SUB):
                pos = mi.Point2f((px + (i + 0.5) / SUB) / 96, (py + (j + 0.5) / SUB) / 64)
                ray, _ = sensor.sample_ray(0, 0.5, pos, mi.Point2f(0.5, 0.5))
                si = scene.ray_intersect(ray)
                if not si.is_valid():
                    continue
                if si.shape.emitter() is not None:
                    total += radiance if np.array(ray.d) @ normal < 0 else 0.0
                elif (np.array(si.p) - corners[0]) @ normal > 0:
                    total += 0.7 / np.pi * radiance * lambert(np.array(si.p), np.array(si.n), corners)
        analytic[(px, py)] = total / SUB**2
    images = {}
    mi.set_variant("llvm_ad_rgb" if os.environ.get("DRJIT_LIBLLVM_PATH") else "scalar_rgb")
    for sampler, path in files.items():
        img = np.array(mi.render(mi.load_file(path), spp=a.spp))
        images["Mitsuba " + sampler] = img[:, :, :3].mean(axis=2)
    out = os.path.join(folder, "lightlab.pfm")
    subprocess.run([a.lightlab, "render", files["ldsampler"], "--spp", str(a.spp), "-o", out],
                   check=True, capture_output=True)
    mi.set_variant("scalar_rgb")
    images["lightlab (sobol)"] = np.array(mi.Bitmap(out))[:, :, :3].mean(axis=2)
    print("| pixel | analytic | " + " | ".join(images) + " |")
    print("|---|---|" + "---|" * len(images))
    for p in PIXELS:
        print(f"| {p} | {analytic[p]:.3f} | " + " | ".join(f"{im[p[1], p[0]]:.3f}" for im in images.values()) + " |")


if __name__ == "__main__":
    main()
