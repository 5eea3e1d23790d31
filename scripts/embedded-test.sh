#!/bin/sh
# scripts/embedded-test.sh [native|armhf]... 
#
# Builds the embedded profile (SR_EMBEDDED=ON, docs/portability.md) in
# build-embedded/ (native) and build-embedded-armhf/ (32-bit ARM, cross-
# built with Debian's gcc-arm-linux-gnueabihf and run under qemu-arm),
# runs its tests, and prints the static library's `size -t` totals.  With
# no argument, both.  Needs, on Debian 12, for armhf:
#
#   apt-get install gcc-arm-linux-gnueabihf libc6-dev-armhf-cross qemu-user
#
# Both builds treat warnings as errors (SR_WERROR=ON), the armhf one too:
# a cross compiler's warning is fixed in the code (as scripts/cross-test.sh).
#
# The profile has no threads, so the cross package's loader and libc
# (qemu-arm -L /usr/arm-linux-gnueabihf) serve its tests.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
[ $# -gt 0 ] || set -- native armhf
for target in "$@"; do
    case $target in
    native)
        build=$root/build-embedded
        cmake -S "$root" -B "$build" -DSR_EMBEDDED=ON -DCMAKE_BUILD_TYPE=Release -DSR_WERROR="${SR_WERROR:-ON}" >/dev/null
        size_tool=size
        ;;
    armhf)
        triplet=arm-linux-gnueabihf
        for tool in "$triplet-gcc" qemu-arm; do
            if ! command -v "$tool" >/dev/null; then
                echo "embedded-test.sh: $tool not found (see the packages at the top of $0)" >&2
                exit 2
            fi
        done
        build=$root/build-embedded-armhf
        mkdir -p "$build"
        cat >"$build/toolchain.cmake" <<EOT
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER $triplet-gcc)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-arm -L /usr/$triplet)
EOT
        cmake -S "$root" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$build/toolchain.cmake" \
            -DSR_EMBEDDED=ON -DCMAKE_BUILD_TYPE=Release -DSR_WERROR="${SR_WERROR:-ON}" >/dev/null
        size_tool=$triplet-size
        ;;
    *)
        echo "usage: scripts/embedded-test.sh [native|armhf]..." >&2
        exit 2
        ;;
    esac
    cmake --build "$build" -j2 >/dev/null
    echo "== embedded profile, $target: libsoftrast.a =="
    "$size_tool" -t "$build/libsoftrast.a" | tail -n 1
    ctest --test-dir "$build" --output-on-failure -j2
done
