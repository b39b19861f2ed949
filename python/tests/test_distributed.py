"""lightlab.distributed on a LocalCluster of two worker processes: passes as tasks give
the single render, scene files travel by content, and a lost worker costs only its task."""

import os
import shutil

import cloudpickle
import numpy as np
import pytest

import lightlab
import lightlab.distributed as ld

distributed = pytest.importorskip("distributed")

SIZE = dict(width=32, height=24, threads=1)


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def test_scene_files_travel_by_content(mesh_scene, tmp_path):
    payload = ld.scene_payload(lightlab.load_scene(mesh_scene, spp=2))
    assert set(payload["files"]) == {"mesh_obj.xml", "meshes/torus.obj"}
    assert payload["query"] == "spp=2" and len(payload["sha256"]) == 64
    original = lightlab.render(mesh_scene, defines={"spp": 2}, threads=2)
    shutil.rmtree(mesh_scene.parent)  # the worker's copy must not need the original
    spec = ld.materialize(payload)
    assert payload["sha256"] in spec and ld.materialize(payload) == spec
    np.testing.assert_array_equal(lightlab.render(spec, threads=2).image, original.image)
    assert ld.scene_payload("builtin:assignment") == "builtin:assignment"


def test_a_large_folder_ships_only_the_files_the_scene_names(mesh_scene, monkeypatch):
    (mesh_scene.parent / "unrelated.bin").write_bytes(b"x" * 100)
    (mesh_scene.parent.parent / "outside.obj").write_bytes(b"v 0 0 0\n")
    text = mesh_scene.read_text().replace("</scene>", '<!-- value="../outside.obj" --></scene>')
    mesh_scene.write_text(text)
    assert "unrelated.bin" in ld.scene_payload(mesh_scene)["files"]
    monkeypatch.setattr(ld, "WHOLE_FOLDER_BYTES", 10)
    payload = ld.scene_payload(mesh_scene)
    assert set(payload["files"]) == {"mesh_obj.xml", "meshes/torus.obj"}
    payload["files"]["meshes/torus.obj"] += b"# changed\n"
    with pytest.raises(ValueError, match="does not match its SHA-256"):
        ld.materialize(payload)


def test_distributed_render_equals_the_single_render(client, mesh_scene):
    single = lightlab.render(mesh_scene, spp=12, seed=5, **SIZE)
    merged = ld.render(mesh_scene, spp=12, parts=3, client=client, seed=5, **SIZE)
    assert merged.spp == 12 and merged.settings == single.settings
    np.testing.assert_allclose(merged.image, single.image, rtol=1e-5, atol=1e-6)


class KillOnce(distributed.WorkerPlugin):
    """Kills its worker process when a pass task starts, once (a marker file says so)."""

    def __init__(self, marker):
        self.marker = marker

    def transition(self, key, start, finish, **kwargs):
        name = key if isinstance(key, str) else str(key)
        if finish == "executing" and "lightlab-pass" in name and not os.path.exists(self.marker):
            open(self.marker, "w").close()
            os._exit(1)


def test_a_worker_killed_mid_run_costs_only_its_task(client, tmp_path):
    import sys

    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    marker = str(tmp_path / "killed")
    client.register_plugin(KillOnce(marker), name="kill-once")
    try:
        single = lightlab.render("builtin:assignment", spp=8, **SIZE)
        merged = ld.render("builtin:assignment", spp=8, parts=4, client=client, **SIZE)
    finally:
        client.unregister_worker_plugin("kill-once")
    assert os.path.exists(marker)  # a worker did die
    np.testing.assert_allclose(merged.image, single.image, rtol=1e-5, atol=1e-6)


def test_reference_and_converge_on_the_cluster(client):
    ref = ld.reference("builtin:assignment", rel_error=0.2, client=client, spp=16, **SIZE)
    assert ref.rel_error <= 0.2 and ref.spp % 16 == 0
    rows = ld.converge("builtin:assignment", ["light", "bsdf"], [1, 4], seeds=2,
                       reference_result=ref, client=client, **SIZE)
    assert [(r["label"], r["spp"]) for r in rows] == [("light", 1), ("light", 4),
                                                      ("bsdf", 1), ("bsdf", 4)]
    assert all(r["relmse_min"] <= r["relmse"] <= r["relmse_max"] for r in rows)
    with pytest.raises(ValueError, match="parts=0"):
        ld.render("builtin:assignment", spp=1, parts=0, client=client)
