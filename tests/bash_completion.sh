#!/bin/bash
# tests/bash_completion.sh TOOL_DIR SRC
#
# share/bash-completion/completions/softrast sourced in a non-interactive
# bash, with the softrast of TOOL_DIR first on PATH, completing as bash
# would (COMP_WORDS, COMP_CWORD): each answer is compared with what the
# tool's --help lists, read here on its own, and the model extensions with
# the ones the batch reader takes (SRC/apps/softrast/batch_inputs.c).
set -u
if [ $# -ne 2 ]; then
    echo "usage: tests/bash_completion.sh TOOL_DIR SRC" >&2
    exit 2
fi
PATH=$1:$PATH
src=$2
# shellcheck source-path=SCRIPTDIR/.. source=share/bash-completion/completions/softrast
source "$src/share/bash-completion/completions/softrast" || exit 1
failures=0

# complete WORD...: COMPREPLY for the last WORD, sorted, one a line.
complete_words() {
    COMP_WORDS=("$@")
    COMP_CWORD=$(($# - 1))
    COMP_LINE="$*"
    COMP_POINT=${#COMP_LINE}
    COMPREPLY=()
    _softrast softrast "${COMP_WORDS[COMP_CWORD]}" "${COMP_WORDS[COMP_CWORD - 1]}"
    printf '%s\n' "${COMPREPLY[@]}" | sort -u | sed '/^$/d'
}

# expect "WORDS" EXPECTED: the completion of WORDS (the last one may be
# empty) is exactly the lines of EXPECTED.
expect() {
    local got want
    read -ra words <<<"$1"
    [[ $1 == *' ' ]] && words+=('')
    got=$(complete_words "${words[@]}")
    want=$(printf '%s\n' "$2" | sort -u | sed '/^$/d')
    if [[ $got != "$want" ]]; then
        echo "FAIL: '$1<TAB>'"
        diff <(echo "$want") <(echo "$got") | sed 's/^/  /'
        failures=$((failures + 1))
    else
        echo "ok: '$1<TAB>' ($(echo "$got" | wc -l) words)"
    fi
}

# From a help text: the first words of the items (lines indented two
# spaces) below the line HEADING, up to a blank line.
items_under() { sed -n "/^$1\$/,/^\$/s/^  \\([^ ][^ ]*\\).*/\\1/p"; }
# The --long options in the terms of a help text's items.
long_options() {
    sed -n 's/^  \(-[^ ].*\)$/\1/p' | sed 's/  .*//' | tr ' ,|' '\n' | grep -E '^--[a-z]'
}

expect "softrast re" "render"
expect "softrast " "$(softrast --help | items_under commands: | grep -v '^softrast')
--help
--version"
expect "softrast render --" "$(softrast render --help | long_options)"
expect "softrast svg --" "$(softrast svg --help | long_options)"
expect "softrast view --no-" "$(softrast view --help | long_options | grep '^--no-')"
expect "softrast demo " "$(softrast demo --help | items_under demos:)"
expect "softrast explain " "$(softrast explain --help | items_under algorithms:)"
expect "softrast render --shading " \
    "$(softrast render --help | sed -n 's/^  --shading MODE *\([a-z|]*\) .*/\1/p' | tr '|' '\n')"
expect "softrast explain triangle --connectivity " "$(printf '4\n8')"

# File arguments by extension, in either case (a name with a space is one
# word), and directories.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir "$dir/sub"
touch "$dir/a.obj" "$dir/b.STL" "$dir/c.glb" "$dir/my part.ply" "$dir/notes.txt" "$dir/logo.svg" \
    "$dir/run.jsonl"
models="$dir/a.obj
$dir/b.STL
$dir/c.glb
$dir/my part.ply
$dir/sub"
expect "softrast render $dir/" "$models"
expect "softrast thumbnail $dir/" "$models"
expect "softrast svg $dir/" "$dir/logo.svg
$dir/sub"
expect "softrast render --log $dir/" "$dir/run.jsonl
$dir/sub"
expect "softrast render --output-dir $dir/" "$dir/sub"

# The extensions are the batch reader's: its own formats, then Assimp's.
readers=$(sed -n 's/.*const own\[\] = { \(.*\), NULL };/\1/p; s/.*const assimp\[\] = { \(.*\), NULL };/\1/p' \
    "$src/apps/softrast/batch_inputs.c" | tr -d '" ' | tr ',\n' '||' | sed 's/|$//')
if [[ -z $readers || $readers != "$_softrast_models" ]]; then
    echo "FAIL: the completion's model extensions '$_softrast_models' are not the readers' '$readers'"
    failures=$((failures + 1))
fi

if ((failures)); then
    echo "$failures failures"
    exit 1
fi
echo "bash completion: all checks passed"
