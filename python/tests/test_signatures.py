"""Every public callable has a signature inspect can read (help() shows
it), and the C extension's, which come from their docstrings' first lines
("name($self, /, ...)\\n--\\n\\n"), name the parameters its stub
_softrast.pyi names, in the same order and kinds."""

import ast
import inspect
import os
import pydoc

import pytest
import softrast
from softrast import _softrast


def public_callables():
    """(qualified name, object) of the package's functions, classes and
    their public methods, and the extension module's."""
    out = []
    for module, names in ((softrast, softrast.__all__),
                          (_softrast, [n for n in dir(_softrast) if not n.startswith("_")])):
        for name in names:
            obj = getattr(module, name)
            if not callable(obj):
                continue
            out.append((f"{module.__name__}.{name}", obj))
            if isinstance(obj, type) and not issubclass(obj, BaseException):
                for attr, value in vars(obj).items():
                    if not attr.startswith("_") and callable(getattr(obj, attr)) and \
                            not isinstance(value, property):
                        out.append((f"{module.__name__}.{name}.{attr}", getattr(obj, attr)))
    return out


CALLABLES = public_callables()


@pytest.mark.parametrize("name, obj", CALLABLES, ids=[n for n, _ in CALLABLES])
def test_every_public_callable_has_a_signature(name, obj):
    sig = inspect.signature(obj)
    kinds = [p.kind for p in sig.parameters.values() if p.name not in ("self", "cls")]
    # Not the slot wrapper's "(*args, **kwargs)": the real parameters.
    assert kinds != [inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD], name


def test_camera_shows_its_public_constructor():
    # Camera's constructor was the file reader's (a dict of fields):
    # help() now shows the one users call.
    first = pydoc.render_doc(softrast.Camera, renderer=pydoc.plaintext).splitlines()
    assert any("Camera(eye" in line for line in first[:5]), first[:5]
    params = list(inspect.signature(softrast.Camera).parameters)
    assert params == ["eye", "target", "up", "yfov", "ymag", "znear"]
    a = softrast.Camera((0, 0, 5), (0, 0, 0), ymag=2.0)
    b = softrast.Camera.orthographic((0, 0, 5), (0, 0, 0), ymag=2.0)
    assert repr(a) == repr(b) and a.type == "orthographic"
    c = softrast.Camera((0, 0, 5), (0, 0, 0))
    assert repr(c) == repr(softrast.Camera.perspective((0, 0, 5), (0, 0, 0)))
    with pytest.raises(TypeError, match="yfov, ymag: give one"):
        softrast.Camera((0, 0, 5), (0, 0, 0), yfov=1.0, ymag=1.0)


def stub_functions():
    """{qualified name in _softrast: ast arguments} of _softrast.pyi."""
    with open(os.path.join(os.path.dirname(softrast.__file__), "_softrast.pyi")) as f:
        tree = ast.parse(f.read())
    out = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out[node.name] = (node.args, False)
        elif isinstance(node, ast.ClassDef):
            for item in node.body:
                decorators = [d.id for d in getattr(item, "decorator_list", ())
                              if isinstance(d, ast.Name)]
                if isinstance(item, ast.FunctionDef) and "property" not in decorators:
                    out[f"{node.name}.{item.name}"] = (item.args, True)
    return out


def stub_parameters(args, method):
    """(name, kind, has a default) of stub arguments, self/cls left out."""
    P = inspect.Parameter
    pos = [(a, P.POSITIONAL_ONLY) for a in args.posonlyargs] + \
        [(a, P.POSITIONAL_OR_KEYWORD) for a in args.args]
    defaults = [False] * (len(pos) - len(args.defaults)) + [True] * len(args.defaults)
    out = [(a.arg, kind, d) for (a, kind), d in zip(pos, defaults)]
    if method:
        out = out[1:]
    out += [(a.arg, P.KEYWORD_ONLY, d is not None)
            for a, d in zip(args.kwonlyargs, args.kw_defaults)]
    return out


def runtime_parameters(obj):
    return [(p.name, p.kind, p.default is not p.empty)
            for p in inspect.signature(obj).parameters.values() if p.name not in ("self",)]


EXTENSION = [(n[len("softrast._softrast."):], obj) for n, obj in CALLABLES
             if n.startswith("softrast._softrast.")]


@pytest.mark.parametrize("name, obj", EXTENSION, ids=[n for n, _ in EXTENSION])
def test_extension_signatures_match_the_stub(name, obj):
    stubs = stub_functions()
    key = f"{name}.__init__" if isinstance(obj, type) else name
    assert key in stubs, f"{key} is not in _softrast.pyi"
    args, method = stubs[key]
    assert runtime_parameters(obj) == stub_parameters(args, method), name


def test_the_package_reexports_are_the_extension_callables():
    # softrast.Path, Mesh, read_image, write_png are the extension's own.
    for name in ("Path", "Mesh", "read_image", "write_png"):
        assert getattr(softrast, name) is getattr(_softrast, name)
