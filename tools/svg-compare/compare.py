#!/usr/bin/python3
"""Render a directory of SVGs with softrast, rsvg-convert and resvg and
report, per file and in all, the share of pixels where softrast differs
from each beyond antialiasing.

    tools/svg-compare/compare.py DIR [--softrast BUILD/softrast] [--size 48]
        [--every N] [--threshold 32] [--match 0.01] [--csv OUT.csv]
        [--no-resvg] [--quiet]

A pixel differs when any channel of the two images, composited over white,
differs by more than --threshold (out of 255): edges antialiased
differently stay under it.  A file matches a renderer when at most --match
of its pixels differ.  softrast's exit status and warnings (stderr lines)
are counted too: a crash is any status other than 0 (drawn) or 2
(refused).  One line per file (unless --quiet): the two shares ("-" where
that renderer failed or gave another size), then the warnings.  With
resvg, a last line takes it as the reference for a conformance suite:
of all the files resvg drew, how many softrast and rsvg-convert match
(a file softrast refused counts as not matching).

rsvg-convert is Debian's librsvg2-bin; resvg is the npm package
@resvg/resvg-js, installed beside this script by
`npm ci --prefix tools/svg-compare` and run by render-resvg.js in one node
process.  Every image is --size pixels wide, its height in the drawing's
proportions (as rsvg-convert gives it; softrast is asked for that size).  Neither is a build dependency: only this tool uses them.
Standard library only: the PNGs are decoded here (8-bit RGB or RGBA).
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile
import zlib


def read_png(path):
    """(width, height, bytes of RGBA8 rows) of a non-interlaced 8-bit
    RGBA or RGB PNG."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, w = 8, [], 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or interlace:
                raise ValueError("unsupported PNG form")
            ch = 4 if ctype == 6 else 3
        elif kind == b"IDAT":
            idat.append(body)
        pos += 12 + n
    raw = zlib.decompress(b"".join(idat))
    stride = w * ch
    out = bytearray(h * stride)
    prev = bytearray(stride)
    for y in range(h):
        ft = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b = prev[i]
            c = prev[i - ch] if i >= ch else 0
            if ft == 1:
                line[i] = (line[i] + a) & 255
            elif ft == 2:
                line[i] = (line[i] + b) & 255
            elif ft == 3:
                line[i] = (line[i] + ((a + b) >> 1)) & 255
            elif ft == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pr = a if pa <= pb and pa <= pc else b if pb <= pc else c
                line[i] = (line[i] + pr) & 255
        out[y * stride:(y + 1) * stride] = line
        prev = line
    if ch == 3:
        rgba = bytearray()
        for i in range(0, len(out), 3):
            rgba += out[i:i + 3] + b"\xff"
        out = rgba
    return w, h, bytes(out)


def differing_share(a, b, threshold):
    """Share of pixels differing beyond threshold, both over white."""
    n = len(a) // 4
    bad = 0
    for i in range(0, len(a), 4):
        aa, ba = a[i + 3], b[i + 3]
        for k in range(3):
            ca = (a[i + k] * aa + 255 * (255 - aa)) // 255
            cb = (b[i + k] * ba + 255 * (255 - ba)) // 255
            if abs(ca - cb) > threshold:
                bad += 1
                break
    return bad / n if n else 0.0


def png_size(path):
    """(width, height) from a PNG's header, or None."""
    try:
        with open(path, "rb") as f:
            head = f.read(24)
    except OSError:
        return None
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    return struct.unpack(">II", head[16:24])


def share_between(ours, theirs, threshold):
    """The differing share of two PNG files, or None when either is
    missing or their sizes differ."""
    try:
        wa, ha, a = read_png(ours)
        wb, hb, b = read_png(theirs)
    except (OSError, ValueError):
        return None
    return differing_share(a, b, threshold) if (wa, ha) == (wb, hb) else None


def render_resvg(jobs):
    """Render (svg, png, width) jobs with resvg in one node process; the
    set of pngs written.  resvg aborts the process on some drawings (a
    panic): that file counts as failed and the rest go to a new process."""
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "render-resvg.js")
    written = set()
    while jobs:
        text = "".join("%s\t%s\t%d\n" % job for job in jobs)
        r = subprocess.run(["node", script], input=text, capture_output=True, text=True,
                           errors="replace")
        answers = r.stdout.splitlines()
        written |= {job[1] for job, answer in zip(jobs, answers) if answer == "ok"}
        jobs = jobs[len(answers) + 1:]
    return written


def have_resvg():
    here = os.path.dirname(os.path.abspath(__file__))
    return os.path.isdir(os.path.join(here, "node_modules", "@resvg", "resvg-js"))


