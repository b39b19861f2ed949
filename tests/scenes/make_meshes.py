#!/usr/bin/env python3
"""Writes the small meshes and textures the conformance scenes use (run once; outputs are
committed): meshes/torus.obj (no normals: Mitsuba smooths it), meshes/ball.ply (binary,
normals and uv), meshes/shapes.serialized (two shapes, version 4, zlib), and
textures/checker.png, textures/quadrants.jpg (flat 8x8 blocks; JPEG decoders still differ by
up to 2 codes per channel, IDCT and chroma rounding, so scenes that show a texture directly
use PNG), textures/spots.png (a dim field with one bright 2x2 spot), textures/ramp.exr and textures/sky.exr (a lat-long sky with a small sun; needs Pillow and
mitsuba). meshes/quad_uv.obj is written by hand."""
import math
import os
import struct
import zlib

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "meshes")


def torus(R=0.7, r=0.25, nu=20, nv=10):
    v, f = [], []
    for i in range(nu):
        for j in range(nv):
            a, b = 2 * math.pi * i / nu, 2 * math.pi * j / nv
            v.append(((R + r * math.cos(b)) * math.cos(a), r * math.sin(b), (R + r * math.cos(b)) * math.sin(a)))
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
            f.append((a, d, c, b))  # quads: fan-triangulated by the loaders
    return v, f


def ball(nu=16, nv=8):
    v, n, uv, f = [], [], [], []
    for j in range(nv + 1):
        for i in range(nu + 1):
            t, p = math.pi * j / nv, 2 * math.pi * i / nu
            d = (math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p))
            v.append(d), n.append(d), uv.append((i / nu, j / nv))
    for j in range(nv):
        for i in range(nu):
            a, b = j * (nu + 1) + i, (j + 1) * (nu + 1) + i
            f.append((a, a + 1, b + 1)), f.append((a, b + 1, b))
    return v, n, uv, f


def serialized_shape(v, f):
    body = struct.pack("<I", 0x1000) + b"shape\0" + struct.pack("<QQ", len(v), len(f))
    body += b"".join(struct.pack("<3f", *p) for p in v)
    body += b"".join(struct.pack("<3I", *t) for t in f)
    return struct.pack("<HH", 0x041C, 4) + zlib.compress(body)


def main():
    os.makedirs(HERE, exist_ok=True)
    v, f = torus()
    with open(os.path.join(HERE, "torus.obj"), "w") as out:
        out.write("# torus, quads, no normals\n")
        out.writelines(f"v {x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in v)
        out.writelines("f " + " ".join(str(i + 1) for i in q) + "\n" for q in f)
    v, n, uv, f = ball()
    with open(os.path.join(HERE, "ball.ply"), "wb") as out:
        out.write((f"ply\nformat binary_little_endian 1.0\nelement vertex {len(v)}\n"
                   "property float x\nproperty float y\nproperty float z\n"
                   "property float nx\nproperty float ny\nproperty float nz\n"
                   "property float u\nproperty float v\n"
                   f"element face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n").encode())
        for p, q, t in zip(v, n, uv):
            out.write(struct.pack("<8f", *p, *q, *t))
        for t in f:
            out.write(struct.pack("<B3i", 3, *t))
    # A pyramid (shape 0) and a tetrahedron (shape 1); the file ends with the offsets.
    pyramid = ([(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1), (0, 1.2, 0)],
               [(0, 4, 1), (1, 4, 2), (2, 4, 3), (3, 4, 0), (0, 1, 2), (0, 2, 3)])
    tet = ([(-0.8, 0, -0.6), (0.8, 0, -0.6), (0, 0, 0.8), (0, 1.1, 0)],
           [(0, 3, 1), (1, 3, 2), (2, 3, 0), (0, 1, 2)])
    blobs = [serialized_shape(*pyramid), serialized_shape(*tet)]
    data, offsets = b"", []
    for b in blobs:
        offsets.append(len(data))
        data += b
    data += b"".join(struct.pack("<Q", o) for o in offsets) + struct.pack("<I", len(blobs))
    with open(os.path.join(HERE, "shapes.serialized"), "wb") as out:
        out.write(data)


def textures():
    from PIL import Image
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    d = os.path.join(os.path.dirname(HERE), "textures")
    os.makedirs(d, exist_ok=True)
    im = Image.new("RGB", (8, 8))
    for y in range(8):
        for x in range(8):
            im.putpixel((x, y), (230, 200, 60) if (x + y) % 2 == 0 else (40, 90, 180))
    im.save(os.path.join(d, "checker.png"))
    im = Image.new("RGB", (16, 16))
    cols = [(200, 60, 60), (60, 200, 60), (60, 60, 200), (220, 220, 220)]
    for y in range(16):
        for x in range(16):
            im.putpixel((x, y), cols[(y // 8) * 2 + x // 8])
    im.save(os.path.join(d, "quadrants.jpg"), quality=95)
    im = Image.new("RGB", (16, 8), (40, 40, 60))
    for y in (2, 3):
        for x in (5, 6):
            im.putpixel((x, y), (255, 230, 150))
    im.save(os.path.join(d, "spots.png"))
    ramp = []
    for y in range(2):
        for x in range(4):
            ramp += [0.1 + 0.25 * x, 0.2 + 0.3 * y, 0.5]
    mi.Bitmap(mi.TensorXf(ramp, (2, 4, 3))).write(os.path.join(d, "ramp.exr"))
    W, H, sky = 32, 16, []
    for j in range(H):
        for i in range(W):
            t = j / (H - 1)
            rgb = [0.3 + 0.5 * (1 - t), 0.4 + 0.5 * (1 - t), 0.8 * (1 - t) + 0.1]
            if abs(i - 20) <= 1 and abs(j - 4) <= 1:
                rgb = [20, 18, 14]
            sky += rgb
    mi.Bitmap(mi.TensorXf(sky, (H, W, 3))).write(os.path.join(d, "sky.exr"))


if __name__ == "__main__":
    main()
    textures()
