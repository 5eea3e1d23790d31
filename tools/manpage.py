#!/usr/bin/python3
"""tools/manpage.py - the manual page softrast(1), written at build time
from the tool's own help texts so that it cannot drift from them.

    manpage.py TEMPLATE OUTPUT TOOL...

TOOL... (the tool, after a cross build's emulator if any) is run as
`TOOL --help`, `TOOL --version` and `TOOL COMMAND --help` for each command
the first one lists.  TEMPLATE (tools/softrast.1.in) holds the hand-written
sections; its @DATE@, @VERSION@, @SYNOPSIS@ and @COMMANDS@ become the
build's date, the version, and the commands' usage lines and help texts.

A help text is read by its layout: a line at column 0 is prose (one ending
in ':' before an indented item heads a group), a line indented two spaces
starts an item (its term, then after two spaces or more its description),
and a line indented deeper continues the item or prose above it."""
import os
import re
import subprocess
import sys
import time

OPTION = re.compile(r"(?<![\w-])(--?[A-Za-z0-9][\w-]*)")


def run(tool, *args):
    out = subprocess.run(tool + list(args), check=True, stdout=subprocess.PIPE, text=True)
    return out.stdout


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


def parse(text):
    """The help text as (usage lines, blocks): each block is ('prose',
    lines), ('group', heading) or ('item', term, description lines,
    whether the description starts on the term's line)."""
    lines = text.rstrip("\n").split("\n")
    usage = []
    while lines and lines[0].startswith("usage: "):
        usage.append(lines.pop(0).removeprefix("usage: ").strip())
        while lines and lines[0].startswith(" "):  # the usage goes on
            usage[-1] += " " + lines.pop(0).strip()
    blocks = []
    for i, raw in enumerate(lines):
        if not raw.strip():
            blocks.append(("break",))
            continue
        indent = len(raw) - len(raw.lstrip(" "))
        body = raw.strip()
        if indent == 0:
            if blocks and blocks[-1][0] == "prose":
                blocks[-1][1].append(body)
            else:
                blocks.append(("prose", [body]))
        elif indent == 2:
            parts = re.split(r" {2,}", body, maxsplit=1)
            blocks.append(("item", parts[0], parts[1:], len(parts) > 1))
        elif blocks and blocks[-1][0] == "item":
            blocks[-1][2].append(body)
        elif blocks and blocks[-1][0] == "prose":
            blocks[-1][1].append(body)
        else:
            blocks.append(("prose", [body]))
        # Prose ending in ':' right above an item heads the items.
        if indent == 2 and len(blocks) > 1 and blocks[-2][0] == "prose" and \
                blocks[-2][1][-1].endswith(":"):
            blocks[-2] = ("group", " ".join(blocks[-2][1]))
    return usage, blocks


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


def synopsis(usage):
    out = []
    for u in usage:
        words = u.split(" ", 2)
        out += [".br"] if out else []
        out += [line("\\fB" + escape(" ".join(words[:2])) + "\\fR " +
                                              escape(" ".join(words[2:])))]
    return out


def commands(top):
    """The command names in the top-level help's "commands:" group."""
    _, blocks = parse(top)
    names = []
    for b in blocks:
        if b[0] == "item" and not b[1].startswith("softrast"):
            names.append(b[1].split()[0])
    return names


def main(argv):
    if len(argv) < 4:
        sys.stderr.write(__doc__)
        return 2
    template_path, output_path, tool = argv[1], argv[2], argv[3:]
    top = run(tool, "--help")
    version = run(tool, "--version").split()[-1]
    usage_lines, section = [], []
    for name in commands(top):
        usage, blocks = parse(run(tool, name, "--help"))
        usage_lines += usage
        section += ['.SS "softrast %s"' % name] + synopsis(usage) + roff_blocks(blocks)
    with open(template_path, encoding="utf-8") as f:
        page = f.read()
    page = page.replace("@VERSION@", version)
    # The build's date as help2man gives it: SOURCE_DATE_EPOCH's for a
    # reproducible build, else today's.
    stamp = int(os.environ.get("SOURCE_DATE_EPOCH", time.time()))
    page = page.replace("@DATE@", time.strftime("%Y-%m-%d", time.gmtime(stamp)))
    page = page.replace("@SYNOPSIS@\n", "\n".join(synopsis(usage_lines)) + "\n")
    page = page.replace("@COMMANDS@\n", "\n".join(section) + "\n")
    with open(output_path + ".tmp", "w", encoding="utf-8") as f:
        f.write(page)
    os.replace(output_path + ".tmp", output_path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
