#!/bin/sh
# tests/bench_man_page.sh MANPAGE SRC MODELS TOOL...
#
# The built softrast-bench(1) against the bench it documents, as
# tests/man_page.sh holds softrast(1) to the tool: groff (and mandoc,
# where installed) format it without a warning; its OPTIONS hold every
# option and scene `TOOL --help` lists, and the SYNOPSIS its usage line;
# its header names the version `TOOL --version` prints; "--" ends the
# options; the ENVIRONMENT section names every variable the bench reads
# (getenv in SRC's bench/); the build machine's paths (SRC, and MODELS,
# the models directory compiled in) are not in it, the help's words for a
# reader of any machine are.  Exits 77 (skipped) without groff.
set -eu
if [ $# -lt 4 ]; then
    echo "usage: tests/bench_man_page.sh MANPAGE SRC MODELS TOOL..." >&2
    exit 2
fi
man=$1
src=$2
models=$3
shift 3
. "$(dirname "$0")/man_page_common.sh"

section() {
    awk -v head="$1" '$0 == head { on = 1; next } on && /^[A-Z]/ { exit } on { print }' \
        "$work/page.txt"
}
section OPTIONS >"$work/options.txt"
section ENVIRONMENT >"$work/environment.txt"
[ -s "$work/options.txt" ] || fail "no OPTIONS section"

# Every option and every scene of the help: the terms of the lines
# indented two spaces (the term ends at two spaces), split at ", ".
"$@" --help >"$work/help.txt"
sed -n 's/^  \([^ ].*\)$/\1/p' "$work/help.txt" | sed 's/  .*//' | sed 's/, /\n/g' |
    sed 's/ .*//' >"$work/terms.txt"
count=0
while read -r term; do
    count=$((count + 1))
    has_word "$work/options.txt" "$term" || fail "'$term' of --help is not in OPTIONS"
done <"$work/terms.txt"
[ "$count" -ge 20 ] || fail "only $count options and scenes read from --help"
echo "softrast-bench: $count options and scenes found"

usage=$(sed -n '1,/^$/p' "$work/help.txt" | sed 's/^usage: //' | tr -s ' \n' '  ' | sed 's/ *$//')
tr -s ' \n' '  ' <"$work/page.txt" | grep -qF -- "$usage" ||
    fail "the usage '$usage' is not in the page"

version=$("$@" --version | awk '{ print $NF }')
[ -n "$version" ] || fail "'$* --version' prints no version"
grep -q "softrast $version" "$work/page.txt" || fail "the page does not name version $version"

# "--" ends the options, as every softrast command takes it.
if "$@" -- --help >"$work/out.txt" 2>"$work/err.txt" || ! grep -q "unknown scene '--help'" "$work/err.txt"; then
    fail "'$* -- --help' does not take --help as a scene"
fi

vars=$(grep -rhoE 'getenv\("[A-Za-z_0-9]+"' "$src/bench" | sed 's/.*("//; s/"$//' | sort -u)
[ -n "$vars" ] || fail "no getenv calls found under $src/bench"
for v in $vars; do
    has_word "$work/environment.txt" "$v" || fail "ENVIRONMENT does not name $v"
done

for path in "$src" "$models"; do
    ! grep -qF -- "$path" "$man" || fail "the page holds the build's path $path"
done
grep -q "else the models directory it was built with" "$work/page.txt" ||
    fail "the page does not say where the models come from"

finish "bench man page"