def fmt(share):
    return "-" if share is None else "%.4f" % share


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir")
    ap.add_argument("--softrast", default="build/softrast")
    ap.add_argument("--size", type=int, default=48)
    ap.add_argument("--every", type=int, default=1, help="take every Nth file (sorted)")
    ap.add_argument("--threshold", type=int, default=32)
    ap.add_argument("--match", type=float, default=0.01)
    ap.add_argument("--csv")
    ap.add_argument("--no-resvg", action="store_true", help="compare with rsvg-convert only")
    ap.add_argument("--quiet", action="store_true", help="the totals only")
    args = ap.parse_args()
    use_resvg = not args.no_resvg and have_resvg()
    if not args.no_resvg and not use_resvg:
        print("resvg not installed (npm ci --prefix tools/svg-compare): rsvg-convert only",
              file=sys.stderr)
    files = []
    for root, _, names in os.walk(args.dir):
        for name in names:
            p = os.path.join(root, name)
            if name.endswith(".svg") and os.path.isfile(p) and not os.path.islink(p):
                files.append(p)
    files = sorted(files)[::args.every]
    stats = {"files": 0, "crash": 0, "refused": 0, "warned": 0}
    renderers = ["rsvg-convert"] + (["resvg"] if use_resvg else [])
    matched = {r: 0 for r in renderers}
    compared = {r: 0 for r in renderers}
    rows = []
    against_resvg = {"files": 0, "softrast": 0, "rsvg-convert": 0}
    with tempfile.TemporaryDirectory() as tmp:
        drawn = []
        for k, path in enumerate(files):
            stats["files"] += 1
            ours = os.path.join(tmp, "%d.png" % k)
            # rsvg-convert first: its image (--size wide, proportions kept)
            # sets the size the others draw at
            rsvg = os.path.join(tmp, "%d.rsvg.png" % k)
            subprocess.run(["rsvg-convert", "-w", str(args.size), "-a", "-o", rsvg, path],
                           capture_output=True)
            size = png_size(rsvg) or (args.size, args.size)
            r = subprocess.run([args.softrast, "svg", path, "-o", ours, "--size",
                                "%dx%d" % size], capture_output=True, text=True,
                               errors="replace")
            warnings = len([l for l in r.stderr.splitlines() if "warning" in l])
            stats["warned"] += warnings > 0
            if r.returncode not in (0, 2):
                stats["crash"] += 1
                rows.append((path, "crash %d" % r.returncode, "", warnings, ""))
                continue
            if r.returncode == 2:
                stats["refused"] += 1
                rows.append((path, "refused", "", warnings, r.stderr.strip()))
                continue
            drawn.append((k, path, warnings))
        written = set()
        if use_resvg:
            written = render_resvg([(path, os.path.join(tmp, "%d.resvg.png" % k), args.size)
                                    for k, path in enumerate(files)])
            # resvg as the reference: every file it drew, and which of
            # softrast's and rsvg-convert's images match it
            drawn_k = {k for k, _, _ in drawn}
            for k in range(len(files)):
                ref = os.path.join(tmp, "%d.resvg.png" % k)
                if ref not in written:
                    continue
                against_resvg["files"] += 1
                for name, png in (("softrast", "%d.png" % k), ("rsvg-convert", "%d.rsvg.png" % k)):
                    if name == "softrast" and k not in drawn_k:
                        continue
                    share = share_between(os.path.join(tmp, png), ref, args.threshold)
                    against_resvg[name] += share is not None and share <= args.match
        for k, path, warnings in drawn:
            ours = os.path.join(tmp, "%d.png" % k)
            shares = []
            for name in renderers:
                theirs = os.path.join(tmp, "%d.%s.png" % (k, "rsvg" if name == "rsvg-convert"
                                                              else "resvg"))
                share = None
                if name == "rsvg-convert" or theirs in written:
                    share = share_between(ours, theirs, args.threshold)
                if share is not None:
                    compared[name] += 1
                    matched[name] += share <= args.match
                shares.append(share)
            rows.append((path, fmt(shares[0]), fmt(shares[1]) if use_resvg else "", warnings,
                         ""))
    if not args.quiet:
        print("%-8s %-8s %-3s %s" % ("rsvg", "resvg", "w", "file (share of pixels differing)"))
        for row in rows:
            print("%-8s %-8s %-3d %s%s" % (row[1], row[2] or "-", row[3], row[0],
                                           "  " + row[4] if row[4] else ""))
    if args.csv:
        with open(args.csv, "w") as f:
            f.write("file,rsvg_convert,resvg,warnings,note\n")
            for row in rows:
                f.write("%s,%s,%s,%d,%s\n" % (row[0], row[1], row[2], row[3],
                                             row[4].replace(",", ";")))
    print("files %d: crashes %d, refused %d, with warnings %d"
          % (stats["files"], stats["crash"], stats["refused"], stats["warned"]))
    for name in renderers:
        print("match %s (<= %.1f%% of pixels differing by > %d): %d of %d compared (%.1f%%)"
              % (name, 100 * args.match, args.threshold, matched[name], compared[name],
                 100.0 * matched[name] / compared[name] if compared[name] else 0))
    n = against_resvg["files"]
    if use_resvg:
        print("against resvg, all %d files it drew: softrast matches %d (%.1f%%), rsvg-convert %d "
              "(%.1f%%)" % (n, against_resvg["softrast"],
                            100.0 * against_resvg["softrast"] / n if n else 0,
                            against_resvg["rsvg-convert"],
                            100.0 * against_resvg["rsvg-convert"] / n if n else 0))
    return 1 if stats["crash"] else 0


if __name__ == "__main__":
    sys.exit(main())
