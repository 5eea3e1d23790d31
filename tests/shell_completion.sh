#!/bin/bash
# tests/shell_completion.sh SHELL TOOL_DIR SRC [COMPLETION]
#
# softrast's completion for SHELL (bash, zsh or fish) asked what it offers
# for command lines as that shell asks it: bash's
# share/bash-completion/completions/softrast sourced with the softrast of
# TOOL_DIR first on PATH (COMP_WORDS, COMP_CWORD), the built zsh
# COMPLETION (_softrast) in an interactive zsh (tests/zsh_complete.zsh),
# the built fish COMPLETION (softrast.fish) through fish's `complete -C`,
# each found where the shell looks for a command's completion.
# Each answer is compared with what the tool's --help lists, read here on
# its own: every option of every command, the choices of options, demo and
# algorithm names, the descriptions zsh and fish show, and files by
# extension; for bash, the model extensions with the ones the batch reader
# takes (SRC/apps/softrast/batch_inputs.c), which the others are written
# from.  Exits 77 (skipped) when SHELL is not installed.
set -u
if [ $# -lt 3 ] || { [ "$1" != bash ] && [ $# -ne 4 ]; }; then
    echo "usage: tests/shell_completion.sh bash|zsh|fish TOOL_DIR SRC [COMPLETION]" >&2
    exit 2
fi
shell=$1
PATH=$2:$PATH
src=$3
completion=${4-}
if ! command -v "$shell" >/dev/null; then
    echo "SKIP: $shell is not installed (Debian: $shell)"
    exit 77
fi
if [[ $shell == bash ]]; then
    # shellcheck source-path=SCRIPTDIR/.. source=share/bash-completion/completions/softrast
    source "$src/share/bash-completion/completions/softrast" || exit 1
fi
failures=0

# offered LINE: what SHELL offers for LINE<TAB>, one a line, as WORD or
# WORD<TAB>DESCRIPTION.
offered() {
    case $shell in
    bash)
        local -a COMP_WORDS
        read -ra COMP_WORDS <<<"$1"
        [[ $1 == *' ' ]] && COMP_WORDS+=('')
        COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
        COMP_LINE=$1
        COMP_POINT=${#COMP_LINE}
        COMPREPLY=()
        _softrast softrast "${COMP_WORDS[COMP_CWORD]}" "${COMP_WORDS[COMP_CWORD - 1]}"
        printf '%s\n' "${COMPREPLY[@]}"
        ;;
    zsh) printf '%s' "${zsh_answers[$1]-}" ;;
    fish)
        # shellcheck disable=SC2016 # fish expands $argv, not bash
        fish --no-config -c 'set -p fish_complete_path $argv[1]; complete -C $argv[2]' \
            "$(dirname "$completion")" "$1"
        ;;
    esac
}

# zsh completes every line in one session (each session takes about a
# second): the checks run once to collect the lines (ask LINE), then
# again on zsh's answers.
declare -A zsh_answers=()
collect=''
ask() {
    [[ -n $collect ]] && printf '%s\0' "$1" >>"$collect"
    [[ -z $collect ]]
}

# complete LINE: the words offered, sorted, each file by its name (bash
# and fish offer the path, zsh the name; fish's directories end in '/').
complete_words() {
    offered "$1" | cut -f1 | sed 's|/$||; s|.*/||' | sort -u | sed '/^$/d'
}

# expect LINE EXPECTED: the completion of LINE (its last word may be
# empty) is exactly the lines of EXPECTED.
expect() {
    local got want
    ask "$1" || return
    got=$(complete_words "$1")
    want=$(printf '%s\n' "$2" | sed 's|.*/||' | sort -u | sed '/^$/d')
    if [[ $got != "$want" ]]; then
        echo "FAIL: '$1<TAB>'"
        diff <(echo "$want") <(echo "$got") | sed 's/^/  /'
        failures=$((failures + 1))
    else
        echo "ok: '$1<TAB>' ($(echo "$got" | wc -l) words)"
    fi
}

# describe LINE WORD DESCRIPTION: the completion of LINE shows WORD with
# DESCRIPTION (zsh and fish).
describe() {
    [[ $shell == bash ]] && return
    local got
    ask "$1" || return
    got=$(offered "$1" | sed -n "s/^$2\t//p" | head -n 1)
    if [[ $got != "$3" ]]; then
        echo "FAIL: '$1<TAB>' describes $2 as '$got', --help as '$3'"
        failures=$((failures + 1))
    else
        echo "ok: '$1<TAB>' describes $2"
    fi
}

