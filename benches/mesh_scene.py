#!/usr/bin/env python3
"""Mitsuba 3 scenes around the benchmark meshes that examples/bvh_compare.rs dumps (the
bumpy sphere of 10^5 and 10^6 triangles), so the renderer's mesh path can be timed against
Mitsuba with benches/mitsuba_compare.py on the same meshes the ray benchmarks use.

    cargo run --release --features obvhs-compare --example bvh_compare -- --dump DIR
    python3 benches/mesh_scene.py DIR OUT        # writes OUT/bumpy_{100k,1M}.{ply,xml}
    python3 benches/mitsuba_compare.py --spp 64 OUT/bumpy_1M.xml OUT/bumpy_100k.xml

Each scene: the mesh (flat-shaded diffuse) on a diffuse floor under one rectangle light,
320x240, independent sampler, box filter.
"""
import array
import os
import sys

SCENE = """<scene version="3.0.0">
    <default name="spp" value="16"/>
    <integrator type="path"><integer name="max_depth" value="2"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 2.2, 4" target="0, 0, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="320"/>
            <integer name="height" value="240"/>
            <rfilter type="box"/>
        </film>
    </sensor>
    <shape type="ply">
        <string name="filename" value="bumpy_{name}.ply"/>
        <boolean name="face_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.5, 0.3"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/><translate y="-1.1"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.5, 0.5"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.6"/><rotate x="1" angle="120"/><translate y="2.5" z="-0.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="20, 20, 20"/></emitter>
    </shape>
</scene>
"""


def read(path, code):
    values = array.array(code)
    with open(path, "rb") as f:
        values.frombytes(f.read())
    return values


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: mesh_scene.py DUMP_DIR OUT_DIR")
    if sys.byteorder != "little":
        sys.exit("mesh_scene.py: the dump and the PLY files are little-endian; run it on such a host")
    dump, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    for name in ["100k", "1M"]:
        vertices = read(os.path.join(dump, f"{name}.vertices.f32"), "f")
        indices = read(os.path.join(dump, f"{name}.indices.u32"), "I")
        header = (
            "ply\nformat binary_little_endian 1.0\n"
            f"element vertex {len(vertices) // 3}\n"
            "property float x\nproperty float y\nproperty float z\n"
            f"element face {len(indices) // 3}\n"
            "property list uchar int vertex_indices\nend_header\n"
        )
        with open(os.path.join(out, f"bumpy_{name}.ply"), "wb") as f:
            f.write(header.encode())
            f.write(vertices.tobytes())
            for k in range(0, len(indices), 3):
                f.write(b"\x03")
                f.write(array.array("i", indices[k : k + 3]).tobytes())
        with open(os.path.join(out, f"bumpy_{name}.xml"), "w") as f:
            f.write(SCENE.replace("{name}", name))
        print(f"{out}/bumpy_{name}.xml: {len(indices) // 3} triangles")


if __name__ == "__main__":
    main()
