"""The `dermis` Python module (docs/python.md), for the scripts built on `dermis study`."""
import importlib
import importlib.util
import os
import sys

from bench.harness.paths import ROOT

BUILD_PACKAGE = os.path.join(ROOT, "build", "python", "dermis")  # where `make` builds it


def load(submodule=None):
    """The module `dermis` (or its `submodule`, e.g. "study"): the one Python finds
    (PYTHONPATH), else the build tree's, imported from its folder without changing sys.path."""
    package = _package()
    return importlib.import_module(f"dermis.{submodule}") if submodule else package


def _package():
    try:
        return importlib.import_module("dermis")
    except ModuleNotFoundError as e:
        if e.name != "dermis":
            raise
    init = os.path.join(BUILD_PACKAGE, "__init__.py")
    if not os.path.exists(init):
        raise ModuleNotFoundError(f"the module dermis is not built (no {init}): make build", name="dermis")
    spec = importlib.util.spec_from_file_location("dermis", init, submodule_search_locations=[BUILD_PACKAGE])
    module = importlib.util.module_from_spec(spec)
    sys.modules["dermis"] = module  # before it runs: its own `from dermis import ...` find it
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules["dermis"]
        raise
    return module
