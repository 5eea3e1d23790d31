#!/bin/sh
# scripts/wasm.sh test [ctest options...]
# scripts/wasm.sh web
#
# softrast in WebAssembly with Debian's emscripten, built in build-wasm/
# (or $SR_WASM_BUILD).  Needs, on Debian 12:
#
#   apt-get install emscripten node-acorn
#
# `test` builds the library and its tests and runs the suite under Node.js
# (docs/portability.md says which tests run there and why the rest do not).
# `web` builds the interactive pages of `softrast explain` (web/README.md)
# into BUILD/web/site; serve them with
#
#   python3 -m http.server -d build-wasm/web/site
#
# Debian's emscripten compiles offline once node-acorn is installed and
# NODE_PATH names Debian's Node modules; its output runs under Node with
# --no-experimental-fetch (Node 18 and later would otherwise try to fetch
# the .wasm file rather than read it).
set -eu
cd "$(dirname "$0")/.."
if [ $# -lt 1 ] || { [ "$1" != test ] && [ "$1" != web ]; }; then
    echo "usage: scripts/wasm.sh test [ctest options...] | scripts/wasm.sh web" >&2
    exit 2
fi
what=$1
shift
build=${SR_WASM_BUILD:-build-wasm}
export NODE_PATH=/usr/share/nodejs
node=$(command -v node)
emcmake cmake -B "$build" -Wno-dev -DCMAKE_BUILD_TYPE=Release -DSR_BUILD_BENCH=OFF \
    -DSR_BUILD_EXAMPLES=OFF -DSR_BUILD_PYTHON=OFF -DSR_WITH_ASSIMP=OFF \
    "-DCMAKE_CROSSCOMPILING_EMULATOR=$node;--no-experimental-fetch" >/dev/null
if [ "$what" = web ]; then
    cmake --build "$build" -j2 --target web_site
    echo "site: $build/web/site (python3 -m http.server -d $build/web/site)"
else
    cmake --build "$build" -j2
    ctest --test-dir "$build" --output-on-failure "$@"
fi
