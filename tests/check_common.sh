# tests/check_common.sh - sourced by the shell tests (man_page_common.sh,
# bench_options.sh): sets $work (a directory removed at exit) and
# $failures, and defines fail (count a failure, saying why) and finish
# (NAME: exit 1 after the failures, else say that NAME passed).
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}

finish() {
    if [ "$failures" -gt 0 ]; then
        echo "$failures failures"
        exit 1
    fi
    echo "$1: all checks passed"
}
