#!/bin/sh
# Installs what softrast needs on a fresh Debian 12 machine: the compiler and
# CMake, libpng (PNG in and out), libjpeg-turbo (JPEG textures in), Assimp
# (model formats beyond OBJ/PLY/STL), jansson (the glTF reader's JSON),
# meshoptimizer (glTF's EXT_meshopt_compression), libdraco (glTF's
# KHR_draco_mesh_compression), expat (the SVG reader),
# fontconfig, HarfBuzz, FreeType and FriBidi (the SVG reader's text) with
# IPAGothic (a Japanese font with vertical metrics and vertical alternates:
# the tests of upright glyphs in vertical text), Mesa's OSMesa
# (llvmpipe, for the benchmark's side-by-side comparison), cairo (the 2D fill
# benchmark's comparison), libwebp (WebP textures, glTF's EXT_texture_webp,
# and animated WebP turntables, 'softrast render --animate'), the Breeze icon
# theme and rsvg-convert (the benchmark's icons scene renders every 16th SVG
# of /usr/share/icons/breeze, beside rsvg-convert; without them it is
# skipped), and
# clang with its sanitizer and fuzzer runtimes, and for `softrast view` SDL2
# (the window), FreeType and DejaVu (the overlay font's outlines) with Xvfb
# and xauth (its tests run on a virtual display), and the de_DE.UTF-8 locale
# (the readers' numbers must not depend on a host program's locale; the
# test sets one whose decimal separator is a comma), and for the Python
# package (python/) Python's headers, NumPy, pytest, setuptools, pip,
# Dask's distributed (softrast.dask's tests on a local cluster) and mypy
# (the type checks of its annotations and stubs), and for the
# WebAssembly build (scripts/wasm.sh) emscripten with node-acorn (it compiles
# offline with them), chromium for the explain pages' browser test and npm
# for its one package, playwright-core (web/package.json), groff and
# mandoc (the tests format and lint the manual page that python3 writes),
# and zsh and fish (the tests run their completions, which python3 writes).
# Runs apt-get directly as root, through sudo otherwise.
set -eu
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends \
    build-essential cmake pkg-config ca-certificates \
    libpng-dev zlib1g-dev libjpeg-dev libassimp-dev libosmesa6-dev libexpat1-dev libcairo2-dev \
    libjansson-dev libwebp-dev libmeshoptimizer-dev libdraco-dev breeze-icon-theme librsvg2-bin \
    clang libclang-rt-14-dev \
    libsdl2-dev libfreetype-dev libfontconfig-dev libharfbuzz-dev libfribidi-dev fonts-dejavu-core fonts-ipafont-gothic xvfb xauth locales \
    python3-dev python3-numpy python3-pytest python3-setuptools python3-pip python3-distributed mypy \
    emscripten node-acorn chromium \
    groff-base mandoc zsh fish \
    >/dev/null
# Node.js from elsewhere (NodeSource) brings its own npm, which Debian's
# package would conflict with.
if ! command -v npm >/dev/null; then
    $SUDO apt-get install -y -qq --no-install-recommends npm >/dev/null
fi
# Generate de_DE.UTF-8 once: uncomment (or add) its line, then locale-gen.
if ! locale -a 2>/dev/null | grep -qi '^de_DE\.utf-\?8$'; then
    if grep -q '^# *de_DE.UTF-8 UTF-8' /etc/locale.gen; then
        $SUDO sed -i 's/^# *de_DE.UTF-8 UTF-8/de_DE.UTF-8 UTF-8/' /etc/locale.gen
    elif ! grep -q '^de_DE.UTF-8 UTF-8' /etc/locale.gen; then
        echo 'de_DE.UTF-8 UTF-8' | $SUDO tee -a /etc/locale.gen >/dev/null
    fi
    $SUDO locale-gen >/dev/null
fi
echo "softrast: dependencies installed"
