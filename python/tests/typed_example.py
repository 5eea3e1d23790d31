"""A small program written against softrast's documented API with full
annotations: test_types.py holds it to `mypy --strict` (it must pass) and
runs it.  Not collected by pytest (not test_*.py).

    python3 typed_example.py MODEL OUT_DIR
"""

import sys
from typing import Dict, List, Tuple

from dask.base import compute
import numpy as np
from numpy.typing import NDArray

import softrast
import softrast.dask
from softrast.typing import Color, ShardManifest


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


def badge() -> NDArray[np.uint8]:
    """A 2D drawing: a gradient disc with an outline, a patterned square
    drawn into the caller's array."""
    image = np.zeros((48, 64, 4), np.uint8)
    canvas = softrast.Canvas.from_array(image)
    canvas.clear("white")
    disc = softrast.Path().move_to(12, 24).arc_to(12, 12, 0, True, True, 36, 24).close()
    disc.arc_to(12, 12, 0, True, True, 12, 24)
    stops: List[Tuple[float, Color]] = [(0.0, "gold"), (1.0, (0.8, 0.2, 0.0))]
    canvas.fill(disc, softrast.RadialGradient((24, 24), 12, stops, focal=(20, 20)))
    canvas.stroke(disc, softrast.LinearGradient((12, 0), (36, 0), stops, spread="reflect"),
                  width=2.5, join="round")
    checker = np.zeros((2, 2, 4), np.uint8)
    checker[0, 0] = checker[1, 1] = (0, 0, 0, 255)
    square: List[List[float]] = [[40, 8], [60, 8], [60, 28], [40, 28]]
    canvas.fill(square, softrast.Pattern(checker, transform=[[4, 0, 0], [0, 4, 0]]),
                rule="evenodd", opacity=0.5)
    with canvas.save():  # a clipped, turned and scaled bar
        canvas.clip(square)
        canvas.translate(50, 18)
        canvas.rotate(0.5)
        canvas.scale(2.0, 0.5)
        canvas.fill([[-10, -4], [10, -4], [10, 4], [-10, 4]], "navy")
        matrix: Tuple[float, float, float, float, float, float] = canvas.get_transform()
    canvas.set_transform(*matrix)
    canvas.reset_transform()
    canvas.reset_clip()
    assert canvas.image is image
    return image


def main(model: str, out_dir: str) -> Dict[str, object]:
    drawn = badge()
    depth = depth_of_quad()
    colors = turntable(model)
    manifests = shards(model, out_dir)
    return {"depth_min": float(depth.min()), "views": len(colors),
            "badge_pixels": int(np.count_nonzero(drawn[..., 0] != 255)),
            "files": sorted(f for m in manifests for f in m["files"])}


if __name__ == "__main__":
    print(main(sys.argv[1], sys.argv[2]))