# From a help text: the first words of the items (lines indented two
# spaces) below the line HEADING, up to a blank line.
items_under() { sed -n "/^$1\$/,/^\$/s/^  \\([^ ][^ ]*\\).*/\\1/p"; }
# The options in the terms of a help text's items.
options() {
    sed -n 's/^  \(-[^ ].*\)$/\1/p' | sed 's/  .*//' | tr ' ,|' '\n' | grep -E '^--?[A-Za-z0-9]'
}
long_options() { options | grep -E '^--[a-z]'; }
# The description of the item whose term holds WORD, its lines joined.
description() {
    awk -v word="$1" '
        /^  [^ ]/ {
            if (found) exit
            term = substr($0, 3); text = ""
            i = index(term, "  ")
            if (i) { text = substr(term, i); term = substr(term, 1, i - 1) }
            n = split(term, w, /[ ,|]+/)
            for (k = 1; k <= n; k++) if (w[k] == word) found = 1
            next
        }
        /^   / && found { text = text " " $0; next }
        found { exit }
        END { print text }' | tr -s ' ' | sed 's/^ //; s/ $//'
}

# The files the checks complete: by extension, in either case (a name
# with a space is one word), and directories.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir "$dir/sub"
touch "$dir/a.obj" "$dir/b.STL" "$dir/c.glb" "$dir/my part.ply" "$dir/notes.txt" "$dir/logo.svg" \
    "$dir/icon.SVGZ" "$dir/run.jsonl"
commands=$(softrast --help | items_under commands: | grep -v '^softrast')

checks() {
    if [[ $shell == bash ]]; then
        expect "softrast " "$(printf '%s\n' "$commands" --help --version)"
    else
        expect "softrast " "$commands"
    fi
    expect "softrast re" "render"
    expect "softrast --" "$(printf -- '--help\n--version')"
    describe "softrast sv" svg "$(softrast --help | description svg)"
    # Every option of every command; view takes render's too.
    for cmd in $commands; do
        if [[ $cmd == view ]]; then
            expect "softrast $cmd -" "$(softrast view --help | options; softrast render --help | options)"
        else
            expect "softrast $cmd -" "$(softrast "$cmd" --help | options)"
        fi
    done
    expect "softrast view --no-" "$(softrast view --help | long_options | grep '^--no-')"
    describe "softrast render --shadi" --shading "$(softrast render --help | description --shading)"
    describe "softrast render --shard-" --shard-count "$(softrast render --help | description --shard-count)"
    describe "softrast svg --sc" --scale "$(softrast svg --help | description --scale)"
    expect "softrast demo " "$(softrast demo --help | items_under demos:)"
    describe "softrast demo li" lines "$(softrast demo --help | description lines)"
    expect "softrast explain " "$(softrast explain --help | items_under algorithms:)"
    describe "softrast explain forward" forward-differencing \
        "$(softrast explain --help | description forward-differencing)"
    expect "softrast render --shading " \
        "$(softrast render --help | sed -n 's/^  --shading MODE *\([a-z|]*\) .*/\1/p' | tr '|' '\n')"
    expect "softrast render --up " "$(printf -- '+x\n-x\n+y\n-y\n+z\n-z')"
    expect "softrast view --aa " \
        "$(softrast render --help | sed -n 's/^  --aa MODE *\([a-z0-9|]*\): .*/\1/p; s/^ *and filter them down; \([a-z0-9|]*\): .*/\1/p' | tr '|' '\n')"
    expect "softrast explain triangle --connectivity " "$(printf '4\n8')"
    # Files by extension.
    models=$(printf '%s\n' a.obj b.STL c.glb 'my part.ply' sub)
    expect "softrast render $dir/" "$models"
    expect "softrast thumbnail $dir/" "$models"
    expect "softrast view $dir/" "$models"
    expect "softrast svg $dir/" "$(printf '%s\n' icon.SVGZ logo.svg sub)"
    expect "softrast render --log $dir/" "$(printf '%s\n' run.jsonl sub)"
    expect "softrast render --output-dir $dir/" "sub"
    expect "softrast svg -o $dir/" "$(cd "$dir" && ls)"
}

if [[ $shell == zsh ]]; then
    collect=$dir/lines
    checks
    collect=''
    mapfile -d '' -t lines <"$dir/lines"
    i=0
    while IFS= read -r answer; do
        if [[ $answer == --- ]]; then
            i=$((i + 1))
        else
            zsh_answers[${lines[i]}]+=$answer$'\n'
        fi
    done < <(zsh -f "$src/tests/zsh_complete.zsh" "$(dirname "$completion")" "${lines[@]}")
    if ((i != ${#lines[@]})); then
        echo "FAIL: zsh answered $i of ${#lines[@]} lines"
        failures=$((failures + 1))
    fi
fi
checks

if [[ $shell == bash ]]; then
    # The extensions are the batch reader's: its own formats, then Assimp's.
    readers=$(sed -n 's/.*const own\[\] = { \(.*\), NULL };/\1/p; s/.*const assimp\[\] = { \(.*\), NULL };/\1/p' \
        "$src/apps/softrast/batch_inputs.c" | tr -d '" ' | tr ',\n' '||' | sed 's/|$//')
    if [[ -z $readers || $readers != "$_softrast_models" ]]; then
        echo "FAIL: the completion's model extensions '$_softrast_models' are not the readers' '$readers'"
        failures=$((failures + 1))
    fi
fi

if ((failures)); then
    echo "$failures failures"
    exit 1
fi
echo "$shell completion: all checks passed"
