#!/usr/bin/python3
"""tools/manpage.py - a manual page (softrast(1), softrast-bench(1)),
written at build time from the tool's own help texts so that it cannot
drift from them.

    manpage.py [--hide TEXT WORDS]... TEMPLATE OUTPUT TOOL...

TOOL... (the tool, after a cross build's emulator if any) is run as
`TOOL --help` and `TOOL --version`.  TEMPLATE (tools/softrast.1.in,
tools/softrast-bench.1.in) holds the hand-written sections; its @DATE@
and @VERSION@ become the build's date and the version.  A tool of
commands (softrast) is run as `TOOL COMMAND --help` for each command the
first help lists, and @SYNOPSIS@ and @COMMANDS@ become the commands'
usage lines and help texts; a tool without (softrast-bench) has its
usage as @SYNOPSIS@ and the rest of its help as @HELP@.  The help texts
are read by their layout (tools/helptext.py).  --hide puts WORDS for
TEXT in the help: a path compiled into the tool that is the build
machine's, not the reader's."""
import os
import re
import sys
import time

from helptext import parse, read, run

OPTION = re.compile(r"(?<![\w-])(--?[A-Za-z0-9][\w-]*)")


def escape(text):
    """Roff text: backslashes shown as such, options' hyphens as minus
    signs (no line is broken inside an option, and they copy as '-')."""
    text = text.replace("\\", "\\e")
    return OPTION.sub(lambda m: m.group(1).replace("-", "\\-"), text)


def line(text):
    """A text line that no roff request can be mistaken for."""
    return "\\&" + text if text[:1] in (".", "'") else text


def bold_options(term):
    return re.sub(r"(\\-[\w\\-]*)", r"\\fB\1\\fR", escape(term))


def roff_blocks(blocks):
    out = []
    last = None
    for b in blocks:
        if b[0] == "break":
            last = None
            continue
        if b[0] == "prose":
            out.append(".PP")
            for i, text in enumerate(b[1]):
                # "keys: ..." after "mouse: ...": a new line, as in the help.
                if i > 0 and re.match(r"\w+: ", text):
                    out.append(".br")
                out.append(line(escape(text)))
        elif b[0] == "group":
            out += [".PP", line("\\fI" + escape(b[1]) + "\\fR")]
        else:
            # A term without a description shares the next one's (.TQ)
            # when that one's starts below it too (render's two --light).
            joined = last is not None and last[0] == "item" and not last[2] and not b[3]
            out += [".TQ" if joined else ".TP", line(bold_options(b[1]))]
            if b[2]:
                out.append(line(escape(" ".join(b[2]))))
        last = b
    return out


def synopsis(usage, name_words=2):
    """Usage lines with their first name_words words (the command) bold."""
    out = []
    for u in usage:
        words = u.split(" ", name_words)
        out += [".br"] if out else []
        out += [line("\\fB" + escape(" ".join(words[:name_words])) + "\\fR " +
                                              escape(" ".join(words[name_words:])))]
    return out


def main(argv):
    if len(argv) < 4:
        sys.stderr.write(__doc__)
        return 2
    hides = []
    while len(argv) >= 4 and argv[1] == "--hide":
        hides.append((argv[2], argv[3]))
        argv = argv[:1] + argv[4:]
    if len(argv) < 4:
        sys.stderr.write(__doc__)
        return 2
    template_path, output_path, tool = argv[1], argv[2], argv[3:]
    version = run(tool, "--version").split()[-1]
    with open(template_path, encoding="utf-8") as f:
        page = f.read()
    usage_lines, section, name_words = [], [], 2
    if "@HELP@" in page:
        text = run(tool, "--help")
        for hidden, words in hides:
            text = text.replace(hidden, words)
        usage_lines, blocks = parse(text)
        name_words = 1
        page = page.replace("@HELP@\n", "\n".join(roff_blocks(blocks)) + "\n")
    for name, _, usage, blocks in read(tool)[1] if "@COMMANDS@" in page else []:
        usage_lines += usage
        section += ['.SS "softrast %s"' % name] + synopsis(usage) + roff_blocks(blocks)
    page = page.replace("@VERSION@", version)
    # The build's date as help2man gives it: SOURCE_DATE_EPOCH's for a
    # reproducible build, else today's.
    stamp = int(os.environ.get("SOURCE_DATE_EPOCH", time.time()))
    page = page.replace("@DATE@", time.strftime("%Y-%m-%d", time.gmtime(stamp)))
    page = page.replace("@SYNOPSIS@\n", "\n".join(synopsis(usage_lines, name_words)) + "\n")
    page = page.replace("@COMMANDS@\n", "\n".join(section) + "\n")
    with open(output_path + ".tmp", "w", encoding="utf-8") as f:
        f.write(page)
    os.replace(output_path + ".tmp", output_path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
