#!/bin/sh
# tests/man_page.sh MANPAGE SRC TOOL...
#
# The built softrast(1) against the tool it documents: groff (and mandoc,
# where installed) format it without a warning; each command of
# `TOOL --help` has a section holding its usage line and every option and
# name its `TOOL COMMAND --help` lists, and the EXAMPLES use no other
# option; the ENVIRONMENT section names every variable the library and the
# tool read (getenv in SRC's src/ and apps/).  Exits 77 (skipped) without
# groff.
set -eu
if [ $# -lt 3 ]; then
    echo "usage: tests/man_page.sh MANPAGE SRC TOOL..." >&2
    exit 2
fi
man=$1
src=$2
shift 2
. "$(dirname "$0")/man_page_common.sh"

# Lines of the rendered page from the heading "   softrast CMD" to the next
# heading.
section() {
    awk -v head="   softrast $1" '
        $0 == head { on = 1; next }
        on && (/^[A-Z]/ || /^   softrast [a-z]+$/) { exit }
        on { print }' "$work/page.txt"
}

# A help text's items: lines indented two spaces; the term ends at two
# spaces.  Options are the -x and --xx words of a term; names are the
# first words of terms that are not options.
terms() { sed -n 's/^  \([^ ].*\)$/\1/p' | sed 's/  .*//'; }
options() { terms | grep '^-' | tr ' ,|' '\n' | grep -E '^--?[A-Za-z0-9]' || true; }
names() { terms | grep -v '^-' | grep -v '^softrast' | sed 's/ .*//'; }

"$@" --help >"$work/top.txt"
commands=$(names <"$work/top.txt")
[ -n "$commands" ] || fail "no commands read from '$* --help'"
for cmd in $commands; do
    "$@" "$cmd" --help >"$work/help.txt"
    section "$cmd" >"$work/section.txt"
    if [ ! -s "$work/section.txt" ]; then
        fail "no section 'softrast $cmd' in the page"
        continue
    fi
    count=0
    for word in $(options <"$work/help.txt") $(names <"$work/help.txt"); do
        count=$((count + 1))
        has_word "$work/section.txt" "$word" || fail "softrast $cmd: '$word' is not in its section"
    done
    [ "$count" -gt 0 ] || fail "softrast $cmd --help lists nothing"
    # The usage line, spaces squeezed, in the section and in the synopsis.
    usage=$(sed -n '1s/^usage: //p' "$work/help.txt" | tr -s ' ')
    tr -s ' ' <"$work/page.txt" | grep -qF -- " $usage" || fail "softrast $cmd: usage '$usage' is not in the page"
    echo "softrast $cmd: $count options and names found"
    # The EXAMPLES use only options the command has.
    awk '/^EXAMPLES$/ { on = 1; next } on && /^[A-Z]/ { exit } on { print }' "$work/page.txt" |
        sed -n "s/^ *softrast $cmd //p" | tr ' ' '\n' | grep -E '^--?[A-Za-z]' >"$work/used.txt" || true
    options <"$work/help.txt" >"$work/options.txt"
    while read -r word; do
        grep -qxF -- "$word" "$work/options.txt" || fail "EXAMPLES: softrast $cmd has no option $word"
    done <"$work/used.txt"
done

# Every variable read is documented.
awk '/^ENVIRONMENT$/ { on = 1; next } on && /^[A-Z]/ { exit } on { print }' \
    "$work/page.txt" >"$work/environment.txt"
vars=$(grep -rhoE '(getenv|env_whole)\("[A-Za-z_0-9]+"' "$src/src" "$src/apps" |
       sed 's/.*("//; s/"$//' | sort -u)
[ -n "$vars" ] || fail "no getenv calls found under $src"
for v in $vars; do
    has_word "$work/environment.txt" "$v" || fail "ENVIRONMENT does not name $v"
done

finish "man page"
