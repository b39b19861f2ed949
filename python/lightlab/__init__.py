"""lightlab from Python: render, merge, diff, warp, compare and converge (issue 16).

Keyword names and values are the command line's, with ``_`` for ``-``
(``light_sampling="solid-angle"`` is ``--light-sampling solid-angle``); a wrong one
raises ``ValueError`` naming it and the accepted values. ``pass_index`` is 0-based
(``range(pass_count)``); the command line's ``--pass I/N`` is 1-based.

    import lightlab
    r = lightlab.render("builtin:assignment", spp=16, estimator="light")
    r.image        # numpy float32 H x W x 3
    lightlab.diff(r, reference)["relmse"]
"""

import os
import tempfile

import numpy as np

from . import _lightlab
from ._lightlab import Result, Scene, SceneError

__all__ = [
    "Result",
    "Scene",
    "SceneError",
    "SETTINGS",
    "compare",
    "converge",
    "diff",
    "load_scene",
    "merge",
    "render",
    "warp",
]

#: The render settings every function takes as keywords (from the library's flag table).
SETTINGS = tuple(_lightlab.SETTINGS)


def _flags(settings):
    """(keyword, text) pairs for the settings that are not None; unknown keywords are
    reported by the library with the accepted ones."""
    return [(k, str(v)) for k, v in settings.items() if v is not None]


def _defines(defines):
    if defines is None:
        return []
    if not isinstance(defines, dict):
        raise ValueError(f"defines={defines!r}: expected a dict of name -> value")
    return [(str(k), str(v)) for k, v in defines.items()]


def load_scene(path, **defines):
    """Loads a Mitsuba XML file (with ``-D name=value`` definitions as keywords) or a
    ``builtin:NAME`` scene once, to reuse across renders. A scene that does not load
    raises ``SceneError`` (a ``ValueError``) whose text has ``file:line:col``."""
    return _lightlab.load_scene(os.fspath(path), _defines(defines))


def _scene(scene, defines=None):
    if isinstance(scene, Scene):
        if defines:
            raise ValueError("defines= applies to a scene path, not to a loaded Scene")
        return scene
    if isinstance(scene, (str, os.PathLike)):
        return _lightlab.load_scene(os.fspath(scene), _defines(defines))
    raise ValueError(f"scene={scene!r}: expected a path, 'builtin:NAME' or a lightlab.Scene")


def render(scene="builtin:assignment", spp=None, width=None, height=None, seed=None,
           threads=None, estimator=None, mis=None, light_samples=None, bsdf_samples=None,
           light_sampling=None, light_select=None, sampler=None, envmap_compensation=None,
           pass_index=None, pass_count=None, defines=None, display=None, **unknown):
    """Renders ``scene`` (a path, ``builtin:NAME`` or a ``lightlab.Scene``) and returns a
    ``Result`` (``.image``, ``.variance``, ``.spp``, ``.time``, ``.settings``, ...).

    The GIL is released while rendering on ``threads`` workers (default: all cores);
    Ctrl-C raises ``KeyboardInterrupt``. ``display="HOST:PORT"`` shows every round in a
    running tev viewer (a viewer that cannot be reached is a warning)."""
    settings = dict(spp=spp, width=width, height=height, seed=seed, estimator=estimator,
                    mis=mis, light_samples=light_samples, bsdf_samples=bsdf_samples,
                    light_sampling=light_sampling, light_select=light_select,
                    sampler=sampler, envmap_compensation=envmap_compensation,
                    pass_index=pass_index, pass_count=pass_count, **unknown)
    if threads is not None and (not isinstance(threads, int) or threads < 1):
        raise ValueError(f"threads={threads!r}: expected a whole number >= 1")
    loaded = _scene(scene, defines)
    return _lightlab.render(loaded, _flags(settings), threads, display)


def merge(results):
    """Merges results of the same image: all passes of one render give that render (up
    to float summation order); renders with other seeds add their samples."""
    results = list(results)
    if not all(isinstance(r, Result) for r in results):
        raise ValueError("merge takes lightlab.Result objects")
    return _lightlab.merge(results)


def _pixels(x, name):
    if isinstance(x, Result):
        return x.image, x.variance
    try:
        return np.ascontiguousarray(x, dtype=np.float32), None
    except (TypeError, ValueError) as e:
        raise ValueError(f"{name}: expected a lightlab.Result or an H x W x 3 array ({e})")


def diff(image, reference):
    """The command line's ``diff`` metrics of ``image`` against ``reference`` (each a
    ``Result`` or an H x W x 3 array) as a dict: mse, relmse, relative_bias,
    bias_std_error and bias_z (from the results' variances), nan_pixels, inf_pixels."""
    v, var = _pixels(image, "image")
    r, rvar = _pixels(reference, "reference")
    return _lightlab.diff(v, r, var, rvar)


def warp(name, n=10000, seed=1):
    """``n`` samples of the warp ``name`` (``lightlab warp --list``) and the pdf values
    it claims: (n x 3 array, n array)."""
    if not isinstance(n, int) or n < 1:
        raise ValueError(f"n={n!r}: expected a whole number >= 1")
    return _lightlab.warp(name, n, seed)


def _strategies(strategies):
    if isinstance(strategies, str):
        strategies = [s for s in strategies.split(",") if s.strip()]
    return [str(s) for s in strategies]


def _scene_spec(scene):
    return scene.spec if isinstance(scene, Scene) else os.fspath(scene)


def _lab(run, scene, output, **kw):
    if output is not None:
        return run(_scene_spec(scene), output=os.fspath(output), **kw)
    with tempfile.TemporaryDirectory(prefix="lightlab-") as folder:
        return run(_scene_spec(scene), output=folder, **kw)


def compare(scene, strategies, spp=None, time=None, reference=None, reference_spp=1024,
            output=None, threads=None, **settings):
    """``lightlab compare``: each strategy (``"label:--flags"`` or a preset such as
    ``"light"``) at ``spp`` or for ``time`` seconds against a reference; returns the
    table as a list of dicts and writes the HTML report into ``output`` when given."""
    return _lab(_lightlab.compare, scene, output, strategies=_strategies(strategies),
                spp=spp, time=time,
                reference=None if reference is None else os.fspath(reference),
                reference_spp=reference_spp, flags=_flags(settings), threads=threads)


def converge(scene, strategies, max_spp, seeds=1, reference=None, reference_spp=1024,
             output=None, threads=None, **settings):
    """``lightlab converge``: relMSE against spp and time per strategy; returns one dict
    per (strategy, spp) and writes the HTML report into ``output`` when given."""
    return _lab(_lightlab.converge, scene, output, strategies=_strategies(strategies),
                max_spp=max_spp, seeds=seeds,
                reference=None if reference is None else os.fspath(reference),
                reference_spp=reference_spp, flags=_flags(settings), threads=threads)
