"""lightlab on a Dask cluster (issue 16): passes as tasks, merged into one image.

``render`` submits one task per pass (``pass_index=i, pass_count=parts``), the same
per-sample streams a single render uses, and merges them into the single render's
image (up to float summation order). ``reference`` adds batches of independent seeds
until the error target is met; ``converge`` spreads strategies x seeds x spp.

Scene files reach the workers by content, not through a shared file system: the XML
and the files of its folder (all of them when the folder is small, else those the XML
names) travel as bytes with their SHA-256, and each worker writes them once into a
temporary folder named by that hash. A task lost with its worker is run again (Dask's
``retries``); passes are deterministic, so the result does not change.
"""

import hashlib
import os
import re
import tempfile

import lightlab

#: Folders up to this size travel whole; larger ones send only the files the XML names.
WHOLE_FOLDER_BYTES = 64 << 20
#: How often Dask runs a task again when its worker is lost.
RETRIES = 2


def _client(client):
    if client is not None:
        return client
    from distributed import get_client

    return get_client()


def _split_spec(spec):
    """``file.xml?a=1`` -> (``file.xml``, ``a=1``) unless a file has that exact name
    (as the library reads scene specs)."""
    if "?" in spec and not os.path.exists(spec):
        path, query = spec.split("?", 1)
        return path, query
    return spec, ""


def _folder_files(xml_path):
    """The files to ship with ``xml_path``, relative to its folder: all of them while the
    folder is small, else the XML and the files it names in ``value``/``filename``
    attributes (a name built from ``$parameters`` is not seen then)."""
    root = os.path.dirname(os.path.abspath(xml_path))
    files, total = [], 0
    for folder, _, names in os.walk(root):
        for name in names:
            path = os.path.join(folder, name)
            total += os.path.getsize(path)
            if total > WHOLE_FOLDER_BYTES:
                return root, _named_files(xml_path, root)
            files.append(os.path.relpath(path, root))
    return root, files


def _named_files(xml_path, root):
    with open(xml_path, encoding="utf-8", errors="replace") as f:
        values = re.findall(r'(?:value|filename)\s*=\s*"([^"]+)"', f.read())
    named = {os.path.normpath(v) for v in values if os.path.isfile(os.path.join(root, v))}
    return sorted(named | {os.path.basename(xml_path)})


def _inside(name):
    """True for a relative path that stays inside its folder."""
    parts = name.split("/")
    return not os.path.isabs(name) and ".." not in parts and name not in ("", ".")


def scene_payload(scene):
    """What a worker needs to load ``scene`` (a path, ``builtin:NAME`` or a
    ``lightlab.Scene``): a ``builtin:`` spec as is, or a dict with the XML's name, its
    definitions, the files as bytes and their SHA-256."""
    spec = scene.spec if isinstance(scene, lightlab.Scene) else os.fspath(scene)
    if spec.startswith("builtin:"):
        return spec
    path, query = _split_spec(spec)
    root, names = _folder_files(path)
    files = {}
    xml = os.path.relpath(os.path.abspath(path), root).replace(os.sep, "/")
    for name in sorted({n.replace(os.sep, "/") for n in names} | {xml}):
        if _inside(name):  # a file outside the scene's folder is not shipped
            with open(os.path.join(root, *name.split("/")), "rb") as f:
                files[name] = f.read()
    return {"xml": xml, "query": query, "files": files, "sha256": _digest(files)}


def _digest(files):
    """SHA-256 over the files' names, lengths and bytes, in name order."""
    digest = hashlib.sha256()
    for name in sorted(files):
        data = files[name]
        digest.update(name.encode() + b"\0" + len(data).to_bytes(8, "little") + data)
    return digest.hexdigest()


def materialize(payload):
    """The scene spec on this machine: writes the payload's files once into
    ``<tmp>/lightlab-scenes/<sha256>/`` (after checking them against the hash) and names the XML."""
    if isinstance(payload, str):
        return payload
    home = os.path.join(tempfile.gettempdir(), "lightlab-scenes", payload["sha256"])
    if not os.path.isdir(home):
        if _digest(payload["files"]) != payload["sha256"]:
            raise ValueError("scene payload does not match its SHA-256")
        os.makedirs(os.path.dirname(home), exist_ok=True)
        staging = tempfile.mkdtemp(prefix="incoming-", dir=os.path.dirname(home))
        for name, data in payload["files"].items():
            if not _inside(name):
                raise ValueError(f"scene payload file {name!r} leaves its folder")
            target = os.path.join(staging, *name.split("/"))
            os.makedirs(os.path.dirname(target), exist_ok=True)
            with open(target, "wb") as f:
                f.write(data)
        try:
            os.rename(staging, home)  # atomic: another task may have written it first
        except OSError:
            if not os.path.isdir(home):
                raise
    spec = os.path.join(home, *payload["xml"].split("/"))
    return f"{spec}?{payload['query']}" if payload["query"] else spec


