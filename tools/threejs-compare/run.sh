#!/bin/sh
# run.sh - renders glTF assets with `softrast render` and with three.js (in
# headless Chromium) under the same camera, environment, tone mapper and
# exposure, and prints a markdown table of their differences.
#
#   tools/threejs-compare/run.sh [options] [ASSET.glb|.gltf ...] [-- SOFTRAST-OPTIONS]
#
# Without assets, the test assets of make-assets.mjs; an animated one is
# posed by the "N SECONDS" of ASSET.pose beside it (--animation N --time
# SECONDS to both renderers).  Options (given to
# both renderers; each is left out of softrast's command when its `render
# --help` does not list it, and the table says so):
#   --size WxH          image size (default 256x256)
#   --tonemap T         neutral|aces|none (default neutral)
#   --exposure EV       (default 0)
#   --environment F     equirectangular Radiance .hdr (default: make-assets's sky.hdr)
#   --background #RGB   #rrggbb (default #1d2230, softrast's)
#   --environment-intensity S  the environment's radiance scale (default 0.6, softrast's)
# Options of this script:
#   --softrast BIN      (default build/softrast of this checkout)
#   --out DIR           renders, differences and assets (default out/threejs-compare)
#   --sheets DIR        where the side-by-side sheets go (default: --out)
#   --threshold T       codes a channel may differ before a pixel counts (default 16)
#   --lights L          none|key|rig: softrast's camera-relative lights three.js
#                       also gets (default key: what softrast adds to an environment)
#   --light-scale S     their intensities' scale (default 1.6, SR_PBR_LIGHT_SCALE)
# Everything after `--` goes to softrast alone.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
softrast=$root/build/softrast
out=$root/out/threejs-compare
sheets=
size=256x256
tonemap=neutral
exposure=0
environment=
background='#1d2230'
threshold=16
env_intensity=0.6
lights=key
light_scale=1.6
assets=
die() { echo "run.sh: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case $1 in
        --size|--tonemap|--exposure|--environment|--environment-intensity|--background|--softrast|--out|\
        --sheets|--threshold|--lights|--light-scale)
            [ $# -ge 2 ] || die "$1: missing value"
            case $1 in
                --size) size=$2 ;; --tonemap) tonemap=$2 ;; --exposure) exposure=$2 ;;
                --environment) environment=$(realpath "$2") ;; --background) background=$2 ;;
                --softrast) softrast=$(realpath "$2") ;; --out) out=$2 ;; --sheets) sheets=$2 ;;
                --threshold) threshold=$2 ;; --lights) lights=$2 ;; --light-scale) light_scale=$2 ;;
                --environment-intensity) env_intensity=$2 ;;
            esac
            shift 2 ;;
        --) shift; break ;;
        -*) die "unknown option '$1'" ;;
        *) assets="$assets $(realpath "$1")"; shift ;;
    esac
done
[ -x "$softrast" ] || die "$softrast: not built (cmake --build build --target softrast_cli)"
[ -d "$here/node_modules/three" ] || die "run 'npm ci' in $here first"
mkdir -p "$out"
sheets=${sheets:-$out}
mkdir -p "$sheets"
if [ -z "$assets" ] || [ -z "$environment" ]; then
    node "$here/make-assets.mjs" "$out/assets"
fi
[ -n "$assets" ] || assets=$(ls "$out"/assets/*.glb)
[ -n "$environment" ] || environment=$out/assets/sky.hdr

# The shared options softrast has; the rest are named in the table's notes.
help=$("$softrast" render --help)
sr_opts="--size $size --background $background"
missing=
has() { printf '%s\n' "$help" | grep -q -- "^ *$1 "; }
if has --tonemap; then sr_opts="$sr_opts --tonemap $tonemap"; else missing="$missing --tonemap"; fi
if has --exposure; then sr_opts="$sr_opts --exposure $exposure"; else missing="$missing --exposure"; fi
if has --environment; then sr_opts="$sr_opts --environment $environment"; else missing="$missing --environment"; fi
if has --environment-intensity; then
    sr_opts="$sr_opts --environment-intensity $env_intensity"
else
    missing="$missing --environment-intensity"
fi

# Relative to docs/ when the sheets are there, so the table links work in docs/*.md.
case $(realpath "$sheets") in
    "$root"/docs/*) link=$(realpath --relative-to="$root/docs" "$sheets") ;;
    *) link=$(realpath "$sheets") ;;
esac

rows=
webgl=
for asset in $assets; do
    name=$(basename "$asset"); name=${name%.*}
    # ASSET.pose beside an animated asset: "N SECONDS", its animation N at
    # that time for both renderers.
    pose=
    if [ -f "$asset.pose" ]; then
        read -r anim_n anim_t < "$asset.pose"
        pose="--animation $anim_n --time $anim_t"
    fi
    # shellcheck disable=SC2086 # word splitting of the option lists is meant
    "$softrast" render "$asset" $sr_opts $pose "$@" -o "$out/$name-softrast.png" >&2
    # shellcheck disable=SC2086
    info=$(node "$here/render-three.mjs" "$asset" $pose -o "$out/$name-three.png" --size "$size" \
        --tonemap "$tonemap" --exposure "$exposure" --environment "$environment" \
        --background "$background" --env-intensity "$env_intensity" --lights "$lights" \
        --light-scale "$light_scale")
    webgl=${info##*webgl=}
    json=$(node "$here/compare.mjs" "$out/$name-softrast.png" "$out/$name-three.png" \
        --threshold "$threshold" --background "$background" \
        --diff "$out/$name-diff.png" --sheet "$sheets/$name.png")
    # shellcheck disable=SC2016 # the single quotes hold JavaScript
    row=$(printf '%s' "$json" | node -e '
        const j = JSON.parse(require("fs").readFileSync(0, "utf8"));
        const [name, link] = process.argv.slice(1);
        console.log(`| ${name} | ${j.mad.join(" / ")} | ${j.psnr} | ${j.over_pct} | ${j.object_psnr} | ` +
                    `${j.object_over_pct} | [sheet](${link}/${name}.png) |`);' "$name" "$link")
    rows="$rows$row
"
done

commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
three=$(node -p "require('$here/node_modules/three/package.json').version")
chromium=$(chromium --version 2>/dev/null || echo unknown)
echo "$(date -u '+%Y-%m-%d %H:%M UTC'), softrast $commit, $cpu; three.js $three in $chromium, WebGL: $webgl."
echo
echo "softrast render ASSET$(echo " $sr_opts $*" | sed "s|$root/||g; s|  *$||"); three.js: the same size,"
echo "background and framing, tone mapping $tonemap, exposure $exposure EV, environment $(basename "$environment")"
echo "x $env_intensity, softrast's lights: $lights x $light_scale."
[ -z "$missing" ] || echo "softrast render has no${missing}: those are three.js's alone."
echo
echo "| asset | MAD R / G / B | PSNR (dB) | px > $threshold (%) | object PSNR (dB) | object px > $threshold (%) | softrast, three.js, difference x4 |"
echo "|---|---|---|---|---|---|---|"
printf '%s' "$rows"
