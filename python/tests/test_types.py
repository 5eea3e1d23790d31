"""The package's type information (PEP 561) against mypy: py.typed makes
mypy read the installed package, the extension's stub agrees with the
built module (mypy's stubtest, and the checks it cannot make), the package
passes `mypy --strict`, typed_example.py (the documented API, annotated)
passes it and runs, and wrong calls are rejected.  The marker, stubtest and
--strict checks are also shown to fail on a copy of the package made wrong.

Run by CTest as python_types (skipped there without mypy); here skipped
when mypy cannot be imported.
"""

import ast
import inspect
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest
import softrast

pytest.importorskip("mypy.stubtest", reason="the type checks need mypy (Debian: mypy, "
                    "scripts/install-deps.sh)")
from conftest import MODELS  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
# The directory softrast is imported from (the build tree's python/, or
# an installed site): mypy reads the package's annotations and stubs there.
PACKAGE_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(softrast.__file__)))


@pytest.fixture(scope="module")
def mypy_config(tmp_path_factory):
    """A config file whose cache is shared by the module's runs (numpy's
    stubs are read once)."""
    d = tmp_path_factory.mktemp("mypy")
    path = d / "mypy.ini"
    path.write_text(f"[mypy]\ncache_dir = {d / 'cache'}\n")
    return str(path)


def run(args, config, root=PACKAGE_ROOT, source=True, cwd=None):
    """python3 -m <args> with softrast in root; (exit code, output).  mypy
    finds it on sys.path as an installed package, which it reads only with
    a py.typed marker and whose own errors it does not report, or, with
    `source`, in MYPYPATH as code of the program's, checked too."""
    env = dict(os.environ, PYTHONPATH=root)
    env.pop("MYPYPATH", None)
    if source:
        env["MYPYPATH"] = root
    r = subprocess.run([sys.executable, "-m", *args, "--config-file" if args[0] == "mypy"
                        else "--mypy-config-file", config], env=env, cwd=cwd or root,
                       capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def package_copy(tmp_path):
    """A copy of the imported package in tmp_path/softrast."""
    copy = tmp_path / "softrast"
    shutil.copytree(os.path.dirname(softrast.__file__), copy,
                    ignore=shutil.ignore_patterns("__pycache__"))
    return copy


USES = "import softrast\nsoftrast.render(softrast.load('m.obj'), width=8, height=8)\n"


def test_installed_package_is_typed_by_its_marker(tmp_path, mypy_config):
    # As an installed package (found on sys.path, not MYPYPATH) softrast
    # is read for its types because of py.typed; a copy without it is not.
    prog = tmp_path / "prog"
    prog.mkdir()
    (prog / "uses.py").write_text(USES.replace("8,", "'8',"))
    code, out = run(["mypy", "--strict", "uses.py"], mypy_config, source=False, cwd=prog)
    assert code == 1 and 'Argument "width" to "render" has incompatible type "str"' in out, out
    (package_copy(tmp_path / "site") / "py.typed").unlink()
    (prog / "uses.py").write_text(USES)
    code, out = run(["mypy", "--strict", "uses.py"], mypy_config, root=str(tmp_path / "site"),
                    source=False, cwd=prog)
    assert code == 1 and "missing library stubs or py.typed marker" in out, out


def test_stub_matches_the_built_extension(mypy_config):
    # Names, positional/keyword kinds and defaults of _softrast.pyi against
    # the module's signatures (its docstrings' text signatures, which
    # PyArg_ParseTupleAndKeywords' keyword lists must match).
    code, out = run(["mypy.stubtest", "softrast._softrast"], mypy_config)
    assert code == 0, out


def test_stubtest_catches_a_stub_that_drifted(tmp_path, mypy_config):
    # The check above can fail: a copy of the package whose stub names
    # write_png's image argument and Mesh's colors differently.
    stub = package_copy(tmp_path) / "_softrast.pyi"
    text = stub.read_text()
    drifted = text.replace("def write_png(path: PathLike, image:", "def write_png(path: PathLike, "
                           "picture:").replace("colors: Optional", "colours: Optional")
    assert drifted.count("picture") == 1 and drifted.count("colours") == 1
    stub.write_text(drifted)
    code, out = run(["mypy.stubtest", "softrast._softrast"], mypy_config, root=str(tmp_path))
    assert code == 1, out
    assert "softrast._softrast.write_png" in out, out


def stub_parameters(cls, method):
    """(name, has a default) of a method of a class in _softrast.pyi, self left out."""
    with open(os.path.join(os.path.dirname(softrast.__file__), "_softrast.pyi")) as f:
        tree = ast.parse(f.read())
    node = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == cls)
    fn = next(n for n in node.body if isinstance(n, ast.FunctionDef) and n.name == method)
    args = fn.args.args[1:]
    defaults = [False] * (len(args) - len(fn.args.defaults)) + [True] * len(fn.args.defaults)
    return [(a.arg, d) for a, d in zip(args, defaults)]


