"""`pip install ./python` from a copy of this checkout, then the installed
package against the one the CMake build made: the same optional features
(softrast.features), the same bytes for a render, and its type information
(py.typed, the extension's stub) installed with it.

Run by CTest as python_pip_install (not collected by pytest: it builds the
whole library once more, about half a minute of CPU).  Exit 77 (skipped)
where pip or setuptools is missing.  The checkout is copied first because
setup.py writes its build files beside itself.
"""

import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

PROBE = r"""
import hashlib, sys
import numpy as np
import softrast
v = np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 4], [1, 1, 5]], np.float32)
f = np.array([[0, 1, 2], [1, 3, 2]], np.int32)
K = np.array([[40, 0, 32], [0, 40, 24], [0, 0, 1]], np.float64)
out = softrast.render(softrast.Mesh(v, f), K=K, R=np.eye(3), t=np.zeros(3), width=64,
                      height=48, outputs=("color", "depth", "triangle_id", "normal"))
h = hashlib.sha256()
for name in sorted(out):
    h.update(name.encode()); h.update(np.ascontiguousarray(out[name]).tobytes())
print(softrast.__file__)
print(" ".join(softrast.features))
print(softrast.__version__, h.hexdigest())
"""


def probe(pythonpath, cwd):
    # -c puts the working directory first on sys.path: run where no
    # softrast package lies.
    env = dict(os.environ, PYTHONPATH=pythonpath, PYTHONDONTWRITEBYTECODE="1")
    r = subprocess.run([sys.executable, "-c", PROBE], env=env, cwd=cwd, capture_output=True,
                       text=True)
    if r.returncode != 0:
        sys.exit(f"pip_install_check: the render failed under PYTHONPATH={pythonpath}:\n{r.stderr}")
    where, features, digest = r.stdout.splitlines()[-3:]
    return where, features, digest


def main():
    for module in ("pip", "setuptools", "numpy"):
        if subprocess.run([sys.executable, "-c", f"import {module}"],
                          capture_output=True).returncode != 0:
            print(f"softrast: skipped: pip install needs python3-{module} (scripts/install-deps.sh)")
            return 77
    built = os.environ.get("PYTHONPATH", "")
    if not built:
        sys.exit("pip_install_check: PYTHONPATH must name the CMake build's package directory")
    with tempfile.TemporaryDirectory(prefix="softrast-pip-") as tmp:
        src = os.path.join(tmp, "src")
        skip = shutil.ignore_patterns("build", "build-*", "*.egg-info", "__pycache__", "node_modules")
        for part in ("include", "src", "tools", "python"):
            shutil.copytree(os.path.join(ROOT, part), os.path.join(src, part), ignore=skip)
        target = os.path.join(tmp, "site")
        cmd = [sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-deps",
               "--no-index", "--disable-pip-version-check", "--target", target,
               os.path.join(src, "python")]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit("pip_install_check: " + " ".join(cmd) + " failed:\n" + r.stdout[-4000:]
                     + r.stderr[-4000:])
        where, installed_features, installed = probe(target, tmp)
        if not where.startswith(target):
            sys.exit(f"pip_install_check: imported {where}, not the installed package")
        # PEP 561: the type information goes with the package.
        for name in ("py.typed", "_softrast.pyi", "typing.py"):
            if not os.path.isfile(os.path.join(target, "softrast", name)):
                sys.exit(f"pip_install_check: softrast/{name} was not installed")
        _, built_features, reference = probe(built, tmp)
    # setup.py finds the optional libraries CMake found: the installed
    # package reads what the build tree's does (Draco, WebP, text...).
    if installed_features != built_features:
        sys.exit(f"pip_install_check: the installed package has features '{installed_features}', "
                 f"the CMake build's '{built_features}'")
    if installed != reference:
        sys.exit(f"pip_install_check: the installed package renders {installed}, "
                 f"the CMake build's {reference}")
    print("pip install ./python: imports and renders the same bytes as the build tree:", installed)
    print("pip install ./python: built with", installed_features)
    return 0


if __name__ == "__main__":
    sys.exit(main())
