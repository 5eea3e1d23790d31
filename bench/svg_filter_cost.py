#!/usr/bin/python3
"""svg_filter_cost.py - what an SVG drop shadow costs: CPU time per
process (user + system of the child) for a 48 x 48 icon whose square
has a drop shadow (feGaussianBlur of SourceAlpha, feOffset, feFlood,
feComposite, feMerge), and for the same icon without the filter, drawn
at each size by every softrast given and by rsvg-convert (Debian's
librsvg2-bin), the commands alternating so that all see the same load.
Prints the best of ROUNDS rounds of RUNS runs each, in ms, the ratios
to the first softrast and to rsvg-convert, and the load average before
and after.  Not a pass/fail test: the figures depend on the machine.

usage: bench/svg_filter_cost.py SOFTRAST [SOFTRAST...]
           [--sizes 48,256,1024] [--runs 8] [--rounds 2]
"""
import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile

ICON = """<svg xmlns="http://www.w3.org/2000/svg" width="48" height="48" viewBox="0 0 48 48">
  <filter id="shadow" x="-0.3" y="-0.3" width="1.6" height="1.6">
    <feGaussianBlur in="SourceAlpha" stdDeviation="1.5"/>
    <feOffset dx="1" dy="2" result="b"/>
    <feFlood flood-color="#000" flood-opacity="0.5"/>
    <feComposite in2="b" operator="in"/>
    <feMerge><feMergeNode/><feMergeNode in="SourceGraphic"/></feMerge>
  </filter>
  <rect x="8" y="6" width="30" height="32" rx="4" fill="#3daee9" FILTER/>
  <path d="M14 14 h18 v4 h-18z M14 22 h12 v4 h-12z" fill="#fff"/>
</svg>
"""


def cpu_time(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("softrast", nargs="+")
    ap.add_argument("--sizes", default="48,256,1024")
    ap.add_argument("--runs", type=int, default=8)
    ap.add_argument("--rounds", type=int, default=2)
    a = ap.parse_args()
    if not shutil.which("rsvg-convert"):
        print("svg_filter_cost.py: rsvg-convert not found (apt-get install librsvg2-bin)",
              file=sys.stderr)
        return 2
    tmp = tempfile.mkdtemp()
    files = {}
    for name, attr in (("shadow", 'filter="url(#shadow)"'), ("plain", "")):
        files[name] = os.path.join(tmp, name + ".svg")
        with open(files[name], "w") as f:
            f.write(ICON.replace("FILTER", attr))
    out = os.path.join(tmp, "out.png")
    names = ["softrast%d" % i if len(a.softrast) > 1 else "softrast"
             for i in range(len(a.softrast))] + ["rsvg"]
    print("load average %.1f %.1f %.1f" % os.getloadavg())
    for size in [int(s) for s in a.sizes.split(",")]:
        for kind, path in files.items():
            cmds = [[s, "svg", path, "--size", "%dx%d" % (size, size), "-o", out]
                    for s in a.softrast]
            cmds.append(["rsvg-convert", "-w", str(size), "-h", str(size), path, "-o", out])
            best = [float("inf")] * len(cmds)
            for _ in range(a.rounds):
                total = [0.0] * len(cmds)
                for _ in range(a.runs):
                    for i, c in enumerate(cmds):
                        total[i] += cpu_time(c)
                best = [min(b, t / a.runs) for b, t in zip(best, total)]
            cells = " ".join("%s %.1f ms" % (n, b * 1000) for n, b in zip(names, best))
            ratios = " ".join("%s/%s %.2f" % (n, names[0], b / best[0])
                              for n, b in zip(names[1:-1], best[1:-1]))
            print("%5d %-6s %s %s %s/rsvg %.2f" % (size, kind, cells, ratios, names[-2],
                                                  best[-2] / best[-1]))
    print("load average %.1f %.1f %.1f" % os.getloadavg())
    shutil.rmtree(tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
