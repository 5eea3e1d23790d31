#!/usr/bin/python3
"""Views per second of the softrast Python package against Open3D's
RaycastingScene (Embree ray casting on the CPU), computing the same depth
image from the same K, R, t in the same run, and how far the two agree.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_views.py [--views N] [--threads T]

softrast renders depth + triangle_id + normal; Open3D casts one ray per
pixel centre (t_hit, primitive_ids, primitive_normals).  The mesh is a
closed bumpy sphere of 100,352 counter-clockwise triangles (or --model
FILE), seen from --views cameras around it, so softrast renders it with
cull="back" (--cull none draws the back faces too, as for an open mesh).
Agreement: the fraction of pixels hit by both whose depths differ by at
most 1e-4 relative, over the pixels away from edges (whose 3x3
neighbourhood is covered in both images).  ratio is softrast's
views per second over Open3D's; CPU ratio is Open3D's CPU time (process
time, every thread) over softrast's for the same views, which other
processes on a loaded machine disturb far less.  A report, not a test.

Debian 12's python3-open3d 0.16.1 casts every ray with Embree's ray mask
0, and Debian's libembree3 is built with ray masks on, so a ray hits a
geometry only when (ray mask & geometry mask) != 0: nothing is ever hit.
When a probe ray misses a triangle head-on, this script compiles a small
library that sets the mask of each ray to all ones before Embree's
rtcIntersect1M and rtcOccluded1M (one store a ray) and runs itself again
with it in LD_PRELOAD (needs cc); --no-unmask reports the misses instead.
"""

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import softrast


def bumpy_sphere(rows=224, cols=224):
    """A UV sphere of rows x cols quads (2 triangles each) with bumps."""
    theta = np.linspace(0, np.pi, rows + 1)
    phi = np.linspace(0, 2 * np.pi, cols + 1)[:-1]
    th, ph = np.meshgrid(theta, phi, indexing="ij")
    r = 1 + 0.08 * np.sin(7 * th) * np.cos(9 * ph)
    verts = np.stack([r * np.sin(th) * np.cos(ph), r * np.cos(th), r * np.sin(th) * np.sin(ph)], -1)
    idx = np.arange((rows + 1) * cols).reshape(rows + 1, cols)
    a, b = idx[:-1], np.roll(idx[:-1], -1, axis=1)
    c, d = idx[1:], np.roll(idx[1:], -1, axis=1)
    faces = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3),
                            np.stack([b, d, c], -1).reshape(-1, 3)])
    return verts.reshape(-1, 3).astype(np.float32), faces.astype(np.int32)


def cameras(count, centre, radius, width, height):
    out = []
    for i in range(count):
        angle = 2 * math.pi * i / count
        eye = centre + radius * np.array([math.sin(angle), 0.35, math.cos(angle)])
        out.append(softrast.look_at(eye=eye, target=centre, width=width, height=height,
                                    fov_y=0.7))
    return out


UNMASK_C = r"""
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stddef.h>
#include <stdint.h>

/* Embree 3's stream calls; the mask is the 10th 32-bit word of RTCRay. */
typedef void (*stream_fn)(void *, void *, void *, unsigned, size_t);
static stream_fn intersect, occluded;

/* Python opens Open3D (and so Embree) with RTLD_LOCAL: RTLD_NEXT cannot
 * see it, the library's own handle can. */
__attribute__((constructor)) static void find_embree(void)
{
    void *lib = dlopen("libembree3.so.3", RTLD_NOW | RTLD_LOCAL);
    if (lib) {
        intersect = (stream_fn)dlsym(lib, "rtcIntersect1M");
        occluded = (stream_fn)dlsym(lib, "rtcOccluded1M");
    }
}

static void unmask(void *rays, unsigned m, size_t stride)
{
    for (unsigned i = 0; i < m; i++) {
        *(uint32_t *)((char *)rays + i * stride + 36) = 0xffffffffu;
    }
}

void rtcIntersect1M(void *s, void *c, void *r, unsigned m, size_t stride)
{
    unmask(r, m, stride);
    intersect(s, c, r, m, stride);
}

void rtcOccluded1M(void *s, void *c, void *r, unsigned m, size_t stride)
{
    unmask(r, m, stride);
    occluded(s, c, r, m, stride);
}
"""


def open3d_hits(o3d):
    """Whether Open3D's RaycastingScene hits a triangle straight ahead."""
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(np.array([[-1, -1, 5], [1, -1, 5], [0, 1, 5]], np.float32)),
                        o3d.core.Tensor(np.array([[0, 1, 2]], np.uint32)))
    rays = o3d.core.Tensor(np.array([[0, 0, 0, 0, 0, 1]], np.float32))
    return bool(np.isfinite(scene.cast_rays(rays)["t_hit"].numpy()[0]))


def rerun_unmasked():
    """Compile UNMASK_C and exec this script again with it preloaded;
    returns only when that cannot be done."""
    out = os.path.join(tempfile.mkdtemp(prefix="python_views-"), "embree_unmask.so")
    src = out[:-3] + ".c"
    with open(src, "w") as f:
        f.write(UNMASK_C)
    try:
        subprocess.run(["cc", "-shared", "-fPIC", "-O2", "-o", out, src, "-ldl"], check=True)
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"python_views: cannot compile the ray mask fix: {e}", file=sys.stderr)
        return
    env = dict(os.environ, PYTHON_VIEWS_UNMASKED="1")
    env["LD_PRELOAD"] = ":".join(filter(None, [out, env.get("LD_PRELOAD")]))
    sys.stdout.flush()
    os.execve(sys.executable, [sys.executable] + sys.argv, env)


