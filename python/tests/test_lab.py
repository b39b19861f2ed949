"""lightlab.compare and lightlab.converge: tables as dicts, reports in a folder."""

import pytest

import lightlab

TINY = dict(width=16, height=12, threads=2)


def test_compare_returns_the_table_and_writes_the_report(tmp_path):
    rows = lightlab.compare("builtin:assignment", ["light", "bsdf"], spp=2, reference_spp=16,
                            output=tmp_path / "cmp", **TINY)
    assert [r["label"] for r in rows] == ["light", "bsdf"]
    assert all(r["spp"] == 2 and r["relmse"] > 0 and r["time"] > 0 for r in rows)
    assert (tmp_path / "cmp" / "index.html").exists()
    # Without a folder the report goes to a temporary one; strategies may be one string.
    assert len(lightlab.compare("builtin:assignment", "light,cosine", spp=1, reference_spp=4,
                                **TINY)) == 2


def test_converge_returns_one_row_per_strategy_and_spp(tmp_path):
    rows = lightlab.converge("builtin:assignment", ["light"], max_spp=4, reference_spp=16,
                             output=tmp_path / "conv", **TINY)
    assert [r["spp"] for r in rows] == [1, 2, 4]
    assert all(r["relmse_min"] <= r["relmse"] <= r["relmse_max"] for r in rows)
    assert (tmp_path / "conv" / "index.html").exists()


@pytest.mark.parametrize("call, words", [
    (lambda: lightlab.compare("builtin:assignment", ["nope"], spp=1, **TINY), "strategy \"nope\""),
    (lambda: lightlab.compare("builtin:assignment", [], spp=1, **TINY), "at least one"),
    (lambda: lightlab.compare("builtin:assignment", ["light"], **TINY), "give spp=N or time"),
    (lambda: lightlab.compare("builtin:assignment", ["light"], time=1e300, **TINY),
     "at most 1.8e19 seconds, not 1e300"),
    (lambda: lightlab.compare("builtin:assignment", ["light"], time=-1.0, **TINY), "not -1"),
    (lambda: lightlab.compare("builtin:assignment", ["light"], spp=1, colour=1), "colour"),
    (lambda: lightlab.converge("builtin:assignment", ["light"], max_spp=0), "max_spp"),
    (lambda: lightlab.converge("builtin:nope", ["light"], max_spp=1, **TINY), "builtin:nope"),
])
def test_lab_errors_are_value_errors(call, words):
    with pytest.raises(ValueError, match=words):
        call()
