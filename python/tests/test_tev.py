"""The live view: tev's IPC packets, checked by a small fake tev that parses them."""

import socket
import struct
import threading
import warnings

import numpy as np
import pytest

import lightlab
import lightlab.tev

# tev's packet types (tev src/Ipc.cpp, IpcPacket::Type), written here independently of
# the code under test.
CREATE_IMAGE, UPDATE_IMAGE_V3 = 4, 6


def read_string(body, i):
    end = body.index(b"\0", i)
    return body[i:end].decode(), end + 1


def parse(kind, body):
    """One packet's fields, as tev reads them (tev src/Ipc.cpp)."""
    grab_focus = body[0] == 1
    name, i = read_string(body, 1)
    if kind == CREATE_IMAGE:
        w, h, n = struct.unpack_from("<iii", body, i)
        i += 12
        channels = []
        for _ in range(n):
            c, i = read_string(body, i)
            channels.append(c)
        return dict(kind="create", focus=grab_focus, name=name, size=(w, h), channels=channels)
    assert kind == UPDATE_IMAGE_V3, kind
    (n,) = struct.unpack_from("<i", body, i)
    i += 4
    channels = []
    for _ in range(n):
        c, i = read_string(body, i)
        channels.append(c)
    x, y, w, h = struct.unpack_from("<4i", body, i)
    i += 16
    offsets = struct.unpack_from(f"<{n}q", body, i)
    strides = struct.unpack_from(f"<{n}q", body, i + 8 * n)
    data = np.frombuffer(body[i + 16 * n:], dtype="<f4")
    image = np.stack([data[o::s][: w * h] for o, s in zip(offsets, strides)], axis=-1)
    assert len(data) == max(o + (w * h - 1) * s + 1 for o, s in zip(offsets, strides))
    return dict(kind="update", name=name, channels=channels, origin=(x, y),
                image=image.reshape(h, w, n))


class FakeTev:
    """Accepts connections on a free port and parses every packet it receives."""

    def __init__(self):
        self.server = socket.create_server(("127.0.0.1", 0))
        self.address = "127.0.0.1:%d" % self.server.getsockname()[1]
        self.packets = []
        self.thread = threading.Thread(target=self.serve, daemon=True)
        self.thread.start()

    def serve(self):
        self.server.settimeout(30)
        try:
            while True:
                conn, _ = self.server.accept()
                with conn:
                    self.read(conn)
        except OSError:
            return

    def read(self, conn):
        buf = b""
        while True:
            chunk = conn.recv(1 << 16)
            if not chunk:
                return
            buf += chunk
            while len(buf) >= 4 and len(buf) >= struct.unpack_from("<I", buf)[0]:
                (size,) = struct.unpack_from("<I", buf)
                self.packets.append(parse(buf[4], buf[5:size]))
                buf = buf[size:]

    def close(self):
        self.server.close()


def test_a_render_refines_in_a_fake_tev():
    tev = FakeTev()
    r = lightlab.render("builtin:assignment", spp=64, width=32, height=24, threads=2,
                        display=tev.address)
    tev.thread.join(timeout=1)  # the render's connection is closed: its packets are in
    tev.close()
    create, *updates = tev.packets
    assert create == dict(kind="create", focus=True, name=r.scene, size=(32, 24),
                          channels=["R", "G", "B"])
    assert len(updates) >= 2 and all(u["channels"] == ["R", "G", "B"] for u in updates)
    # Frames refine towards the final image, which is the last one sent.
    np.testing.assert_array_equal(updates[-1]["image"], r.image)
    errors = [np.abs(u["image"] - r.image).mean() for u in updates]
    assert errors[0] > errors[-1] == 0


def test_a_refused_connection_is_a_warning_not_a_failure(capfd):
    with socket.socket() as s:  # a port nothing listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    r = lightlab.render("builtin:assignment", spp=2, width=8, height=6,
                        display=f"127.0.0.1:{port}")
    assert r.spp == 2
    assert "warning: no live view: cannot reach tev" in capfd.readouterr().err
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert not lightlab.tev.show(r, address=f"127.0.0.1:{port}")
    assert "cannot reach tev" in str(caught[0].message)


def test_show_sends_an_image():
    tev = FakeTev()
    image = np.random.default_rng(1).random((3, 5, 3), dtype=np.float32)
    assert lightlab.tev.show(image, name="x", address=tev.address)
    deadline = threading.Event()
    for _ in range(100):
        if len(tev.packets) == 2:
            break
        deadline.wait(0.02)
    tev.close()
    assert tev.packets[0]["size"] == (5, 3)
    np.testing.assert_array_equal(tev.packets[1]["image"], image)
    with pytest.raises(ValueError, match=r"image has shape \[3, 5\]"):
        lightlab.tev.show(image[..., 0], address=tev.address)
