"""`dermis render --preview` as a child process, for the preview's tests: started, its URL
read from stderr, its status and images fetched, stopped."""
import json
import re
import signal
import subprocess
import threading
import time
import urllib.error
import urllib.request

import pytest


def long_scene(width, height):
    """A subsurface sphere under a sky with a million samples per pixel: a render to watch
    converge, stopped by Ctrl-C long before its samples are done, on any machine."""
    return f"""LookAt 0 -4 1  0 0 0  0 0 1
Camera "perspective" "float fov" 40
Sampler "independent" "integer pixelsamples" 1000000
Film "rgb" "integer xresolution" {width} "integer yresolution" {height}
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5]
Material "subsurface" "rgb sigma_a" [0.2 0.5 1.0] "rgb sigma_s" [3 4 5] "float eta" 1.4
Shape "sphere"
"""


class PreviewProcess:
    """`dermis render ARGS --preview 0`; a thread keeps reading its stderr (`lines`)."""

    def __init__(self, binary, args, url_timeout=30):
        self.proc = subprocess.Popen([binary, "render", *args, "--preview", "0"], stdout=subprocess.DEVNULL,
                                     stderr=subprocess.PIPE, text=True)
        self.lines, self._url, found = [], [], threading.Event()

        def read():
            for line in self.proc.stderr:
                self.lines.append(line)
                m = re.search(r"preview: (http://127\.0\.0\.1:\d+/)", line)
                if m and not self._url:
                    self._url.append(m[1])
                    found.set()
            found.set()  # end of stderr: the process ended

        threading.Thread(target=read, daemon=True).start()
        found.wait(url_timeout)
        if not self._url:
            self.kill()
            pytest.fail(f"no 'preview: http://127.0.0.1:PORT/' line in {url_timeout} s; stderr:\n" + self.stderr())
        self.url = self._url[0]

    def stderr(self):
        return "".join(self.lines)

    def get(self, path, timeout=10):
        """The body of GET path (raises urllib.error.HTTPError on a status other than 2xx)."""
        with urllib.request.urlopen(self.url + path.lstrip("/"), timeout=timeout) as r:
            return r.read()

    def status_code(self, path):
        try:
            with urllib.request.urlopen(self.url + path.lstrip("/"), timeout=10) as r:
                return r.status
        except urllib.error.HTTPError as e:
            return e.code

    def status(self):
        return json.loads(self.get("status.json"))

    def wait_for(self, condition, what, timeout=60):
        """Polls the status until condition(status); returns it, or fails naming `what`."""
        deadline, status = time.monotonic() + timeout, self.status()
        while not condition(status):
            assert self.proc.poll() is None, f"dermis ended while waiting for {what}:\n{self.stderr()}"
            assert time.monotonic() < deadline, f"not {what} in {timeout} s: {status}\n{self.stderr()}"
            time.sleep(0.05)
            status = self.status()
        return status

    def interrupt(self, timeout=10):
        """Ctrl-C; returns the exit status."""
        self.proc.send_signal(signal.SIGINT)
        try:
            return self.proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            pytest.fail(f"dermis did not exit within {timeout} s of SIGINT")

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.kill()  # a failure above: never leave it running
