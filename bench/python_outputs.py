#!/usr/bin/python3
"""What render()'s dataset outputs cost: views per second of depth +
triangle_id against depth + triangle_id + position + uv (and against all
four dataset outputs with material_id and flow) on the same cameras.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_outputs.py [--views N] [--threads T]

The mesh is python_views.py's closed bumpy sphere of 100,352 triangles,
with texture coordinates (its longitude and latitude), drawn with
cull="back" at 640x480 from --views cameras around it.  The sets are
timed in turns, --rounds times, and each one's best round is reported, so
that a load that comes and goes on a shared machine touches them alike;
ratio is each set's views per second over the first's.  A report, not a
test.
"""

import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from python_views import bumpy_sphere, cameras  # noqa: E402

import softrast  # noqa: E402

SETS = [("depth", "triangle_id"),
        ("depth", "triangle_id", "barycentric", "normal"),
        ("depth", "triangle_id", "position", "uv"),
        ("depth", "triangle_id", "position", "uv", "material_id", "flow")]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--views", type=int, default=24)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--size", default="640x480")
    args = ap.parse_args()
    width, height = (int(s) for s in args.size.split("x"))
    v, f = bumpy_sphere()
    lon_lat = np.stack([np.arctan2(v[:, 2], v[:, 0]) / (2 * np.pi) + 0.5,
                        np.arccos(np.clip(v[:, 1] / np.linalg.norm(v, axis=1), -1, 1)) / np.pi],
                       -1).astype(np.float32)
    mesh = softrast.Mesh(v, f, uvs=lon_lat)
    lo, hi = v.min(0), v.max(0)
    cams = cameras(args.views, (lo + hi) / 2, 1.6 * float(np.linalg.norm(hi - lo)), width, height)
    K = np.stack([c[0] for c in cams])
    R = np.stack([c[1] for c in cams])
    t = np.stack([c[2] for c in cams])
    print(f"mesh: {len(f)} triangles; {args.views} views of {width}x{height} (one batch); "
          f"{args.threads} threads; cull=back; load average {os.getloadavg()[0]:.1f}")
    best = [float("inf")] * len(SETS)
    for _ in range(args.rounds):
        for i, names in enumerate(SETS):
            t0 = time.perf_counter()
            softrast.render(mesh, K=K, R=R, t=t, width=width, height=height, outputs=names,
                            threads=args.threads, cull="back")
            best[i] = min(best[i], time.perf_counter() - t0)
    print(f"{'outputs':<58} {'views/s':>8} {'ratio':>6}")
    for names, seconds in zip(SETS, best):
        rate = args.views / seconds
        print(f"{' + '.join(names):<58} {rate:8.1f} {rate / (args.views / best[0]):6.2f}")
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
