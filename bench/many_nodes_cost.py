#!/usr/bin/python3
"""many_nodes_cost.py - what a glTF scene of many small nodes costs
`softrast render`: tools/many-nodes.py's boxes (each node its own mesh,
the materials alternating, so every node is a draw of its own), N of
them, rendered to a PNG at the default 1280x720 by every softrast given
and by f3d (`f3d --output`) when it is installed, the commands
alternating so that all see the same load.  Prints the CPU model, the
median wall time of RUNS runs each, in ms, the ratios to the first
command, and the load average before and after; with --callgrind, the
instructions of each softrast on one thread (valgrind --tool=callgrind,
the whole process).  Not a pass/fail test: the figures depend on the
machine.

usage: bench/many_nodes_cost.py SOFTRAST [SOFTRAST...]
           [--nodes 2000,10000] [--runs 5] [--callgrind]
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def cpu_model():
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        m = re.search(r"^Model name:\s*(.+)$", out, re.M)
        if m:
            return m.group(1).strip()
    except OSError:
        pass
    return "unknown"


def wall(cmd):
    start = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def instructions(cmd, tmp):
    log = os.path.join(tmp, "callgrind.log")
    subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
                    "--log-file=" + log] + cmd, check=True, stdout=subprocess.DEVNULL)
    with open(log) as f:
        m = re.search(r"Collected : (\d+)", f.read())
    return int(m.group(1)) if m else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("softrast", nargs="+")
    ap.add_argument("--nodes", default="2000,10000")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--callgrind", action="store_true")
    a = ap.parse_args()
    f3d = shutil.which("f3d")
    tmp = tempfile.mkdtemp()
    names = ["softrast%d" % i if len(a.softrast) > 1 else "softrast"
             for i in range(len(a.softrast))]
    print("cpu %s" % cpu_model())
    if not f3d:
        print("f3d not found: softrast alone (Debian's f3d package)")
    print("load average %.1f %.1f %.1f" % os.getloadavg())
    for n in [int(s) for s in a.nodes.split(",")]:
        scene = os.path.join(tmp, "nodes%d.glb" % n)
        subprocess.run([sys.executable, os.path.join(HERE, "..", "tools", "many-nodes.py"),
                        str(n), scene], check=True)
        out = os.path.join(tmp, "out.png")
        cmds = [[s, "render", scene, "-o", out] for s in a.softrast]
        labels = list(names)
        if f3d:
            cmds.append([f3d, scene, "--output", out, "--resolution", "1280,720"])
            labels.append("f3d")
        for c in cmds:   # warm the file cache and the libraries
            wall(c)
        times = [[] for _ in cmds]
        for _ in range(a.runs):
            for i, c in enumerate(cmds):
                times[i].append(wall(c))
        med = [statistics.median(t) for t in times]
        cells = " ".join("%s %.0f ms" % (l, m * 1000) for l, m in zip(labels, med))
        ratios = " ".join("%s/%s %.2f" % (l, labels[0], m / med[0])
                          for l, m in zip(labels[1:], med[1:]))
        print("%6d nodes  %s  %s" % (n, cells, ratios))
        if a.callgrind:
            counts = [instructions(c + ["--threads", "1"], tmp) for c in cmds[:len(names)]]
            print("%6d nodes  %s" % (n, " ".join("%s %.1f M instructions" % (l, c / 1e6)
                                                   for l, c in zip(names, counts))))
    print("load average %.1f %.1f %.1f" % os.getloadavg())
    shutil.rmtree(tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
