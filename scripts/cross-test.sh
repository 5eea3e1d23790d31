#!/bin/sh
# scripts/cross-test.sh ARCH [ctest options...]
#
# Cross-builds the library, the CLI and the tests for ARCH (aarch64: little
# endian; s390x: big endian) with Debian's cross compiler in build-ARCH/ (or
# $SR_CROSS_BUILD) and runs the test suite under qemu-user.  Needs, on
# Debian 12, what scripts/install-cross-deps.sh installs: qemu-user, the
# cross compilers, and dpkg's arm64 and s390x architectures.
#
# The target's libraries (libpng, zlib, expat, jansson) are not installed
# as multiarch packages: a multiarch library must have the same version for
# every architecture, and Debian 12's security archive no longer builds
# s390x, so libpng16-16:s390x can never match the amd64 one.  This script
# downloads them (`apt-get download`, which needs only the architecture's
# package lists) and unpacks them into a sysroot of its own, build-ARCH/sysroot.
#
# The programs then run as `qemu-ARCH -L /usr/TRIPLET`: the loader and the
# C library both come from libc6-ARCH-cross, one glibc build: the cross
# package's lib/ leads LD_LIBRARY_PATH, set for the guest only (qemu's -E),
# then the sysroot's libraries.  (Mixing the cross package's loader with a
# multiarch libc6:ARCH's libc.so.6 makes the first pthread_create loop
# forever in the thread-stack cache.)
#
# Warnings are errors here as in the native builds (SR_WERROR=ON): GCC's
# cross compilers see other vector widths and warn where the native one
# does not, and such a warning is fixed in the code, not switched off.
#
# CTest starts each test through CMAKE_CROSSCOMPILING_EMULATOR, and the
# tests that run the `softrast` tool or the examples start those through it
# too (tests/CMakeLists.txt passes it to sr_test_program_argv), so nothing
# needs qemu registered in binfmt_misc.  SR_CROSS_EXCLUDE names tests to
# leave out (.ci/run's long sweeps).
set -eu
if [ $# -lt 1 ]; then
    echo "usage: scripts/cross-test.sh ARCH [ctest options...]  (ARCH: aarch64, s390x)" >&2
    exit 2
fi
arch=$1
shift
case $arch in
aarch64) triplet=aarch64-linux-gnu debarch=arm64 ;;
s390x) triplet=s390x-linux-gnu debarch=s390x ;;
*)
    echo "cross-test.sh: unknown ARCH '$arch' (known: aarch64, s390x)" >&2
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
sysroot=$build/sysroot
mkdir -p "$build"

if [ ! -e "$sysroot/.complete" ]; then
    rm -rf "$sysroot" "$build/debs"
    mkdir -p "$sysroot" "$build/debs"
    packages="libpng-dev libpng16-16 zlib1g zlib1g-dev libexpat1 libexpat1-dev libjansson4 libjansson-dev"
    # apt-get download writes into the current directory, as _apt when it can.
    chmod 777 "$build/debs"
    (
        cd "$build/debs"
        # shellcheck disable=SC2046
        apt-get download -q $(for p in $packages; do echo "$p:$debarch"; done) >/dev/null
    ) || {
        echo "cross-test.sh: could not download the $debarch libraries" \
            "(is the architecture added? dpkg --add-architecture $debarch && apt-get update)" >&2
        exit 2
    }
    for deb in "$build"/debs/*.deb; do
        dpkg-deb -x "$deb" "$sysroot"
    done
    # Absolute links (libz.so -> /lib/TRIPLET/libz.so.1.2.13) point into
    # the host's root: aim them into the sysroot.
    find "$sysroot" -type l | while read -r link; do
        target=$(readlink "$link")
        case $target in
        /*) ln -sf "$sysroot$target" "$link" ;;
        esac
    done
    touch "$sysroot/.complete"
fi

# The cross package's C library first: where libc6:ARCH is also installed
# (multiarch), the loader would otherwise find that one in
# /lib/TRIPLET, a different glibc build than the loader.
libpath=/usr/$triplet/lib:$sysroot/lib/$triplet:$sysroot/usr/lib/$triplet
cat >"$build/toolchain.cmake" <<EOF
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR $arch)
set(CMAKE_C_COMPILER $triplet-gcc)
set(CMAKE_LIBRARY_ARCHITECTURE $triplet)
set(CMAKE_FIND_ROOT_PATH $sysroot)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,-rpath-link,$libpath")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "-Wl,-rpath-link,$libpath")
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-$arch -L /usr/$triplet -E LD_LIBRARY_PATH=$libpath)
# Here, not in cmake's environment, so that a re-run of the configure step
# (a CMakeLists.txt changed, then cmake --build) finds the target's
# packages too and never the host's.
set(ENV{PKG_CONFIG_LIBDIR} $sysroot/usr/lib/$triplet/pkgconfig:$sysroot/usr/share/pkgconfig)
set(ENV{PKG_CONFIG_SYSROOT_DIR} $sysroot)
EOF
cmake -S "$root" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$build/toolchain.cmake" \
    -DCMAKE_BUILD_TYPE=Release -DSR_BUILD_BENCH=OFF -DSR_WITH_ASSIMP=OFF \
    -DSR_BUILD_PYTHON=OFF -DSR_BUILD_EXAMPLES=OFF -DSR_WERROR="${SR_WERROR:-ON}" >/dev/null
cmake --build "$build" -j2 >/dev/null
# Tests to leave out: $SR_CROSS_EXCLUDE (names, space-separated).
skip=$(printf '%s' "${SR_CROSS_EXCLUDE:-}" | tr -s ' \n' '||')
echo "== $arch: ctest under qemu-$arch =="
cd "$build"
if [ -n "$skip" ]; then
    set -- -E "^($skip)\$" "$@"
fi
ctest --output-on-failure "$@"
