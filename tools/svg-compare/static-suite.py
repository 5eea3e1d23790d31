#!/usr/bin/python3
"""Copy the static part of an SVG conformance suite for compare.py: the
tests that are not about text, with their text elements removed (so that
no renderer is judged on fonts), and the directories of pictures they
read.

    tools/svg-compare/static-suite.py SRC DST [--only PREFIX]

SRC is a directory of W3C SVG 1.1 test files named CHAPTER-...-NN-X.svg,
such as the subset Debian's librsvg2-tests installs in
/usr/libexec/installed-tests/RSVG/fixtures/reftests/svg1.1.  Files whose
names start with text- or ignore- (tests librsvg marks as not checked)
are left out; in the others every text, tref and textPath element is cut
out.  --only keeps the files whose names start with PREFIX (filters-).  The suite's reference PNGs are not
copied: compare.py renders its own references.  Standard library only.
"""
import os
import re
import shutil
import sys

SKIPPED = ("text-", "ignore-")
TEXT = re.compile(r"<(text|tref|textPath)\b[^>]*?/>|<(text|tref|textPath)\b.*?</\2\s*>", re.S)


def main():
    args = sys.argv[1:]
    only = ""
    if len(args) == 4 and args[2] == "--only":
        only = args[3]
        args = args[:2]
    if len(args) != 2:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    src, dst = args
    os.makedirs(dst, exist_ok=True)
    kept = 0
    for name in sorted(os.listdir(src)):
        path = os.path.join(src, name)
        if os.path.isdir(path):
            # pictures and style sheets; its SVGs are resources, not tests
            shutil.copytree(path, os.path.join(dst, name), dirs_exist_ok=True,
                            ignore=shutil.ignore_patterns("*.svg"))
        elif name.endswith(".svg") and not name.startswith(SKIPPED) and name.startswith(only):
            with open(path, encoding="utf-8") as f:
                text = TEXT.sub("", f.read())
            with open(os.path.join(dst, name), "w", encoding="utf-8") as f:
                f.write(text)
            kept += 1
    print("%d static tests in %s" % (kept, dst))
    return 0


if __name__ == "__main__":
    sys.exit(main())
