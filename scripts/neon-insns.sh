#!/bin/sh
# scripts/neon-insns.sh [SCENE...]
#
# Guest instructions per frame of softrast-bench's scenes cross-built for
# aarch64 and run under qemu-aarch64, with the scalar kernels (SR_SIMD=off)
# and with the NEON ones (SR_SIMD=base): what the NEON kernels save where
# no ARM core is at hand (docs/portability.md).  Emulated: it counts
# instructions, not time on a real core.
#
# qemu-user logs each translated block's instructions (-d in_asm) and each
# execution of a block (-d exec; nochain makes every execution pass through
# the logger); the sum over executions of their blocks' lengths is the
# instructions executed.  A frame's count is that of a run with two timed
# frames less that of a run with one (the bench draws three warm-up frames
# first), so loading the model and setting up cancel out; one thread, so
# the count is the same every run.
#
# Needs what scripts/cross-test.sh needs (it makes build-aarch64/'s
# toolchain file and sysroot: run `scripts/cross-test.sh aarch64 -R x`
# once); builds build-aarch64-bench/.  SR_NEON_SIZE sets the frame size
# (default 480x270).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
cross=$root/build-aarch64
build=$root/build-aarch64-bench
if [ ! -e "$cross/toolchain.cmake" ]; then
    echo "neon-insns.sh: run scripts/cross-test.sh aarch64 first (it makes $cross/toolchain.cmake)" >&2
    exit 2
fi
cmake -S "$root" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$cross/toolchain.cmake" \
    -DCMAKE_BUILD_TYPE=Release -DSR_BUILD_BENCH=ON -DSR_WITH_ASSIMP=OFF \
    -DSR_BUILD_PYTHON=OFF -DSR_BUILD_EXAMPLES=OFF -DSR_WERROR="${SR_WERROR:-ON}" >/dev/null
cmake --build "$build" -j2 --target softrast-bench >/dev/null
[ $# -gt 0 ] || set -- teapot bunny phong msaa4 lines
size=${SR_NEON_SIZE:-480x270}
libpath=/usr/aarch64-linux-gnu/lib:$cross/sysroot/lib/aarch64-linux-gnu:$cross/sysroot/usr/lib/aarch64-linux-gnu

# Instructions executed by one run of the bench: SCENE LEVEL FRAMES.
count() {
    SR_SIMD=$2 qemu-aarch64 -d in_asm,exec,nochain -D /dev/stderr -L /usr/aarch64-linux-gnu \
        -E "LD_LIBRARY_PATH=$libpath" "$build/bench/softrast-bench" "$1" --threads 1 \
        --size "$size" --frames "$3" 2>&1 >/dev/null | awk '
        /^IN:/ { inblk = 1; start = ""; next }
        inblk && /^0x[0-9a-f]+:/ {
            a = substr($1, 3, length($1) - 3)
            if (start == "") start = a
            n[start]++
            next
        }
        inblk && /^$/ { inblk = 0; next }
        /^Trace / { split($0, f, "/"); p = f[2]; sub(/^0+/, "", p); total += n[p] }
        END { printf "%d\n", total }'
}

echo "scene size scalar_insns_per_frame neon_insns_per_frame ratio"
for scene in "$@"; do
    off=$(($(count "$scene" off 2) - $(count "$scene" off 1)))
    neon=$(($(count "$scene" base 2) - $(count "$scene" base 1)))
    echo "$scene $size $off $neon $(awk -v a="$off" -v b="$neon" 'BEGIN { printf "%.2f", a / b }')"
done
