#!/usr/bin/python3
"""tools/completions.py - softrast's zsh and fish completions, written at
build time from the tool's own help texts so that they cannot drift from
them.

    completions.py BASH_COMPLETION ZSH_OUTPUT FISH_OUTPUT TOOL...

TOOL... (the tool, after a cross build's emulator if any) is run as
`TOOL --help` and `TOOL COMMAND --help` for each command it lists; the
texts are read as tools/helptext.py says.  Both completions offer the
commands, each command's options with their descriptions (view's own,
then render's, which view takes too), the values of options that take
one of a fixed set, demo and algorithm names, and files by extension.
The model extensions are BASH_COMPLETION's _softrast_models, which its
test holds to the batch reader's (the help names only some)."""
import os
import re
import sys

import helptext

# What each command's arguments are: model files, SVG files, or one of the
# names its help lists (demos, algorithms).
ARGUMENTS = {"render": "models", "view": "models", "thumbnail": "models",
             "svg": "svg", "demo": "names", "explain": "names"}
# Commands that take another command's options too.
BORROWS = {"view": "render"}


def model_extensions(bash_completion):
    with open(bash_completion, encoding="utf-8") as f:
        m = re.search(r"^_softrast_models='([a-z0-9|]+)'$", f.read(), re.M)
    if not m:
        raise SystemExit(f"{bash_completion}: no _softrast_models='...' line")
    return m.group(1)


def command_options(commands):
    """Each command's Options, a borrowed command's after its own."""
    own = {name: helptext.options(blocks) for name, _, _, blocks in commands}
    out = {}
    for name in own:
        opts = list(own[name])
        seen = {n for o in opts for n in o.names}
        for o in own.get(BORROWS.get(name), []):
            kept = [n for n in o.names if n not in seen]
            if kept:
                opts.append(helptext.Option(kept, o.arg, o.description))
        out[name] = opts
    return out


def names_heading(blocks):
    """The heading of the group of names in a help text ("demos")."""
    heading = "names"
    for b in blocks:
        if b[0] == "group":
            heading = b[1].rstrip(":")
        elif b[0] == "item" and not b[1].startswith(("-", "softrast")):
            return heading
    return heading


def sq(text):
    """TEXT in single quotes for zsh and fish."""
    return "'" + text.replace("'", "'\\''") + "'"


# ---- zsh ---------------------------------------------------------------

def zsh_files(exts):
    """_files for names ending in one of EXTS ('a|b', any case), its
    pattern's specials quoted (_arguments reads an action's words).  One
    extension goes without parentheses, which would end the pattern in
    glob qualifiers."""
    pattern = "*.(#i)" + ("(%s)" % exts if "|" in exts else exts)
    return "_files -g " + re.sub(r"([*.()#|])", r"\\\1", pattern) if exts else "_files"


def zsh_action(value):
    if value[0] == "choices":
        return "(%s)" % " ".join(value[1])
    if value[0] == "dir":
        return "_files -/"
    if value[0] == "file":
        return zsh_files(value[1])
    return " "  # a value with nothing to offer: _arguments shows the message


def zsh_option(opt):
    """_arguments specs for OPT: each name excludes its other names, a
    repeatable option may be given again."""
    desc = opt.description.replace("\\", "\\\\").replace("]", "\\]")
    value = opt.value()
    tail = ""
    if value:
        tail = ":%s:%s" % (opt.arg.replace(":", "\\:"), zsh_action(value))
    repeat = "*" if "repeatable" in opt.description else ""
    exclude = "(%s)" % " ".join(opt.names) if len(opt.names) > 1 and not repeat else ""
    return [exclude + repeat + name + "[" + desc + "]" + tail for name in opt.names]


