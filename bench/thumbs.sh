#!/bin/bash
# thumbs.sh - the thumbs benchmark: 256x256 PNG thumbnails of the shared
# models and of generated STL, PLY and glTF copies of them, made three
# ways on the same files:
#   batch     one `softrast render DIR --output-dir OUT` process (2 threads)
#   process   one `softrast thumbnail -s 256 IN OUT` process per file
#   f3d       one `f3d --output OUT IN` process per file (Debian's f3d),
#             all under one xvfb-run, so the X server starts once
# It prints thumbnails per second for each (median of RUNS timed runs,
# wall clock from bash's EPOCHREALTIME) and the ratios, as a Markdown
# table.  Not a pass/fail test: the figures depend on the machine.
#
# usage: bench/thumbs.sh [BUILD_DIR [RUNS]]   (default build, 5)
set -eu
here=$(cd "$(dirname "$0")" && pwd)

now() { echo "${EPOCHREALTIME/./}"; }   # microseconds

# Internal: `thumbs.sh --f3d DIR OUT`, run under xvfb-run: microseconds
# for one f3d process per model in DIR; the count of files f3d failed on
# goes to stderr.
if [ "${1:-}" = --f3d ]; then
    failed=0
    t0=$(now)
    for f in "$2"/*.obj "$2"/*.stl "$2"/*.ply "$2"/*.gltf; do
        [ -e "$f" ] || continue
        f3d --dry-run --quiet --resolution 256,256 --output "$3/$(basename "$f").png" "$f" \
            || failed=$((failed + 1))
    done
    echo $(( $(now) - t0 ))
    [ "$failed" = 0 ] || echo "thumbs.sh: f3d failed on $failed files of $2" >&2
    exit 0
fi

build=${1:-build}
runs=${2:-5}
softrast=$(cd "$build" && pwd)/softrast
models=$here/../../shared/models
[ -x "$softrast" ] || { echo "thumbs.sh: no $softrast (build first)" >&2; exit 2; }
[ -d "$models" ] || { echo "thumbs.sh: no shared models at $models" >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/shared" "$work/generated" "$work/all"
cp "$models"/* "$work/shared/"
/usr/bin/python3 "$here/thumbs_models.py" "$work/generated" "$models"/*.obj
cp "$work/shared"/* "$work/generated"/* "$work/all/"

median() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

model_files() {   # the models of a set, one a line
    find "$work/$1" -maxdepth 1 -type f \( -name '*.obj' -o -name '*.stl' -o -name '*.ply' \
        -o -name '*.gltf' \) | sort
}

# Microseconds for one batch process over a set.
time_batch() {
    local out=$work/out-batch t0
    rm -rf "$out"
    t0=$(now)
    "$softrast" render "$work/$1" --output-dir "$out" --name "{stem}.{ext}.png" --size 256x256 \
        --threads 2
    echo $(( $(now) - t0 ))
}

# Microseconds for one thumbnail process per file.
time_process() {
    local out=$work/out-process f t0
    rm -rf "$out" && mkdir -p "$out"
    t0=$(now)
    while read -r f; do
        "$softrast" thumbnail -s 256 "$f" "$out/$(basename "$f").png"
    done < <(model_files "$1")
    echo $(( $(now) - t0 ))
}

rate() { awk -v n="$1" -v us="$2" 'BEGIN { printf "%.1f", n / (us / 1e6) }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.0f", b / a }'; }

have_f3d=0
if command -v f3d >/dev/null && command -v xvfb-run >/dev/null; then
    have_f3d=1
fi

echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) cores"
echo "softrast $("$softrast" --version | cut -d' ' -f2), $(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo '?')"
[ "$have_f3d" = 1 ] && echo "$(f3d --version 2>&1 | head -1) under xvfb-run (Mesa llvmpipe)"
echo
echo "| files | count | batch /s | process /s | f3d /s | batch / f3d | process / f3d |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
for set in shared generated all; do
    n=$(model_files "$set" | wc -l)
    b=$(for _ in $(seq "$runs"); do time_batch "$set"; done | median)
    p=$(for _ in $(seq "$(( (runs + 1) / 2 ))"); do time_process "$set"; done | median)
    if [ "$have_f3d" = 1 ]; then
        f=$(for _ in 1 2 3; do
                rm -rf "$work/out-f3d" && mkdir -p "$work/out-f3d"
                xvfb-run -a -s "-screen 0 1024x768x24" "$here/thumbs.sh" --f3d "$work/$set" \
                    "$work/out-f3d"
            done | median)
        echo "| $set | $n | $(rate "$n" "$b") | $(rate "$n" "$p") | $(rate "$n" "$f") |" \
             "$(ratio "$b" "$f")× | $(ratio "$p" "$f")× |"
    else
        echo "| $set | $n | $(rate "$n" "$b") | $(rate "$n" "$p") | - | - | - |"
    fi
done
