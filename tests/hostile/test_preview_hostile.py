"""The live preview under hostile requests, sent to loopback only, bounded in count and time:
garbage bytes, an oversized request line and headers, a huge body announced, path
traversal, other methods, many idle connections, clients that leave in the middle of an
image. Throughout, the render goes on (its frame keeps changing); afterwards the preview
still answers, and Ctrl-C ends dermis with the interrupted render's status (no crash)."""
import os
import socket
import sys
import time

import pytest

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python", "tests"))
from preview_process import PreviewProcess, long_scene  # noqa: E402


@pytest.fixture
def dermis_binary():
    binary = os.environ.get("DERMIS_BINARY")
    if not binary:
        pytest.skip("DERMIS_BINARY is not set (ctest sets it)")
    return binary


def port_of(url):
    return int(url.rstrip("/").rsplit(":", 1)[1])


def send(port, data, read=True, timeout=5):
    """Sends raw bytes to the preview; returns what it answers (b"" if it closed)."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        try:
            s.sendall(data)
            if not read:
                return b""
            chunks = []
            while True:
                c = s.recv(65536)
                if not c:
                    break
                chunks.append(c)
            return b"".join(chunks)
        except (ConnectionResetError, BrokenPipeError, socket.timeout):
            return b""


def test_hostile_requests_neither_crash_nor_stall_the_render(dermis_binary, tmp_path):
    scene = tmp_path / "scene.pbrt"
    scene.write_text(long_scene(96, 72))
    with PreviewProcess(dermis_binary, [str(scene), "--threads", "1", "-q", "-o", str(tmp_path / "out.exr")]) as p:
        port = port_of(p.url)
        before = p.wait_for(lambda s: s["frame"] > 0, "a first frame")

        send(port, bytes(range(256)) * 64)  # garbage
        answer = send(port, b"GET /" + b"a" * 100_000 + b" HTTP/1.1\r\nHost: x\r\n\r\n")  # request line
        assert not answer.startswith(b"HTTP/1.1 200"), answer[:200]
        answer = send(port, b"GET / HTTP/1.1\r\nHost: x\r\nX: " + b"b" * 1_000_000 + b"\r\n\r\n")  # a header
        assert not answer.startswith(b"HTTP/1.1 200"), answer[:200]
        answer = send(port, b"POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 1000000000000\r\n\r\n" + b"c" * 10000)
        assert not answer.startswith(b"HTTP/1.1 200"), answer[:200]
        for path in (b"/../../../../etc/passwd", b"/%2e%2e/%2e%2e/etc/passwd", b"//etc/passwd", b"/scene.pbrt",
                     b"/" + str(scene).encode(), b"/image.png/../../scene.pbrt", b"/?file=/etc/passwd/.."):
            answer = send(port, b"GET " + path + b" HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
            assert b"root:" not in answer and b"LookAt" not in answer, (path, answer[:300])
            expected = b"HTTP/1.1 200" if path.startswith(b"/?") else b"HTTP/1.1 404"  # "/" with a query: the page
            assert answer.startswith(expected) or answer.startswith(b"HTTP/1.1 400"), (path, answer[:200])
        for method in (b"PUT", b"DELETE", b"OPTIONS", b"TRACE", b"BREW"):
            answer = send(port, method + b" / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
            assert not answer.startswith(b"HTTP/1.1 200"), (method, answer[:200])
        for exposure in (b"1e400", b"nan", b"-inf", b"9" * 5000, b"%00"):
            answer = send(port, b"GET /image.png?exposure=" + exposure + b" HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
            assert answer.startswith(b"HTTP/1.1 400") or answer.startswith(b"HTTP/1.1 414"), (exposure, answer[:200])

        # Many connections left open (more than the server's threads), then closed.
        idle = [socket.create_connection(("127.0.0.1", port), timeout=5) for _ in range(64)]
        time.sleep(0.5)
        for s in idle:
            s.close()
        # Clients that leave in the middle of an image.
        for _ in range(20):
            with socket.create_connection(("127.0.0.1", port), timeout=20) as s:
                s.sendall(b"GET /image.png HTTP/1.1\r\nHost: x\r\n\r\n")
                s.recv(100)

        # The render went on, and the preview answers.
        after = p.wait_for(lambda s: s["frame"] > before["frame"] and s["samples_per_pixel"] > before["samples_per_pixel"],
                           "the render going on", timeout=60)
        assert after["state"] == "rendering"
        assert p.get("image.png")[1:4] == b"PNG"
        assert p.interrupt() == 130  # interrupted during the render: no crash, no signal
