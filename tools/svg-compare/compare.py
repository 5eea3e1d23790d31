#!/usr/bin/python3
"""Render a directory of SVGs with softrast and rsvg-convert and report,
per file and in all, the share of pixels that differ beyond antialiasing.

    tools/svg-compare/compare.py DIR [--softrast BUILD/softrast] [--size 48]
        [--every N] [--threshold 32] [--match 0.01] [--csv OUT.csv]

A pixel differs when any channel of the two images, composited over white,
differs by more than --threshold (out of 255): edges antialiased
differently stay under it.  A file matches when at most --match of its
pixels differ.  softrast's exit status and warnings (stderr lines) are
counted too: a crash is any status other than 0 (drawn) or 2 (refused).
Standard library only: the PNGs are decoded here (8-bit RGBA, the form
both programs write).  rsvg-convert is Debian's librsvg2-bin (not a build
dependency: only this tool uses it).
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


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir")
    ap.add_argument("--softrast", default="build/softrast")
    ap.add_argument("--size", type=int, default=48)
    ap.add_argument("--every", type=int, default=1, help="take every Nth file (sorted)")
    ap.add_argument("--threshold", type=int, default=32)
    ap.add_argument("--match", type=float, default=0.01)
    ap.add_argument("--csv")
    args = ap.parse_args()
    files = []
    for root, _, names in os.walk(args.dir):
        for name in names:
            p = os.path.join(root, name)
            if name.endswith(".svg") and os.path.isfile(p) and not os.path.islink(p):
                files.append(p)
    files = sorted(files)[::args.every]
    size = "%dx%d" % (args.size, args.size)
    stats = {"files": 0, "match": 0, "crash": 0, "refused": 0, "warned": 0, "rsvg_failed": 0}
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        ours, theirs = os.path.join(tmp, "a.png"), os.path.join(tmp, "b.png")
        for path in files:
            stats["files"] += 1
            r = subprocess.run([args.softrast, "svg", path, "-o", ours, "--size", size],
                               capture_output=True, text=True, errors="replace")
            warnings = len([l for l in r.stderr.splitlines() if "warning" in l])
            stats["warned"] += warnings > 0
            if r.returncode not in (0, 2):
                stats["crash"] += 1
                rows.append((path, "crash %d" % r.returncode, warnings, ""))
                continue
            if r.returncode == 2:
                stats["refused"] += 1
                rows.append((path, "refused", warnings, r.stderr.strip()))
                continue
            q = subprocess.run(["rsvg-convert", "-w", str(args.size), "-h", str(args.size),
                                "-o", theirs, path], capture_output=True)
            if q.returncode != 0:
                stats["rsvg_failed"] += 1
                continue
            wa, ha, a = read_png(ours)
            wb, hb, b = read_png(theirs)
            share = differing_share(a, b, args.threshold) if (wa, ha) == (wb, hb) else 1.0
            ok = share <= args.match
            stats["match"] += ok
            rows.append((path, "%.4f" % share, warnings, "match" if ok else ""))
    if args.csv:
        with open(args.csv, "w") as f:
            f.write("file,differing,warnings,note\n")
            for row in rows:
                f.write("%s,%s,%d,%s\n" % (row[0], row[1], row[2], row[3].replace(",", ";")))
    compared = stats["files"] - stats["crash"] - stats["refused"] - stats["rsvg_failed"]
    print("files %d: crashes %d, refused %d, with warnings %d, rsvg-convert failed %d"
          % (stats["files"], stats["crash"], stats["refused"], stats["warned"],
             stats["rsvg_failed"]))
    print("match rsvg-convert (<= %.1f%% of pixels differing by > %d): %d of %d (%.1f%%)"
          % (100 * args.match, args.threshold, stats["match"], compared,
             100.0 * stats["match"] / compared if compared else 0))
    return 1 if stats["crash"] else 0


if __name__ == "__main__":
    sys.exit(main())