def test_mesh_stub_matches_its_text_signature():
    # stubtest cannot see through the type's __init__ (a slot wrapper taking
    # *args, **kwargs): the stub's __init__ against Mesh's signature.
    sig = inspect.signature(softrast.Mesh)
    runtime = [(p.name, p.default is not p.empty) for p in sig.parameters.values()]
    assert all(p.kind is p.POSITIONAL_OR_KEYWORD for p in sig.parameters.values())
    assert stub_parameters("Mesh", "__init__") == runtime


def test_text_signatures_name_the_c_keywords():
    # The signatures stubtest reads are the docstrings' first lines: every
    # name there is a keyword the C argument parser takes (a wrong one
    # raises TypeError), and passing the defaults draws what leaving them
    # out does.
    from softrast import _softrast
    v = np.array([[0, 0, 1], [1, 0, 1], [0, 1, 1]], np.float32)
    mesh = _softrast.Mesh(**{name: v if name == "vertices" else np.array([[0, 1, 2]], np.int32)
                             if name == "faces" else None
                             for name in inspect.signature(_softrast.Mesh).parameters})
    required = dict(instances=[(mesh, np.hstack([np.eye(3), np.zeros((3, 1))]), np.eye(3), 0)],
                    K=np.array([[4.0, 0, 1.5], [0, 4, 1.5], [0, 0, 1]]), width=4, height=4,
                    near=1e-3, threads=1, depth=np.empty((4, 4), np.float32),
                    background=(0.0, 0.0, 0.0), lit=True)
    kwargs = {p.name: required.get(p.name) if p.default is p.empty else p.default
              for p in inspect.signature(_softrast.render).parameters.values()}
    _softrast.render(**kwargs)
    explicit = dict(kwargs, depth=np.empty((4, 4), np.float32))
    for name in ("rgba", "pbr", "view", "environment", "shadows", "general", "ortho", "far",
                 "msaa", "ssaa", "ground", "cull"):
        del explicit[name]
    _softrast.render(**explicit)
    assert np.array_equal(kwargs["depth"], explicit["depth"], equal_nan=True)


def test_package_passes_mypy_strict(mypy_config):
    code, out = run(["mypy", "--strict", "-p", "softrast"], mypy_config)
    assert code == 0, out


def test_package_check_sees_the_package_errors(tmp_path, mypy_config):
    # The check above can fail: a copy whose look_at returns the wrong type.
    module = package_copy(tmp_path) / "_camera.py"
    text = module.read_text()
    wrong = text.replace("return _intrinsics(f, width, height), R, t", "return R, t")
    assert wrong != text
    module.write_text(wrong)
    code, out = run(["mypy", "--strict", "-p", "softrast"], mypy_config, root=str(tmp_path))
    assert code == 1 and "_camera.py" in out and "Incompatible return value" in out, out


def test_typed_example_passes_mypy_strict(mypy_config):
    code, out = run(["mypy", "--strict", os.path.join(HERE, "typed_example.py")], mypy_config,
                    source=False)
    assert code == 0, out


