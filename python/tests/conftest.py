"""Shared pieces of the Python tests: the repository's test scenes and a small render."""

import os
import shutil

import pytest

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "scenes")
#: A small, quick render of the assignment scene.
SMALL = dict(spp=4, width=32, height=24, threads=2)


@pytest.fixture
def mesh_scene(tmp_path):
    """A copy of tests/scenes/mesh_obj.xml with the mesh it names, in its own folder."""
    folder = tmp_path / "scene"
    (folder / "meshes").mkdir(parents=True)
    shutil.copy(os.path.join(SCENES, "mesh_obj.xml"), folder / "mesh_obj.xml")
    shutil.copy(os.path.join(SCENES, "meshes", "torus.obj"), folder / "meshes" / "torus.obj")
    return folder / "mesh_obj.xml"
