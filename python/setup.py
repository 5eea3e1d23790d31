"""Builds softrast._softrast from the C sources of this checkout.

pip install ./python                        # with a package index
pip install --no-build-isolation ./python   # without one (Debian: python3-setuptools,
                                            # python3-numpy, python3-dev installed)

The extension compiles the library's own sources (../src) into itself, with
the optional parts whose libraries it finds, as the CMake build does: jansson
(glTF), libjpeg (JPEG), libwebp (WebP), meshoptimizer and libdraco (glTF's
compressed meshes), expat (SVG), fontconfig + HarfBuzz + FreeType (SVG text)
and FriBidi (bidirectional text), Assimp (other model formats).  libpng and
zlib are required.  softrast.features names what a build has.
"""

import glob
import os
import shutil
import subprocess
import sys
import sysconfig
import tempfile

import numpy
from setuptools import Extension, setup

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def rel(path):
    return os.path.relpath(path, HERE)


def pkg_config(*args):
    if not shutil.which("pkg-config"):
        return None
    r = subprocess.run(["pkg-config", *args], capture_output=True, text=True)
    return r.stdout.split() if r.returncode == 0 else None


def version():
    with open(os.path.join(ROOT, "include", "softrast.h")) as f:
        for line in f:
            if line.startswith("#define SR_VERSION_STRING"):
                return line.split('"')[1]
    raise RuntimeError("SR_VERSION_STRING not found in include/softrast.h")


if not os.path.exists(os.path.join(ROOT, "src", "draw.c")):
    sys.exit("setup.py: build from a softrast checkout (python/ inside it): ../src is missing")

core = [d for d in ("", "math", "geometry", "raster", "fragment", "target", "parallel", "draw2d")]
sources = sorted(glob.glob(os.path.join(HERE, "src", "*.c")))
for d in core:
    sources += sorted(glob.glob(os.path.join(ROOT, "src", d, "*.c")))
io_sources = sorted(glob.glob(os.path.join(ROOT, "src", "io", "*.c")))
# The stand-ins of CMake's builds without threads or libpng (SR_EMBEDDED):
# this build has both.
sources = [s for s in sources if os.path.basename(s) != "pool_inline.c"]
io_sources = [s for s in io_sources if os.path.basename(s) != "png_none.c"]



def ibl_tables():
    """The image-based light's tables (the BRDF table, the sheen's albedo,
    the built-in studio prefiltered) as C, computed by tools/ibl_tables.c from the library's own
    functions, as the CMake build computes them; their path."""
    out_dir = os.path.join(HERE, "build", "generated")
    os.makedirs(out_dir, exist_ok=True)
    tool, out = os.path.join(out_dir, "sr_ibl_tables"), os.path.join(out_dir, "ibl_tables.c")
    cc = (sysconfig.get_config_var("CC") or "cc").split()
    tool_sources = [os.path.join(ROOT, *p.split("/")) for p in (
        "tools/ibl_tables.c", "src/fragment/brdf_integrate.c", "src/fragment/sheen_integrate.c",
        "src/fragment/environment_studio.c", "src/fragment/environment_prefilter.c")]
    subprocess.run(cc + ["-std=c11", "-O2", "-ffp-contract=off", "-D_POSIX_C_SOURCE=200809L",
                         "-I", os.path.join(ROOT, "include"), "-I", os.path.join(ROOT, "src"),
                         *tool_sources, "-o", tool, "-lm"], check=True)
    subprocess.run([tool, out], check=True)
    return out


sources.append(ibl_tables())
# zlib is required (libpng's), so gzip-compressed SVG always reads.
macros = [("_POSIX_C_SOURCE", "200809L"), ("SR_HAVE_ZLIB", "1"), ("SR_HAVE_PNG", "1")]
include_dirs = [os.path.join(ROOT, "include"), os.path.join(ROOT, "src"), numpy.get_include()]
libraries = ["png", "z", "m", "pthread"]
compile_args = ["-std=c11", "-ffp-contract=off", "-fvisibility=hidden", "-Wno-psabi"]
link_args = []

