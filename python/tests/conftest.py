"""Shared fixtures of the module's tests: a small subsurface scene, the dermis binary."""
import atexit
import os
import shutil
import sys
import tempfile
import threading
import time

import pytest

# Never the user's cache (~/.cache/dermis): ctest gives each test file a fresh folder of its
# own ($XDG_CACHE_HOME, under DERMIS_TEST_CACHE_ROOT); pytest run by hand gets a temporary
# one, removed at exit. Tests of the cache itself choose their own.
if not os.environ.get("DERMIS_TEST_CACHE_ROOT"):
    _cache = tempfile.mkdtemp(prefix="dermis-test-cache-")
    os.environ["XDG_CACHE_HOME"] = _cache
    atexit.register(shutil.rmtree, _cache, True)


def pytest_configure(config):
    """ctest gives each test file its own --basetemp under build/test-tmp: its parent is made here."""
    if config.option.basetemp:
        os.makedirs(os.path.dirname(os.path.abspath(config.option.basetemp)), exist_ok=True)

SOURCE_DIR = os.environ.get("DERMIS_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))

# A sphere of skin-like walk material lit by a sky and a small area light: every pixel
# type (background, walk, light) in 24x18 pixels.
SPHERE_SCENE = """LookAt 0 -4 1  0 0 0  0 0 1
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 24 "integer yresolution" 18
Sampler "zsobol" "integer pixelsamples" 4
Integrator "volpath" "integer maxdepth" 64
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.6 0.7]
AttributeBegin
  AreaLightSource "diffuse" "rgb L" [8 8 8]
  Translate 2 -2 3
  Shape "sphere" "float radius" 0.5
AttributeEnd
MakeNamedMaterial "skin" "string type" "subsurface" "rgb reflectance" [0.8 0.5 0.3] "rgb mfp" [0.5 0.25 0.1]
  "float eta" 1.33 "string method" "randomwalk"
AttributeBegin
  NamedMaterial "skin"
  Shape "sphere" "float radius" 1
AttributeEnd
"""


@pytest.fixture(scope="session")
def dermis_module():
    import dermis
    return dermis


@pytest.fixture
def sphere_scene(dermis_module):
    return dermis_module.load_scene(SPHERE_SCENE)


@pytest.fixture(scope="session")
def dermis_binary():
    path = os.environ.get("DERMIS_BINARY")
    if not path or not os.path.exists(path):
        pytest.skip("DERMIS_BINARY (the dermis executable) is not set; ctest sets it")
    return path


class GilProbe:
    """Shows that a call releases the GIL while it works, whatever the machine's speed.

    Inside `with GilProbe() as probe:` the interpreter's forced switches are off
    (sys.setswitchinterval), so a thread waiting for the GIL gets it only when the holder
    lets it go. Once the call's first progress callback sets probe.started, the probe's
    thread runs 20 steps, each taking the GIL back after a sleep; probe.finished is set
    after them. A call that kept the GIL would let it run none of them until it returned."""

    def __init__(self):
        self.started, self.finished = threading.Event(), threading.Event()
        self._thread = threading.Thread(target=self._run)

    def _run(self):
        self.started.wait()
        for _ in range(20):
            time.sleep(0.001)
        self.finished.set()

    def __enter__(self):
        self._interval = sys.getswitchinterval()
        sys.setswitchinterval(1000.0)
        self._thread.start()
        return self

    def __exit__(self, *exc):
        sys.setswitchinterval(self._interval)
        self.started.set()
        self._thread.join()
        return False
