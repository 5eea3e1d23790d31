#!/bin/sh
# scripts/fuzz.sh TARGET SECONDS [libFuzzer options...]
#
# Builds one fuzz target of tests/fuzz (fuzz_obj, fuzz_ply, fuzz_stl, fuzz_jpeg, fuzz_hdr,
# fuzz_fill2d, fuzz_draw, fuzz_svg, fuzz_gltf) with clang, libFuzzer, ASan and UBSan in build-fuzz/ (or
# $SR_FUZZ_BUILD), and runs it for SECONDS on its seed corpus
# tests/fuzz/corpus/TARGET/.  New inputs go to build-fuzz/corpus/TARGET/,
# crashes to build-fuzz/artifacts/.  Exits non-zero on any crash, leak,
# sanitizer report, invariant failure or input slower than 10 s
# (docs/robustness.md).
set -eu
if [ $# -lt 2 ]; then
    echo "usage: scripts/fuzz.sh TARGET SECONDS [libFuzzer options...]" >&2
    exit 2
fi
target=$1
seconds=$2
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
build=${SR_FUZZ_BUILD:-$root/build-fuzz}
seeds=$root/tests/fuzz/corpus/$target
if [ ! -d "$seeds" ]; then
    echo "fuzz.sh: no seed corpus $seeds" >&2
    exit 2
fi
cmake -S "$root" -B "$build" -DCMAKE_C_COMPILER="${CC:-clang}" -DCMAKE_BUILD_TYPE=Fuzz \
    -DCMAKE_C_FLAGS_FUZZ="-O2 -g" \
    -DSR_FUZZ=ON -DSR_BUILD_TESTS=OFF -DSR_BUILD_BENCH=OFF -DSR_WITH_ASSIMP=OFF >/dev/null
cmake --build "$build" --target "$target" -j2 >/dev/null
mkdir -p "$build/corpus/$target" "$build/artifacts"
# A dictionary of the format's keywords, when the target has one.
dict=$root/tests/fuzz/$target.dict
if [ -f "$dict" ]; then
    set -- -dict="$dict" "$@"
fi
echo "== fuzz $target for ${seconds}s =="
# tests/lsan.supp: fontconfig's own leak while it reads its configuration.
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} \
LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/tests/lsan.supp:print_suppressions=0} \
UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
"$build/tests/fuzz/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$build/artifacts/$target-" \
    "$@" "$build/corpus/$target" "$seeds"
