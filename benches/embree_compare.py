"""Embree 4 (through the `embreex` bindings) on the same mesh and rays as
examples/bvh_compare.rs, so lightlab's Mrays/s can be quoted as a ratio against Embree.

    cargo run --release --features obvhs-compare --example bvh_compare -- --dump DIR
    pip install embreex numpy
    python benches/embree_compare.py DIR

Reads DIR/NAME.{vertices.f32, indices.u32, primary.f32, shadow.f32} (raw little-endian;
rays are 7 floats: origin, direction, t_max) for NAME in 100k and 1M. Reports build time,
closest-hit Mrays/s on the primary rays and occlusion Mrays/s on the shadow rays (median of
5 runs) on one thread and on all threads, and how many rays hit, to compare with the counts
bvh_compare prints. `EmbreeScene.run` loops over single rays (rtcIntersect1/rtcOccluded1) in
native code without the GIL, so all threads run Python threads over equal shares of the rays.
"""

import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
from embreex import mesh_construction, rtcore_scene

RUNS = 5


def median_seconds(f):
    times = []
    for _ in range(RUNS):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return sorted(times)[RUNS // 2]


def mrays(scene, origins, directions, query, dists, threads):
    """Mrays/s of `query` over the rays on `threads` threads (median of RUNS)."""
    shares = np.array_split(np.arange(len(origins)), threads)

    def trace(share):
        kwargs = {} if dists is None else {"dists": dists[share[0] : share[-1] + 1]}
        scene.run(origins[share[0] : share[-1] + 1], directions[share[0] : share[-1] + 1], query=query, **kwargs)

    with ThreadPoolExecutor(threads) as pool:
        seconds = median_seconds(lambda: list(pool.map(trace, shares)))
    return len(origins) / seconds / 1e6


def load_rays(path):
    rays = np.fromfile(path, dtype="<f4").reshape(-1, 7)
    return np.ascontiguousarray(rays[:, 0:3]), np.ascontiguousarray(rays[:, 3:6]), np.ascontiguousarray(rays[:, 6])


def main(directory):
    n = os.cpu_count() or 1
    print(f"| mesh | BVH | build s | closest 1 thr | closest {n} thr | any-hit 1 thr | any-hit {n} thr | primary hits | shadow hits |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name in ["100k", "1M"]:
        base = Path(directory)
        vertices = np.fromfile(base / f"{name}.vertices.f32", dtype="<f4").reshape(-1, 3)
        indices = np.fromfile(base / f"{name}.indices.u32", dtype="<u4").reshape(-1, 3).astype(np.int32)
        p_o, p_d, _ = load_rays(base / f"{name}.primary.f32")
        s_o, s_d, s_t = load_rays(base / f"{name}.shadow.f32")

        start = time.perf_counter()
        scene = rtcore_scene.EmbreeScene()
        mesh_construction.TriangleMesh(scene, vertices, indices)
        # Embree builds lazily at the first query; one ray forces the commit.
        scene.run(p_o[:1], p_d[:1], query="INTERSECT")
        build = time.perf_counter() - start

        closest = [mrays(scene, p_o, p_d, "INTERSECT", None, t) for t in (1, n)]
        occluded = [mrays(scene, s_o, s_d, "OCCLUDED", s_t, t) for t in (1, n)]
        primary_hits = int((scene.run(p_o, p_d, query="INTERSECT") >= 0).sum())
        shadow_hits = int((scene.run(s_o, s_d, dists=s_t, query="OCCLUDED") >= 0).sum())
        print(
            f"| {name} ({len(indices)} tris) | Embree 4 (embreex) | {build:.3f} | "
            f"{closest[0]:.2f} | {closest[1]:.2f} | {occluded[0]:.2f} | {occluded[1]:.2f} | {primary_hits} | {shadow_hits} |"
        )


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
