"""The tev image viewer from Python (issue 16).

``lightlab.render(..., display="HOST:PORT")`` shows a render live: the library sends
tev's IPC packets (tev ``src/Ipc.cpp``, as pbrt-v4's ``--display-server`` does) from a
background thread after every round. ``show`` sends any image the same way, for
instance a merged result or a difference image.
"""

import socket
import warnings

import numpy as np

from . import _lightlab

#: tev listens here unless started with ``--hostname``.
DEFAULT_ADDRESS = "127.0.0.1:14158"


def show(image, name="lightlab", address=DEFAULT_ADDRESS, timeout=2.0):
    """Sends ``image`` (a ``lightlab.Result`` or an H x W x 3 array) to tev at
    ``address`` as image ``name``; returns False, with a warning, when tev cannot be
    reached."""
    pixels = np.ascontiguousarray(getattr(image, "image", image), dtype=np.float32)
    create, update = _lightlab.tev_packets(name, pixels)
    host, _, port = address.rpartition(":")
    try:
        with socket.create_connection((host, int(port)), timeout=timeout) as s:
            s.sendall(create + update)
        return True
    except (OSError, ValueError) as e:
        warnings.warn(f"cannot reach tev at {address}: {e}")
        return False
