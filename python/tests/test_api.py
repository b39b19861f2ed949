"""lightlab.render, load_scene, merge, diff, warp and pickling, and their error paths."""

import os
import pickle

import numpy as np
import pytest

import lightlab
from conftest import SCENES, SMALL


def test_render_returns_arrays_settings_and_a_png():
    r = lightlab.render("builtin:assignment", estimator="light", light_sampling="solid-angle",
                        **SMALL)
    assert r.image.shape == (24, 32, 3) and r.image.dtype == np.float32
    assert r.variance.shape == (24, 32, 3) and (r.variance >= 0).all()
    assert r.image.mean() > 0 and np.isfinite(r.image).all()
    assert (r.spp, r.pass_index, r.pass_count) == (4, 0, 1)
    assert "--estimator light" in r.settings and "--light-sampling solid-angle" in r.settings
    assert r.time > 0 and not r.stopped
    assert r._repr_png_().startswith(b"\x89PNG\r\n\x1a\n")


def test_same_seed_same_image_for_any_thread_count():
    a = lightlab.render("builtin:assignment", seed=3, **dict(SMALL, threads=1))
    b = lightlab.render("builtin:assignment", seed=3, **SMALL)
    c = lightlab.render("builtin:assignment", seed=4, **SMALL)
    assert np.array_equal(a.image, b.image) and not np.array_equal(a.image, c.image)


@pytest.mark.parametrize("kw, words", [
    (dict(colour="red"), r"unknown setting `colour` \(accepted: .*light_sampling"),
    (dict(estimator="nope"), r"estimator=nope: .*known: hemisphere, "),
    (dict(light_sampling="solid_angle"), r"light_sampling=solid_angle: .*solid-angle"),
    (dict(spp=0), r"spp=0: .*at least 1"),
    (dict(light_samples=5000), r"light_samples=5000: .*1..=1024"),
    (dict(seed=-1), r"seed=-1"),
    (dict(pass_index=1), r"pass_index and pass_count go together"),
    (dict(pass_index=2, pass_count=2), r"0 <= pass_index < pass_count"),
    (dict(envmap_compensation="maybe"), r"envmap_compensation=maybe: expected True or False"),
    (dict(envmap_compensation=True, estimator="light"), r"envmap-compensation"),
    (dict(threads=0), r"threads=0"),
    (dict(defines=[1]), r"defines="),
])
def test_a_wrong_keyword_or_value_is_a_value_error_naming_it(kw, words):
    with pytest.raises(ValueError, match=words):
        lightlab.render("builtin:assignment", **{**SMALL, **kw})


