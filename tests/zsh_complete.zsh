#!/usr/bin/zsh -f
# tests/zsh_complete.zsh FPATH_DIR LINE...: what zsh's completion system
# offers for each LINE<TAB>, one a line: WORD, or WORD<TAB>DESCRIPTION
# when it shows one (file names unquoted), and a line '---' after each
# LINE's.  One interactive zsh on a pseudo-terminal (zpty), FPATH_DIR
# first on its fpath, completes them all, its compadd writing down each
# match as it adds it.
zmodload zsh/zpty || exit 1
export SR_ZSH_FPATH=$1 SR_ZSH_MATCHES=$(mktemp) || exit 1
setup='
setopt interactive_comments
stty columns 4000  # descriptions are cut to the terminal width
PS1="> "
unsetopt auto_list prompt_sp  # matches are written down, not listed; no padding
fpath=($SR_ZSH_FPATH $fpath)
autoload -Uz compinit && compinit -u -D
compadd() {
    # Calls that only ask which words match add nothing.
    if [[ ${@[1,(i)(-|--)]} == *-(O|A|D)\ * ]]; then
        builtin compadd "$@"
        return
    fi
    local -a words shown
    local i d=${@[(i)-d]} tab=$'\''\t'\''
    (( d < $# )) && shown=("${(@P)@[d+1]}")
    builtin compadd -O words ${shown:+-D shown} "$@"
    for i in {1..$#words}; do
        if [[ $shown[i] == *" -- "* ]]; then
            print -r -- "${(Q)words[i]}$tab${shown[i]#* -- }"
        else
            print -r -- "${(Q)words[i]}"
        fi
    done >>$SR_ZSH_MATCHES
    builtin compadd "$@"
}
print -r -- R${:-EADY}
'
zpty z zsh -f -i
zpty -w z "$setup"
# Type-ahead before a prompt can be lost: each line waits for one.
zpty -r z x '*READY*> *' || exit 1
shift
for line; do
    zpty -w -n z "$line"$'\t'
    zpty -w z $'\C-u'"print -r -- --- >>\$SR_ZSH_MATCHES; print -r -- M\${:-ARK}"
    zpty -r z x '*MARK*> *' || exit 1
done
zpty -d z
cat -- $SR_ZSH_MATCHES
rm -f -- $SR_ZSH_MATCHES
