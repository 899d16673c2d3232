"""Shared fixtures of the module's tests: a small subsurface scene, the dermis binary."""
import os
import sys

import pytest

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
