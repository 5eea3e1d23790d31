#!/bin/sh
# scripts/cross-test.sh ARCH [ctest options...]
#
# Cross-builds the library, the CLI and the tests for ARCH (aarch64) with
# Debian's cross compiler in build-ARCH/ (or $SR_CROSS_BUILD) and runs the
# test suite under qemu-user.  Needs, on Debian 12:
#
#   dpkg --add-architecture arm64 && apt-get update
#   apt-get install gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user \
#       libpng-dev:arm64 zlib1g-dev:arm64
#
# The tests run as `qemu-aarch64 TEST`, without -L: the binaries' loader
# /lib/ld-linux-aarch64.so.1 is then libc6:arm64's own, the one that matches
# the libc.so.6 it loads from /lib/aarch64-linux-gnu.  With
# -L /usr/aarch64-linux-gnu the loader comes from libc6-arm64-cross, a
# different glibc build than that libc.so.6, and the two disagree on their
# private data: the first pthread_create loops forever in the thread-stack
# cache, so every test that starts a thread pool hangs.
#
# The tests that run the `softrast` tool or the examples start them as
# programs, which works under qemu-user only with qemu registered in
# binfmt_misc (qemu-user-binfmt); without that they are left out, and the
# script says which.  Emulated, the suite takes about half an hour on two
# shared cores with -j2, most of it test_properties and test_msaa (the
# emulator's one-hour test limit, tests/CMakeLists.txt, allows for that).
set -eu
if [ $# -lt 1 ]; then
    echo "usage: scripts/cross-test.sh ARCH [ctest options...]  (ARCH: aarch64)" >&2
    exit 2
fi
arch=$1
shift
case $arch in
aarch64) triplet=aarch64-linux-gnu ;;
*)
    echo "cross-test.sh: unknown ARCH '$arch' (known: aarch64)" >&2
    exit 2
    ;;
esac
for tool in "$triplet-gcc" "qemu-$arch"; do
    if ! command -v "$tool" >/dev/null; then
        echo "cross-test.sh: $tool not found (see the packages at the top of $0)" >&2
        exit 2
    fi
done
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SR_CROSS_BUILD:-$root/build-$arch}
mkdir -p "$build"
# Only the target's libraries and .pc files: the host's libexpat or SDL2
# would otherwise be found and fail to link.
cat >"$build/toolchain.cmake" <<EOF
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR $arch)
set(CMAKE_C_COMPILER $triplet-gcc)
set(CMAKE_LIBRARY_ARCHITECTURE $triplet)
set(CMAKE_IGNORE_PATH /usr/lib/x86_64-linux-gnu /lib/x86_64-linux-gnu)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-$arch)
EOF
PKG_CONFIG_LIBDIR=/usr/lib/$triplet/pkgconfig:/usr/share/pkgconfig \
cmake -S "$root" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$build/toolchain.cmake" \
    -DCMAKE_BUILD_TYPE=Release -DSR_BUILD_BENCH=OFF -DSR_WITH_ASSIMP=OFF >/dev/null
cmake --build "$build" -j2 >/dev/null
skip=
if [ ! -e "/proc/sys/fs/binfmt_misc/qemu-$arch" ]; then
    skip=$(cd "$root/tests" && grep -l -e sr_test_run_cli -e SR_CLI_PATH -e SR_EXAMPLE_ test_*.c | sed 's/\.c$//' | paste -sd'|')
    echo "cross-test.sh: qemu-$arch is not in binfmt_misc: leaving out the tests that run" \
        "the softrast tool or the examples ($skip)"
fi
echo "== $arch: ctest under qemu-$arch =="
cd "$build"
if [ -n "$skip" ]; then
    set -- -E "^($skip)\$" "$@"
fi
ctest --output-on-failure "$@"
