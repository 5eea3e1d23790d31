"""tools/helptext.py - softrast's --help texts read by their layout, for
the files the build writes from them (the manual page, the zsh and fish
completions), so that those cannot drift from the tool.

A help text's layout: a line at column 0 is prose (one ending in ':'
before an indented item heads a group), a line indented two spaces
starts an item (its term, then after two spaces or more its description),
and a line indented deeper continues the item or prose above it.  An
item whose term starts with '-' gives options, any other item a name (a
command, a demo, an algorithm)."""
import re
import subprocess

CHOICES = re.compile(r"^[A-Za-z0-9+.-]+(\|[A-Za-z0-9+.-]+)+$")
FILE_ARG = re.compile(r"(FILE|LIST|PATTERN|INPUT)(\.([a-z]+))?")


def run(tool, *args):
    out = subprocess.run(tool + list(args), check=True, stdout=subprocess.PIPE, text=True)
    return out.stdout


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
    for raw in lines:
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


def names(blocks):
    """(name, description) for each item that is not an option, but for
    examples of the tool's use ("softrast COMMAND --help")."""
    out = []
    for b in blocks:
        if b[0] == "item" and not b[1].startswith(("-", "softrast")):
            out.append((b[1].split()[0], " ".join(b[2])))
    return out


class Option:
    """An item's options ("-o, --output FILE", "--near Z, --far Z"): their
    names, the argument (the first word after the first name that is not
    an option; '' for a flag) and the description."""

    def __init__(self, names, arg, description):
        self.names, self.arg, self.description = names, arg, description

    def choices(self):
        """The fixed set of values: the words joined by '|' in the
        argument or description ("MODE pbr|flat|...", "on|off")."""
        out = []
        for word in (self.arg + " " + self.description).split():
            word = word.rstrip(":,;)").lstrip("(")
            if CHOICES.match(word):
                out += [w for w in word.split("|") if w not in out]
        return out

    def value(self):
        """What the value is: ('choices', [...]), ('dir',), ('file', EXT
        or ''), ('text',) for another value, or None for a flag."""
        if not self.arg:
            return None
        if self.choices():
            return ("choices", self.choices())
        if self.arg.startswith("DIR"):
            return ("dir",)
        m = FILE_ARG.search(self.arg)
        if m:
            return ("file", m.group(3) or "")
        return ("text",)


def options(blocks):
    """The Options of a help text's items, each name once (the first item
    that names it gives its argument).  An item without a description
    shares the next one's, when that one's starts below its term too
    (render's two --light)."""
    items = [b for b in blocks if b[0] == "item" and b[1].startswith("-")]
    out, seen = [], set()
    for i, (_, term, desc, _) in enumerate(items):
        if not desc and i + 1 < len(items) and not items[i + 1][3]:
            desc = items[i + 1][2]
        words = term.split()
        found = []
        for j, word in enumerate(words):
            if not re.match(r"^--?[A-Za-z0-9]", word):
                continue
            arg = next((w.rstrip(",") for w in words[j + 1:] if not w.startswith("-") and w != "|"), "")
            name = word.rstrip(",")
            if name not in seen and name not in [n for n, _ in found]:
                found.append((name, arg))
        if found:
            seen.update(n for n, _ in found)
            out.append(Option([n for n, _ in found], found[0][1], " ".join(desc)))
    return out


def read(tool):
    """The tool's help texts: the top-level one parsed, and for each
    command of its "commands:" (name, description, usage lines, blocks)."""
    top = parse(run(tool, "--help"))
    commands = []
    for name, description in names(top[1]):
        usage, blocks = parse(run(tool, name, "--help"))
        commands.append((name, description, usage, blocks))
    return top, commands