def test_a_bad_scene_names_file_line_and_column(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text('<scene version="3.0.0">\n  <shape type="sphere">\n'
                   '    <float name="radius" value="abc"/>\n  </shape>\n</scene>\n')
    with pytest.raises(lightlab.SceneError, match=r"bad\.xml:3:\d+: "):
        lightlab.render(bad)
    with pytest.raises(ValueError, match=r"no-such\.xml"):
        lightlab.load_scene(tmp_path / "no-such.xml")
    with pytest.raises(ValueError, match="builtin:nope"):
        lightlab.render("builtin:nope")
    with pytest.raises(ValueError, match="scene=42"):
        lightlab.render(42)


def test_a_loaded_scene_is_reused_with_its_definitions(mesh_scene):
    scene = lightlab.load_scene(mesh_scene, spp=2)
    assert scene.size == (64, 64) and "spp=2" in scene.spec
    a, b = lightlab.render(scene, threads=2), lightlab.render(scene, threads=2)
    assert a.spp == 2 and np.array_equal(a.image, b.image)
    assert lightlab.render(mesh_scene, defines={"spp": 3}, threads=2).spp == 3
    with pytest.raises(ValueError, match="defines= applies to a scene path"):
        lightlab.render(scene, defines={"spp": 3})


def test_merging_all_passes_gives_the_single_render():
    whole = lightlab.render("builtin:assignment", **dict(SMALL, spp=9))
    parts = [lightlab.render("builtin:assignment", pass_index=i, pass_count=3,
                             **dict(SMALL, spp=9)) for i in (2, 0, 1)]
    assert [p.spp for p in parts] == [3, 3, 3] and parts[0].pass_index == 2
    merged = lightlab.merge(parts)
    assert merged.spp == 9 and merged.settings == whole.settings
    assert (merged.pass_index, merged.pass_count) == (0, 1)
    np.testing.assert_allclose(merged.image, whole.image, rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(merged.variance, whole.variance, rtol=1e-3, atol=1e-9)
    with pytest.raises(ValueError, match="at least one"):
        lightlab.merge([])
    with pytest.raises(ValueError, match="cannot merge a 16x12"):
        lightlab.merge([whole, lightlab.render("builtin:assignment",
                                               **dict(SMALL, width=16, height=12))])


def test_results_pickle_exactly():
    r = lightlab.render("builtin:assignment", **SMALL)
    back = pickle.loads(pickle.dumps(r))
    assert np.array_equal(back.image, r.image) and np.array_equal(back.variance, r.variance)
    assert (back.settings, back.spp, back.time) == (r.settings, r.spp, r.time)
    assert back.shadow_rays == r.shadow_rays > 0
    with pytest.raises(ValueError, match="not a lightlab result"):
        lightlab._lightlab._result_from_state(b"nope")


def test_diff_gives_the_cli_metrics():
    r = lightlab.render("builtin:assignment", **SMALL)
    ref = lightlab.render("builtin:assignment", **dict(SMALL, spp=64))
    d = lightlab.diff(r, ref)
    assert set(d) == {"mse", "relmse", "relative_bias", "bias_std_error", "bias_z",
                      "nan_pixels", "inf_pixels"}
    assert d["relmse"] > 0 and d["bias_std_error"] > 0 and abs(d["bias_z"]) < 5
    same = lightlab.diff(r.image, r.image)
    assert same["mse"] == 0 and same["bias_std_error"] is None
    with pytest.raises(ValueError, match=r"reference has shape"):
        lightlab.diff(r.image, r.image[:4])
    with pytest.raises(ValueError, match=r"image has shape \[2, 2\]"):
        lightlab.diff(np.zeros((2, 2)), np.zeros((2, 2)))


def test_warp_samples_and_pdf_values():
    samples, pdf = lightlab.warp("hemisphere-uniform", 1000, seed=1)
    assert samples.shape == (1000, 3) and pdf.shape == (1000,)
    np.testing.assert_allclose(np.linalg.norm(samples, axis=1), 1, atol=1e-5)
    assert (samples[:, 2] >= 0).all()
    np.testing.assert_allclose(pdf, 1 / (2 * np.pi), rtol=1e-5)
    again, _ = lightlab.warp("hemisphere-uniform", 1000, seed=1)
    assert np.array_equal(samples, again)
    with pytest.raises(ValueError, match=r"unknown warp \"nope\" \(known: .*hemisphere-uniform"):
        lightlab.warp("nope", 10)
    with pytest.raises(ValueError, match="n=0"):
        lightlab.warp("hemisphere-uniform", 0)


def test_merge_refuses_the_same_samples_twice():
    part = lightlab.render("builtin:assignment", pass_index=0, pass_count=2, **SMALL)
    with pytest.raises(ValueError, match=r"samples 0:0\.\.2 \(pass 1/2\) overlap samples 0:0\.\.2"):
        lightlab.merge([part, part])
    third = lightlab.render("builtin:assignment", pass_index=0, pass_count=3,
                            **dict(SMALL, spp=6))
    with pytest.raises(ValueError, match="overlap"):
        lightlab.merge([part, third])
    other_seed = lightlab.render("builtin:assignment", **dict(SMALL, seed=7))
    assert lightlab.merge([part, other_seed]).spp == 6


def test_strategy_settings_keep_both_compensation_switches():
    from lightlab._lightlab import strategy_settings
    assert strategy_settings("plain:--estimator mis --no-envmap-compensation") == (
        "plain", [("estimator", "mis"), ("envmap_compensation", "False")])
    assert strategy_settings("comp:--envmap-compensation") == (
        "comp", [("envmap_compensation", "True")])


def test_a_scene_exports_as_mitsuba_xml_that_reads_back(tmp_path):
    scene = lightlab.load_scene("builtin:sphere-near-plane")
    files, notes = scene.export(tmp_path / "snp.xml")
    assert [os.path.basename(f) for f in files] == ["snp_mesh0.ply", "snp.xml"]
    assert notes == []
    back = lightlab.load_scene(str(tmp_path / "snp.xml"))
    a = lightlab.render(scene, **SMALL)
    b = lightlab.render(back, **SMALL)
    assert np.abs(a.image - b.image).max() < 1e-3
    _, notes = lightlab.load_scene("builtin:assignment").export(tmp_path / "a.xml")
    assert any("phong" in n for n in notes)
    textured = lightlab.load_scene(os.path.join(SCENES, "textures_bitmap.xml"))
    with pytest.raises(lightlab.SceneError, match="material-0 is textured"):
        textured.export(tmp_path / "t.xml")