def zsh(commands, models):
    opts = command_options(commands)
    out = ["#compdef softrast",
           "# zsh completion for softrast(1), written by tools/completions.py from the",
           "# tool's --help when it was built.",
           "",
           "_softrast() {",
           "    local curcontext=$curcontext state state_descr line ret=1",
           "    local -a commands names",
           "    typeset -A opt_args",
           "    _arguments -C \\",
           "        '(- :)--help[list the commands]' \\",
           "        '(- :)--version[print the version]' \\",
           "        '1:command:->command' \\",
           "        '*::argument:->argument' && ret=0",
           "    case $state in",
           "    command)",
           "        commands=("]
    for name, desc, _, _ in commands:
        out.append("            " + sq(name + ":" + desc))
    out += ["        )",
            "        _describe -t commands 'softrast command' commands && ret=0",
            "        ;;",
            "    argument)",
            "        curcontext=${curcontext%:*:*}:softrast-$words[1]:",
            "        case $words[1] in"]
    for name, _, _, blocks in commands:
        kind = ARGUMENTS.get(name, "files")
        specs = [s for o in opts[name] for s in zsh_option(o)]
        what = names_heading(blocks)
        if kind == "models":
            specs.append("*:model:" + zsh_files(models))
        elif kind == "svg":
            specs.append("*:drawing:" + zsh_files("svg|svgz"))
        elif kind == "names":
            specs.append("1:%s:->name" % what)
        else:
            specs.append("*:file:_files")
        out.append("        %s)" % name)
        if kind == "names":
            out.append("            names=(")
            out += ["                " + sq(n + ":" + d) for n, d in helptext.names(blocks)]
            out.append("            )")
        out.append("            _arguments \\")
        out += ["                %s \\" % sq(s) for s in specs[:-1]]
        out.append("                %s && ret=0" % sq(specs[-1]))
        if kind == "names":
            out.append("            [[ $state == name ]] && _describe -t names %s names && ret=0"
                       % sq(what))
        out.append("            ;;")
    out += ["        esac",
            "        ;;",
            "    esac",
            "    return ret",
            "}",
            "",
            '_softrast "$@"',
            ""]
    return "\n".join(out)


# ---- fish --------------------------------------------------------------

FISH_HEAD = r"""# fish completion for softrast(1), written by tools/completions.py from the
# tool's --help when it was built.

# True when the command line's command (its second word) is one of ARGV.
function __softrast_command
    set -l words (commandline -opc)
    test (count $words) -ge 2; and contains -- $words[2] $argv
end

# True when the command line holds only COMMAND so far.
function __softrast_first_argument -a command
    set -l words (commandline -opc)
    test (count $words) -eq 2 -a "$words[2]" = "$command"
end

# Files whose names end in one of EXTS ('a|b', any case), and directories
# to reach them, for the token being completed.
function __softrast_files -a exts
    set -l files (complete -C "__fish_command_without_completions "(commandline -ct))
    string match -r -- '^.*/$' $files
    string match -ri --entire -- "\\.(?:$exts)\$" $files
end

complete -c softrast -f
complete -c softrast -n 'test (count (commandline -opc)) -eq 1' -l help -d 'list the commands'
complete -c softrast -n 'test (count (commandline -opc)) -eq 1' -l version -d 'print the version'
"""


def fish_option(cmd, opt):
    """complete lines for OPT: its values (without its description, which
    fish would show beside each), then the option with its description."""
    head = ["complete -c softrast -n", sq("__softrast_command " + cmd)]
    for name in opt.names:
        head += ["-l", name[2:]] if name.startswith("--") else ["-s", name[1:]]
    value = opt.value()
    values = None
    if value is None:
        pass
    elif value[0] == "choices":
        values = " ".join(value[1])
    elif value[0] == "dir":
        values = "(__fish_complete_directories)"
    elif value[0] == "file" and value[1]:
        values = "(__softrast_files %s)" % value[1]
    elif value[0] == "file":
        head.append("-r -F")
    else:
        head.append("-x")
    lines = []
    if values:
        lines.append(" ".join(head + ["-x -a", sq(values)]))
        head.append("-x")
    lines.append(" ".join(head + (["-d", sq(opt.description)] if opt.description else [])))
    return lines


def fish(commands, models):
    opts = command_options(commands)
    out = [FISH_HEAD]
    for name, desc, _, _ in commands:
        out.append("complete -c softrast -n 'test (count (commandline -opc)) -eq 1' -a %s -d %s"
                   % (name, sq(desc)))
    for name, _, _, blocks in commands:
        out.append("")
        out += [line for o in opts[name] for line in fish_option(name, o)]
        kind = ARGUMENTS.get(name, "files")
        cond = sq("__softrast_command " + name)
        if kind == "models":
            out.append("complete -c softrast -n %s -a %s" % (cond, sq("(__softrast_files '%s')" % models)))
        elif kind == "svg":
            out.append("complete -c softrast -n %s -a %s" % (cond, sq("(__softrast_files 'svg|svgz')")))
        elif kind == "names":
            for n, d in helptext.names(blocks):
                out.append("complete -c softrast -n %s -a %s -d %s"
                           % (sq("__softrast_first_argument " + name), n, sq(d)))
        else:
            out.append("complete -c softrast -n %s -F" % cond)
    return "\n".join(out) + "\n"


def write(path, text):
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def main(argv):
    if len(argv) < 5:
        sys.stderr.write(__doc__)
        return 2
    bash_completion, zsh_path, fish_path, tool = argv[1], argv[2], argv[3], argv[4:]
    models = model_extensions(bash_completion)
    commands = helptext.read(tool)[1]
    write(zsh_path, zsh(commands, models))
    write(fish_path, fish(commands, models))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
