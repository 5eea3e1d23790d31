# tests/man_page_common.sh - sourced by man_page.sh and bench_man_page.sh
# with $man set: exits 77 (skipped) without groff; else sources
# check_common.sh ($work, fail, finish), defines has_word, checks that
# groff (and mandoc, where installed) format the page without a warning,
# and writes the page as a reader sees it, each paragraph on one line (no
# hyphenation, wide lines), without bold or underlining, to
# $work/page.txt.
if ! command -v groff >/dev/null; then
    echo "SKIP: groff is not installed (Debian: groff-base)"
    exit 77
fi
. "$(dirname "$0")/check_common.sh"

has_word() { # FILE WORD: WORD in FILE, not as part of a longer word
    grep -Eq -- "(^|[^A-Za-z0-9_-])$2([^A-Za-z0-9_-]|\$)" "$1"
}

groff -man -ww -z "$man" 2>"$work/groff.err" || fail "groff failed"
if [ -s "$work/groff.err" ]; then
    fail "groff -man -ww warns:"
    cat "$work/groff.err"
fi
if command -v mandoc >/dev/null; then
    if ! mandoc -Tlint -W warning "$man" >"$work/mandoc.err" 2>&1 || [ -s "$work/mandoc.err" ]; then
        fail "mandoc -Tlint warns:"
        cat "$work/mandoc.err"
    fi
else
    echo "note: mandoc is not installed; its lint is left out"
fi
groff -man -Tascii -P-cbou -rLL=250n -rHY=0 "$man" 2>/dev/null >"$work/page.txt"
