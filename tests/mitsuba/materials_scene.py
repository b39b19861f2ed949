"""Renders lightlab's `builtin:materials` scene with Mitsuba 3 (scalar_rgb, direct
lighting) and compares it with lightlab renders, sphere by sphere.

    lightlab render builtin:materials --estimator light --spp 256 -o /tmp/ll-light.pfm
    lightlab render builtin:materials --estimator bsdf  --spp 1024 -o /tmp/ll-bsdf.pfm
    python3 tests/mitsuba/materials_scene.py /tmp/ll-light.pfm /tmp/ll-bsdf.pfm

Measured (lightlab 256/1024 spp, Mitsuba 256 spp): mean over each sphere agrees within
0.6% (Au mirror +0.6%, Cu GGX 0.1 0.0%, Al Beckmann 0.3 -0.1%, roughplastic -0.1%,
plastic +0.5%).

Rough spheres are compared with the light-sampled render, smooth (Dirac) ones with the
BSDF-sampled render, since lightlab's light estimator cannot see Dirac lobes.
"""
import struct
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")

W, H = 384, 256


def rect(o, ea, eb, bsdf, emitter=None):
    o, ea, eb = (mi.ScalarVector3f(v) for v in (o, ea, eb))
    n = dr_normalize(cross(ea, eb))
    c = o + 0.5 * ea + 0.5 * eb
    m = [[ea[i] / 2, eb[i] / 2, n[i], c[i]] for i in range(3)] + [[0, 0, 0, 1]]
    d = {"type": "rectangle", "to_world": mi.ScalarTransform4f(m), "bsdf": bsdf}
    if emitter:
        d["emitter"] = emitter
    return d


def cross(a, b):
    return mi.ScalarVector3f(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dr_normalize(v):
    n = (v[0] ** 2 + v[1] ** 2 + v[2] ** 2) ** 0.5
    return mi.ScalarVector3f(v[0] / n, v[1] / n, v[2] / n)


rgb = lambda r, g, b: {"type": "rgb", "value": [r, g, b]}
grey = {"type": "diffuse", "reflectance": rgb(0.5, 0.5, 0.5)}
black = {"type": "diffuse", "reflectance": rgb(0, 0, 0)}
spheres = [
    {"type": "conductor", "material": "Au"},
    {"type": "roughconductor", "material": "Cu", "distribution": "ggx", "alpha": 0.1},
    {"type": "roughconductor", "material": "Al", "distribution": "beckmann", "alpha": 0.3},
    {"type": "roughplastic", "distribution": "ggx", "alpha": 0.2, "diffuse_reflectance": rgb(0.1, 0.2, 0.6)},
    {"type": "plastic", "diffuse_reflectance": rgb(0.6, 0.1, 0.1)},
]
scene = {
    "type": "scene",
    "integrator": {"type": "direct", "emitter_samples": 1, "bsdf_samples": 1},
    "camera": {
        "type": "perspective",
        "fov": 45.0,
        "fov_axis": "x",
        "to_world": mi.ScalarTransform4f().look_at(origin=[0, 1.4, 5.0], target=[0, 0.45, 0], up=[0, 1, 0]),
        "film": {"type": "hdrfilm", "width": W, "height": H, "rfilter": {"type": "box"}},
        "sampler": {"type": "independent", "sample_count": 256},
    },
    "floor": rect([-3, 0, 3], [6, 0, 0], [0, 0, -6], grey),
    "wall": rect([-3, 0, -3], [6, 0, 0], [0, 6, 0], grey),
    "light": rect([-0.5, 2.4, 1.2], [1, 0, 0], [0, 0, 1], black,
                  {"type": "area", "radiance": rgb(6, 6, 6)}),
}
for i, b in enumerate(spheres):
    scene[f"sphere{i}"] = {"type": "sphere", "center": [-1.8 + 0.9 * i, 0.4, 0], "radius": 0.4, "bsdf": b}

image = mi.render(mi.load_dict(scene))
mi.Bitmap(image).write("/tmp/mitsuba-materials.exr")
mi.Bitmap(image).write("/tmp/mitsuba-materials.pfm")


def read_pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        fmt = "<" if scale < 0 else ">"
        data = struct.unpack(fmt + "f" * (w * h * 3), f.read(w * h * 12))
    # PFM rows run bottom to top.
    return [[[data[((h - 1 - y) * w + x) * 3 + c] for c in range(3)] for x in range(w)] for y in range(h)]


def project(p):
    """Pixel of world point p for the scene's camera (lightlab's look-at, fov_x 45°)."""
    import math
    o, t = [0, 1.4, 5.0], [0, 0.45, 0]
    d = [t[i] - o[i] for i in range(3)]
    n = math.sqrt(sum(x * x for x in d)); d = [x / n for x in d]
    up = [0, 1, 0]
    left = [up[1] * d[2] - up[2] * d[1], up[2] * d[0] - up[0] * d[2], up[0] * d[1] - up[1] * d[0]]
    n = math.sqrt(sum(x * x for x in left)); left = [x / n for x in left]
    new_up = [d[1] * left[2] - d[2] * left[1], d[2] * left[0] - d[0] * left[2], d[0] * left[1] - d[1] * left[0]]
    v = [p[i] - o[i] for i in range(3)]
    z = sum(v[i] * d[i] for i in range(3))
    x = sum(v[i] * left[i] for i in range(3)) / z
    y = sum(v[i] * new_up[i] for i in range(3)) / z
    tx = math.tan(math.radians(22.5)); ty = tx * H / W
    return (1 - x / tx) * W / 2, (1 - y / ty) * H / 2


def sphere_mean(img, i):
    cx, cy = project([-1.8 + 0.9 * i, 0.4, 0])
    r = 0.6 * 0.4 / 5.0 * W / 2 / 0.414  # well inside the sphere's disk
    total, count = [0.0] * 3, 0
    for y in range(int(cy - r), int(cy + r) + 1):
        for x in range(int(cx - r), int(cx + r) + 1):
            if (x - cx) ** 2 + (y - cy) ** 2 <= r * r:
                for c in range(3):
                    total[c] += img[y][x][c]
                count += 1
    return [t / count for t in total]


mitsuba = read_pfm("/tmp/mitsuba-materials.pfm")
light, bsdf = read_pfm(sys.argv[1]), read_pfm(sys.argv[2])
names = ["conductor Au", "roughconductor Cu ggx 0.1", "roughconductor Al beckmann 0.3",
         "roughplastic ggx 0.2", "plastic"]
for i, name in enumerate(names):
    ours = sphere_mean(bsdf if i in (0, 4) else light, i)
    theirs = sphere_mean(mitsuba, i)
    rel = [ours[c] / theirs[c] - 1 for c in range(3)]
    print(f"{name:32} lightlab {[round(v, 4) for v in ours]} mitsuba {[round(v, 4) for v in theirs]} "
          f"rel diff {[f'{v:+.3f}' for v in rel]}")
