#!/bin/sh
# tests/bench_options.sh TOOL...
#
# softrast-bench's options as every softrast command takes them: a value
# after '=' as well as in the next word, a flag refused with one, and a
# --size whose frames pass the memory limit (SR_MEMORY_LIMIT) refused in
# one line, exit status 2, before any scene runs; a scene whose inputs
# are not installed (the icons' theme) is skipped, not failed.
set -u
if [ $# -lt 1 ]; then
    echo "usage: tests/bench_options.sh TOOL..." >&2
    exit 2
fi
. "$(dirname "$0")/check_common.sh"

# ARGS...: run the bench, status in $status, output in $work/out, $work/err.
bench() {
    "$@" >"$work/out" 2>"$work/err"
    status=$?
}

bench "$@" fill --size=64x48 --frames=2 --threads=1
[ "$status" -eq 0 ] || fail "--size=64x48 --frames=2: exit status $status: $(cat "$work/err")"
grep -q "scene=fill renderer=softrast size=64x48 threads=1 frames=2 " "$work/out" ||
    fail "--size=64x48 --frames=2 --threads=1 not taken: $(cat "$work/out")"

bench "$@" fill --compare=yes
[ "$status" -eq 2 ] && grep -qx "softrast-bench: --compare: takes no value" "$work/err" ||
    fail "--compare=yes: exit status $status: $(cat "$work/err")"

bench "$@" fill --frames=
[ "$status" -eq 2 ] && grep -q "^softrast-bench: --frames: '' is not an integer" "$work/err" ||
    fail "--frames=: exit status $status: $(cat "$work/err")"

SR_MEMORY_LIMIT=1M bench "$@" fill msaa4 --size 1920x1080
want="softrast-bench: --size 1920x1080 with a multisampled scene needs about 79 MiB of frame memory, more than SR_MEMORY_LIMIT=1M allows: give a smaller --size"
[ "$status" -eq 2 ] || fail "beyond SR_MEMORY_LIMIT: exit status $status"
[ "$(cat "$work/err")" = "$want" ] || fail "beyond SR_MEMORY_LIMIT: '$(cat "$work/err")'"
[ ! -s "$work/out" ] || fail "beyond SR_MEMORY_LIMIT: a scene ran: $(cat "$work/out")"

# The icons scene without its icon theme is skipped, naming the package
# (as it is, naming expat, by a build without SVG).
SR_BENCH_ICONS="$work/no-theme" bench "$@" icons --frames 1
[ "$status" -eq 0 ] || fail "icons without a theme: exit status $status"
if grep -q "^softrast-bench: icons: skipped: softrast was built without expat" "$work/err"; then
    grep -qx "scene=icons skipped=no-svg" "$work/out" || fail "icons without SVG: '$(cat "$work/out")'"
else
    grep -qx "scene=icons skipped=missing-icons" "$work/out" ||
        fail "icons without a theme: '$(cat "$work/out")'"
    grep -q "^softrast-bench: icons: skipped: no icon theme at $work/no-theme (install breeze-icon-theme" \
        "$work/err" || fail "icons without a theme: '$(cat "$work/err")'"
fi

finish "bench options"