def test_typed_example_runs(tmp_path):
    pytest.importorskip("dask", reason="the example's Dask recipe needs python3-dask")
    cow = os.path.join(MODELS, "cow.obj")
    if not os.path.exists(cow):
        pytest.skip(f"{cow} is missing")
    r = subprocess.run([sys.executable, os.path.join(HERE, "typed_example.py"), cow, str(tmp_path)],
                       env=dict(os.environ, PYTHONPATH=PACKAGE_ROOT), capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr
    assert "'files': ['shard-000000.npz', 'shard-000001.npz']" in r.stdout, r.stdout
    assert sorted(os.listdir(tmp_path)) == ["shard-000000.npz", "shard-000001.npz"]


# Each line marked "# wrong" must draw a mypy error, and no other line.
WRONG_CALLS = '''
import pathlib

import numpy as np
import softrast

v = np.zeros((3, 3), np.float32)
f = np.array([[0, 1, 2]], np.int32)
mesh = softrast.Mesh(v, f)
K, R, t = softrast.look_at((0, 0, -2), (0, 0, 0), width=8, height=8)
out = softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, outputs=("depth",))
depth: "np.ndarray[object, np.dtype[np.float32]]" = out["depth"]
softrast.Mesh("vertices", f)  # wrong: a str where an array goes
softrast.Mesh(v, f.astype(np.uint8))  # wrong: faces are int32 or int64
softrast.render(mesh, K="K", R=R, t=t, width=8, height=8)  # wrong: K a str
softrast.render(mesh, K, R, t, width=8, height=8)  # wrong: the camera is keyword-only
softrast.render(mesh, K=K, R=R, t=t, width=8.0, height=8)  # wrong: width an int
softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, outputs="depth")  # wrong: not a tuple
softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, outputs=("dpeth",))  # wrong: a name
softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, shading="phong")  # wrong: a shading
softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, cull="front")  # wrong: a cull mode
sun = softrast.Light.directional((0.0, -1.0, 0.0), color=(1.0, 0.9, 0.8), intensity=3.0)
lamp = softrast.Light.spot((0, 2, 0), (0, -1, 0), intensity=5.0, range=4.0, outer_cone=0.5)
softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, shading="pbr", lights=[sun, lamp])
softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, shading="pbr", lights="both")
softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, lights="sun")  # wrong: a lights mode
softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, lights=[(0, -1, 0)])  # wrong: Lights
softrast.Light.point((0, 1, 0), 5.0)  # wrong: intensity is keyword-only
softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, shading="pbr", exposure=-1.0, tonemap="aces")
softrast.render(mesh, K=K, R=R, t=t, width=8, height=8, tonemap="filmic")  # wrong: a tone curve
dark: bool = sun.dark
ids: "np.ndarray[object, np.dtype[np.float32]]" = out["triangle_id"]  # wrong: int32
out["dpeth"]  # wrong: no such output
softrast.look_at((0, 0, -2), (0, 0, 0), fov_y=1.0, ymag=2.0, width=8, height=8)  # wrong: both
softrast.orbit(mesh, 4, 64, 48)  # wrong: width, height keyword-only
softrast.fit_camera(mesh, width=8, height=8, projection="ortho")  # wrong: a projection
softrast.load(3)  # wrong: a path
softrast.Material(alpha_mode="translucent")  # wrong: an alpha mode
softrast.write_png("out.png", v)  # wrong: a uint8 image
icon: "np.ndarray[object, np.dtype[np.uint8]]" = softrast.render_svg(b"<svg/>", scale=2)
softrast.render_svg("icon.svg", width="8", height=8)  # wrong: width an int
softrast.render_svg(3)  # wrong: a path or the document
softrast.render_svg("icon.svg", 8, 8)  # wrong: the size is keyword-only
softrast.render_svg(b"<svg/>", background="navy", resources_dir=".")
softrast.render_svg(b"<svg/>", background=(0.0, 0.0, 0.5, 0.5), resources_dir=pathlib.Path("."))
softrast.render_svg(b"<svg/>", background=0.5)  # wrong: a color or 3 or 4 numbers
softrast.render_svg(b"<svg/>", resources_dir=3)  # wrong: a directory
canvas = softrast.Canvas(8, 8, background="white")
canvas.fill(softrast.Path().move_to(0, 0).line_to(8, 0).line_to(0, 8).close(), (1.0, 0.0, 0.0))
canvas.fill([[0, 0], [8, 0], [0, 8]], "red", rule="nonzero", antialias=False, opacity=0.5)
canvas.fill([[0, 0], [8, 0], [0, 8]], "red", rule="winding")  # wrong: a fill rule
canvas.stroke(softrast.Path(), "red", width=2, join="round", cap="square")
canvas.stroke(softrast.Path(), "red", join="rounded")  # wrong: a join
canvas.stroke(softrast.Path(), "red", 2.0)  # wrong: width is keyword-only
canvas.fill(softrast.Path(), 3)  # wrong: a paint
softrast.Path().arc_to(1, 1, 0, True, False, 2, 2).cubic_to(0, 0, 1, 1, 2, "2")  # wrong: a str
softrast.LinearGradient((0, 0), (1, 0), [(0.0, "red")], spread="mirror")  # wrong: a spread
softrast.Pattern(np.zeros((2, 2, 4), np.uint8), wrap="clamp")
softrast.Canvas.from_array(v)  # wrong: a uint8 image
'''


def test_mypy_rejects_wrong_calls(tmp_path, mypy_config):
    src = tmp_path / "wrong_calls.py"
    src.write_text(WRONG_CALLS)
    code, out = run(["mypy", "--strict", str(src)], mypy_config, source=False)
    assert code == 1, out
    flagged = {int(m) for m in re.findall(r"wrong_calls\.py:(\d+): error:", out)}
    wrong = {i + 1 for i, line in enumerate(WRONG_CALLS.splitlines()) if "# wrong" in line}
    assert flagged == wrong, f"lines flagged {sorted(flagged)}, marked {sorted(wrong)}:\n{out}"
