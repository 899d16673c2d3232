"""The type stubs (dermis/_dermis.pyi, with dermis/py.typed: PEP 561) against the module
as built: every public name of dermis._dermis has a stub and every stub a name; functions
and methods have the same parameters (names, order, kinds, defaults); properties are
properties, with a setter exactly where the module has one. A binding added or changed
without its stub fails here."""
import ast
import inspect
import os
import re

import pytest

import dermis
from dermis import _dermis

PACKAGE = os.path.dirname(_dermis.__file__)
STUB = os.path.join(PACKAGE, "_dermis.pyi")


@pytest.fixture(scope="module")
def stub():
    with open(STUB) as f:
        return ast.parse(f.read())


def public(names):
    return sorted(n for n in names if not n.startswith("_") or n in ("__version__", "__init__"))


def _default(node):
    return ast.literal_eval(node)


def stub_params(fn):
    """(name, kind, default) of a stub function; default is inspect.Parameter.empty if none."""
    a, empty = fn.args, inspect.Parameter.empty
    out = []
    positional = a.posonlyargs + a.args
    defaults = [empty] * (len(positional) - len(a.defaults)) + [_default(d) for d in a.defaults]
    for p, d in zip(positional, defaults):
        out.append((p.arg, "positional", d))
    if a.vararg:
        out.append((a.vararg.arg, "*args", empty))
    for p, d in zip(a.kwonlyargs, a.kw_defaults):
        out.append((p.arg, "keyword-only", empty if d is None else _default(d)))
    if a.kwarg:
        out.append((a.kwarg.arg, "**kwargs", empty))
    return out


def runtime_params(name, obj):
    """The signatures of a pybind11 function or method, from the lines pybind11 writes at
    the top of its docstring ("name(a: int, *, b: float = 1.0) -> T"; one per overload)."""
    doc = inspect.getdoc(obj) or ""
    lines = [re.sub(r"^\d+\. ", "", line) for line in doc.splitlines()]
    sigs = [line for line in lines if line.startswith(name + "(")]
    assert sigs, f"{name}: no signature in its docstring: {doc[:200]!r}"
    out = []
    for line in sigs:
        tree = ast.parse("def " + line.split(" -> ")[0] + ": pass")
        out.append(stub_params(tree.body[0]))
    return out


def stub_members(body):
    """name -> list of nodes (a function with overloads or a property with a setter gives several)."""
    out = {}
    for node in body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            out.setdefault(node.name, []).append(node)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            out.setdefault(node.target.id, []).append(node)
    return out


def decorators(fn):
    return {ast.unparse(d) for d in fn.decorator_list}


def check_function(where, name, obj, stubs):
    functions = [s for s in stubs if isinstance(s, ast.FunctionDef)]
    assert functions, f"{where}{name}: the stub is not a function"
    actual = runtime_params(name, obj)
    written = [stub_params(f) for f in functions]
    for w in written:  # every overload of the stub: the same parameters and kinds
        assert [(n, k) for n, k, _ in w] in [[(n, k) for n, k, _ in a] for a in actual], \
            f"{where}{name}: stub parameters {w} differ from the module's {actual}"
    # ...and one of them with the module's defaults exactly (overloads may narrow a default).
    assert any(w in actual for w in written), f"{where}{name}: stub defaults {written} differ from {actual}"


def test_the_stubs_and_the_marker_are_installed_beside_the_module():
    assert os.path.isfile(STUB)
    assert os.path.isfile(os.path.join(PACKAGE, "py.typed"))  # PEP 561: the package ships its types


def test_every_public_name_has_a_stub_and_every_stub_a_name(stub):
    members = stub_members(stub.body)
    module_names = public(dir(_dermis))
    stubbed = public(n for n in members if n not in ("FloatImage", "Number"))  # the stub's own type aliases
    assert module_names == stubbed
    assert set(dermis.__all__) <= set(members)  # the package re-exports the module


def test_functions_have_the_modules_parameters(stub):
    members = stub_members(stub.body)
    functions = [n for n in public(dir(_dermis)) if inspect.isroutine(getattr(_dermis, n))]
    assert "render" in functions and "load_scene" in functions
    for name in functions:
        check_function("", name, getattr(_dermis, name), members[name])


@pytest.mark.parametrize("cls_name", [n for n in public(dir(_dermis)) if inspect.isclass(getattr(_dermis, n))])
def test_classes_have_the_modules_members(stub, cls_name):
    cls = getattr(_dermis, cls_name)
    node = stub_members(stub.body)[cls_name][0]
    assert isinstance(node, ast.ClassDef)
    if issubclass(cls, BaseException):  # the exceptions: the same base, nothing else to check
        assert [ast.unparse(b) for b in node.bases] == [cls.__base__.__name__]
        return
    members = stub_members(node.body)
    own = {n: v for n, v in vars(cls).items()
           if n in public([n]) and not (n == "__init__" and not (inspect.getdoc(v) or "").startswith("__init__("))}
    assert sorted(own) == sorted(n for n in members if n in public([n])), cls_name
    for name, value in own.items():
        stubs = members[name]
        if isinstance(value, property):
            getters = [s for s in stubs if "property" in decorators(s)]
            setters = [s for s in stubs if f"{name}.setter" in decorators(s)]
            assert len(getters) == 1, f"{cls_name}.{name}: a property, not so in the stub"
            assert len(setters) == (value.fset is not None), f"{cls_name}.{name}: setter in one and not the other"
            continue
        if isinstance(value, staticmethod):
            assert all("staticmethod" in decorators(s) for s in stubs), f"{cls_name}.{name}: static in the module"
            check_function(f"{cls_name}.", name, value.__func__, stubs)
            continue
        assert not any("staticmethod" in decorators(s) for s in stubs), f"{cls_name}.{name}: not static"
        check_function(f"{cls_name}.", name, value, stubs)