def render_task(payload, settings):
    """One task: renders the materialized scene with ``settings`` (keywords)."""
    return lightlab.render(materialize(payload), **settings)


def scene_data(payload):
    """A task whose result is the payload: the scheduler keeps its bytes once, and a
    worker lost with the result computes it again (scattered data would be lost)."""
    return payload


def _submit(client, payload, settings_list, key):
    token = payload if isinstance(payload, str) else payload["sha256"]
    shared = client.submit(scene_data, payload, key=f"lightlab-scene-{token}", retries=RETRIES)
    return [
        client.submit(render_task, shared, s, key=f"{key}-{i}", pure=False, retries=RETRIES)
        for i, s in enumerate(settings_list)
    ]


def render(scene, spp, parts, client=None, **settings):
    """Renders ``scene`` at ``spp`` as ``parts`` passes on the cluster and merges them:
    the same result as ``lightlab.render(scene, spp=spp, **settings)`` with the same
    seed (up to float summation order)."""
    if not isinstance(parts, int) or parts < 1:
        raise ValueError(f"parts={parts!r}: expected a whole number >= 1")
    client = _client(client)
    tasks = [{**settings, "spp": spp, "pass_index": i, "pass_count": parts} for i in range(parts)]
    futures = _submit(client, scene_payload(scene), tasks, "lightlab-pass")
    return lightlab.merge(client.gather(futures))


def reference(scene, rel_error=0.01, client=None, spp=64, batch=None, max_spp=1 << 20,
              seed=0, **settings):
    """Adds batches of ``batch`` tasks (default: one per worker) of ``spp`` samples, each
    with its own seed, until the merged image's relative error (``Result.rel_error``,
    as ``lightlab reference`` measures it) is at most ``rel_error`` or ``max_spp`` is
    reached; returns the merged ``Result``."""
    if not rel_error > 0:
        raise ValueError(f"rel_error={rel_error!r}: must be positive")
    client = _client(client)
    batch = batch or max(1, len(client.scheduler_info().get("workers", {})))
    payload = scene_payload(scene)
    total, k = None, 0
    while total is None or (total.rel_error > rel_error and total.spp < max_spp):
        tasks = [{**settings, "spp": spp, "seed": seed + k + j} for j in range(batch)]
        futures = _submit(client, payload, tasks, f"lightlab-reference-{k}")
        parts = client.gather(futures) + ([total] if total is not None else [])
        total = lightlab.merge(parts)
        k += batch
    return total


def converge(scene, strategies, spp_list, seeds=1, reference_result=None, client=None,
             **settings):
    """Renders every strategy (``"label:--flags"`` or a preset) at every spp of
    ``spp_list`` with ``seeds`` seeds as tasks, and measures each against
    ``reference_result`` (default: ``reference(scene, client=client)``); returns one
    dict per (strategy, spp): label, spp, mean time and the relMSE mean, min and max."""
    from lightlab._lightlab import strategy_settings

    client = _client(client)
    if reference_result is None:
        reference_result = reference(scene, client=client, **settings)
    labels = lightlab._strategies(strategies)
    jobs, tasks = [], []
    for label in labels:
        name, patch = strategy_settings(label)
        for spp in spp_list:
            for s in range(seeds):
                jobs.append((name, spp))
                tasks.append({**settings, **dict(patch), "spp": spp, "seed": s})
    results = client.gather(_submit(client, scene_payload(scene), tasks, "lightlab-converge"))
    rows = {}
    for (name, spp), r in zip(jobs, results):
        e = lightlab.diff(r.image, reference_result.image)["relmse"]
        rows.setdefault((name, spp), []).append((e, r.time))
    return [
        {
            "label": name,
            "spp": spp,
            "time": sum(t for _, t in v) / len(v),
            "relmse": sum(e for e, _ in v) / len(v),
            "relmse_min": min(e for e, _ in v),
            "relmse_max": max(e for e, _ in v),
        }
        for (name, spp), v in rows.items()
    ]