def agreement(d_sr, d_o3d):
    hit = np.isfinite(d_sr) & np.isfinite(d_o3d)
    pad = np.pad(hit, 1)
    inner = np.ones_like(hit)
    for dy in range(3):
        for dx in range(3):
            inner &= pad[dy:dy + hit.shape[0], dx:dx + hit.shape[1]]
    rel = np.abs(d_sr[inner].astype(np.float64) - d_o3d[inner]) / d_o3d[inner]
    return (rel <= 1e-4).mean() if inner.any() else float("nan"), int(inner.sum())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--views", type=int, default=24)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--model", help="a model file instead of the bumpy sphere")
    ap.add_argument("--cull", choices=("back", "none"), default="back",
                    help="softrast's cull (default back: the mesh is closed and seen from "
                         "outside)")
    ap.add_argument("--no-unmask", action="store_true",
                    help="do not preload the ray mask fix when Open3D hits nothing")
    args = ap.parse_args()
    try:
        import open3d as o3d
    except ImportError:
        o3d = None
        print("python_views: Open3D not found (Debian: python3-open3d); softrast alone",
              file=sys.stderr)
    if o3d is not None and not open3d_hits(o3d):
        if not args.no_unmask and not os.environ.get("PYTHON_VIEWS_UNMASKED"):
            print("python_views: Open3D misses a triangle head-on (Embree ray mask 0); "
                  "running again with every ray's mask set", file=sys.stderr)
            rerun_unmasked()
        print("python_views: Open3D's cast_rays hits nothing: its depth cannot be compared",
              file=sys.stderr)
    elif o3d is not None and os.environ.get("PYTHON_VIEWS_UNMASKED"):
        print("Open3D: with every Embree ray's mask set by LD_PRELOAD")
    if args.model:
        mesh = softrast.load_mesh(args.model)
    else:
        v, f = bumpy_sphere()
        mesh = softrast.Mesh(v, f)
    verts = np.asarray(mesh.vertices, np.float32)
    faces = np.asarray(mesh.faces, np.uint32)
    lo, hi = verts.min(0), verts.max(0)
    centre, size = (lo + hi) / 2, float(np.linalg.norm(hi - lo))
    print(f"mesh: {len(faces)} triangles; {args.views} views; {args.threads} threads; "
          f"cull={args.cull}; load average {os.getloadavg()[0]:.1f}")
    if o3d is not None:
        scene = o3d.t.geometry.RaycastingScene()
        scene.add_triangles(o3d.core.Tensor(verts), o3d.core.Tensor(faces))
        # Embree builds its BVH at the first cast, once for every view: not timed.
        scene.cast_rays(o3d.core.Tensor(np.array([[0, 0, 0, 0, 0, 1]], np.float32)))
    print(f"{'size':>9} {'softrast views/s':>17} {'Open3D views/s':>15} {'ratio':>6} "
          f"{'CPU ratio':>10} {'depth agreement':>16} {'pixels':>8} {'same triangle':>14}")
    for width, height in [(256, 256), (640, 480)]:
        cams = cameras(args.views, centre, 1.6 * size, width, height)
        outs = []
        t0, c0 = time.perf_counter(), time.process_time()
        for K, R, t in cams:
            outs.append(softrast.render(mesh, K=K, R=R, t=t, width=width, height=height,
                                        outputs=("depth", "triangle_id", "normal"),
                                        threads=args.threads, cull=args.cull))
        sr_rate = len(cams) / (time.perf_counter() - t0)
        sr_cpu = time.process_time() - c0
        line = f"{width}x{height:<5} {sr_rate:17.1f}"
        if o3d is None:
            print(line)
            continue
        hits = []
        t0, c0 = time.perf_counter(), time.process_time()
        for K, R, t in cams:
            E = np.eye(4)
            E[:3, :3], E[:3, 3] = R, t
            # Open3D's ray for pixel (u, v) passes through u + 1/2, v + 1/2
            # of its K; OpenCV's (and softrast's) pixel centres are at u, v.
            K_o3d = K.copy()
            K_o3d[:2, 2] += 0.5
            rays = o3d.t.geometry.RaycastingScene.create_rays_pinhole(
                o3d.core.Tensor(K_o3d), o3d.core.Tensor(E), width, height)
            hits.append((rays, scene.cast_rays(rays, nthreads=args.threads)))
        o3d_rate = len(cams) / (time.perf_counter() - t0)
        o3d_cpu = time.process_time() - c0
        agree, pixels, same = [], 0, []
        for out, (K, R, t), (rays, hit) in zip(outs, cams, hits):
            # t_hit is in units of the ray direction's length: times the
            # direction's camera z it is the depth along the optical axis.
            d_o3d = hit["t_hit"].numpy() * (rays.numpy()[..., 3:] @ R[2].astype(np.float32))
            a, n = agreement(out["depth"], d_o3d)
            agree.append(a * n)
            pixels += n
            prim = hit["primitive_ids"].numpy().astype(np.int64)
            prim[~np.isfinite(d_o3d)] = -1
            same.append((prim == out["triangle_id"]).mean())
        line = f"{line} {o3d_rate:15.1f} {sr_rate / o3d_rate:6.2f} {o3d_cpu / sr_cpu:10.2f}"
        if pixels == 0:
            print(f"{line} {'n/a':>16} {0:8d} {'n/a':>14}")
            continue
        print(f"{line} {sum(agree) / pixels:16.5f} {pixels:8d} {np.mean(same):14.5f}")


if __name__ == "__main__":
    main()
