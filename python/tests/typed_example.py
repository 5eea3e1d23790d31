"""A small program written against softrast's documented API with full
annotations: test_types.py holds it to `mypy --strict` (it must pass) and
runs it.  Not collected by pytest (not test_*.py).

    python3 typed_example.py MODEL OUT_DIR
"""

import sys
from typing import Dict, List

from dask.base import compute
import numpy as np
from numpy.typing import NDArray

import softrast
import softrast.dask
from softrast.typing import ShardManifest


def quad() -> softrast.Mesh:
    """A unit square in the z = 0 plane, two counter-clockwise faces."""
    vertices = np.array([[-0.5, -0.5, 0.0], [0.5, -0.5, 0.0], [0.5, 0.5, 0.0], [-0.5, 0.5, 0.0]],
                        np.float32)
    faces = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    return softrast.Mesh(vertices, faces)


def depth_of_quad() -> NDArray[np.float32]:
    """The quad seen head on from 2 units away, its depth image."""
    K, R, t = softrast.look_at(eye=(0.0, 0.0, 2.0), target=(0.0, 0.0, 0.0), fov_y=0.8,
                               width=64, height=48)
    out = softrast.render(quad(), K=K, R=R, t=t, width=64, height=48,
                          outputs=("depth", "triangle_id", "mask"))
    ids: NDArray[np.int32] = out["triangle_id"]
    assert set(np.unique(ids).tolist()) <= {-1, 0, 1}
    return out["depth"]


def turntable(model: str) -> NDArray[np.uint8]:
    """A loaded model from 4 orbiting cameras and from softrast render's
    default camera; the orbit's color images, (4, H, W, 3)."""
    scene = softrast.load(model)
    K, R, t = softrast.orbit(scene, 4, width=64, height=48)
    batch = softrast.render(scene, K=K, R=R, t=t, width=64, height=48,
                            outputs=("color", "normal"), normal_frame="world",
                            shading="unlit", cull="back", antialias="msaa4")
    camera = softrast.fit_camera(scene, width=64, height=48, projection="orthographic")
    single = softrast.render(scene, camera=camera, width=64, height=48, outputs=("depth",))
    assert single["depth"].shape == (48, 64)
    return batch["color"]


def shards(model: str, out_dir: str) -> List[ShardManifest]:
    """The Dask recipe, computed in this process: two views a shard."""
    K, R, t = softrast.orbit(softrast.load_mesh(model), 3, width=32, height=24)
    jobs = [{"mesh": model, "K": k, "R": r, "t": v} for k, r, v in zip(K, R, t)]
    tasks = softrast.dask.shard_tasks(jobs, out_dir, width=32, height=24,
                                      outputs=("depth", "instance_id"), views_per_shard=2)
    # (Dask 2022.12 leaves compute unannotated: its result is Any.)
    done = compute(*tasks, scheduler="synchronous")  # type: ignore[no-untyped-call]
    manifests: List[ShardManifest] = list(done)
    return manifests


def main(model: str, out_dir: str) -> Dict[str, object]:
    depth = depth_of_quad()
    colors = turntable(model)
    manifests = shards(model, out_dir)
    return {"depth_min": float(depth.min()), "views": len(colors),
            "files": sorted(f for m in manifests for f in m["files"])}


if __name__ == "__main__":
    print(main(sys.argv[1], sys.argv[2]))