extra_objects = []


def use(modules, macro):
    """Builds with the pkg-config modules when all are found; whether."""
    libs = pkg_config("--libs", *modules)
    if libs is None:
        return False
    macros.append((macro, "1"))
    compile_args.extend(pkg_config("--cflags", *modules) or [])
    link_args.extend(libs)
    return True


def links(code, flags):
    """Whether the C compiler builds and links code with flags."""
    cc = (sysconfig.get_config_var("CC") or "cc").split()
    with tempfile.TemporaryDirectory() as tmp:
        src = os.path.join(tmp, "probe.c")
        with open(src, "w") as f:
            f.write(code)
        r = subprocess.run(cc + [src, "-o", os.path.join(tmp, "probe"), *flags],
                           capture_output=True)
        return r.returncode == 0


def draco_object():
    """src/io/draco_decode.cc, libdraco's C++ API behind a C header, compiled
    as C++17 (setuptools compiles one language per extension); its path."""
    out_dir = os.path.join(HERE, "build", "generated")
    os.makedirs(out_dir, exist_ok=True)
    out = os.path.join(out_dir, "draco_decode.o")
    cxx = (sysconfig.get_config_var("CXX") or "c++").split()
    subprocess.run(cxx + ["-std=c++17", "-O2", "-fPIC", "-fvisibility=hidden",
                          "-DSR_HAVE_DRACO=1", "-I", os.path.join(ROOT, "include"),
                          "-I", os.path.join(ROOT, "src"), *(pkg_config("--cflags", "draco") or []),
                          "-c", os.path.join(ROOT, "src", "io", "draco_decode.cc"), "-o", out],
                   check=True)
    return out


if use(["jansson"], "SR_HAVE_JANSSON"):
    # Debian ships meshoptimizer without a .pc file: its header and library.
    if links("#include <meshoptimizer.h>\n"
             "int main(void) { meshopt_decodeFilterOct(0, 0, 4); return 0; }\n",
             ["-lmeshoptimizer"]):
        macros.append(("SR_HAVE_MESHOPT", "1"))
        link_args.append("-lmeshoptimizer")
    if pkg_config("--exists", "draco") is not None:
        macros.append(("SR_HAVE_DRACO", "1"))
        extra_objects.append(draco_object())
        link_args.extend((pkg_config("--libs", "draco") or []) + ["-lstdc++"])
else:
    io_sources = [s for s in io_sources if not os.path.basename(s).startswith("gltf")]
use(["libjpeg"], "SR_HAVE_JPEG")
use(["libwebp"], "SR_HAVE_WEBP_DECODE")
if use(["expat"], "SR_HAVE_EXPAT") and use(["fontconfig", "harfbuzz", "freetype2"],
                                           "SR_HAVE_SVG_TEXT"):
    use(["fribidi"], "SR_HAVE_FRIBIDI")
assimp = pkg_config("--cflags", "assimp")
if assimp is not None:
    # Headers only: the library is opened with dlopen when a file needs it.
    macros.append(("SR_HAVE_ASSIMP", "1"))
    compile_args += assimp
    libraries.append("dl")

setup(
    name="softrast",
    version=version(),
    description="Exact, deterministic CPU rendering of triangle meshes to numpy arrays",
    packages=["softrast"],
    # PEP 561: the extension's stub and the marker that the package is typed.
    package_data={"softrast": ["py.typed", "*.pyi"]},
    python_requires=">=3.8",
    install_requires=["numpy"],
    ext_modules=[Extension(
        "softrast._softrast", [rel(s) for s in sources + io_sources], define_macros=macros,
        include_dirs=include_dirs, libraries=libraries, extra_compile_args=compile_args,
        extra_link_args=link_args, extra_objects=extra_objects)],
)
