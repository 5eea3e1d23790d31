"""Render a table of (mesh, camera) jobs as shards on a Dask cluster.

Each shard is one task: it renders its views in order and writes
``shard-NNNNNN.npz`` (every requested output stacked along a first axis, and
``job`` the views' rows in the table) and, when ``color`` is requested,
``view-NNNNNNNN.png`` for each view (its row in the table).  Files are
written atomically (a temporary file renamed into place), their bytes depend
only on the jobs, and a shard's names only on its index, so a task that runs
twice - because its worker died and the scheduler retried it - writes the
same files again: nothing is lost or duplicated.  The same graph runs on a
``distributed.LocalCluster``, on Kubernetes (dask-kubernetes) or Slurm
(dask-jobqueue), or without a cluster (``dask.compute`` with any scheduler,
or :func:`render_shard` in a loop).

    jobs = [{"mesh": "bunny.obj", "K": K, "R": R, "t": t}, ...]
    tasks = softrast.dask.shard_tasks(jobs, "out/", width=640, height=480,
                                      outputs=("depth", "triangle_id"), views_per_shard=64)
    manifests = client.compute(tasks, sync=True)     # or dask.compute(*tasks)

A job is a mapping with ``mesh`` (a model file's path, read on the worker
with ``mesh_loader``, default :func:`softrast.load_mesh`, once per process;
or a :class:`softrast.Mesh`, :class:`softrast.Scene` or anything
:func:`softrast.render` takes, sent with the task) and the camera: ``K`` and
``R``, ``t`` or ``extrinsics``, unbatched.
"""

from __future__ import annotations

import functools
import os
import tempfile
import zipfile
from typing import (TYPE_CHECKING, Any, Callable, Dict, Iterable, List, Mapping, Optional,
                    Sequence, Union)

import numpy as np
from numpy.typing import NDArray

from . import _render
from ._softrast import write_png

if TYPE_CHECKING:
    from dask.delayed import Delayed

    from .typing import OutputName, SceneLike, ShardManifest

#: A directory or file name.
_Dir = Union[str, "os.PathLike[str]"]

_CAMERA_KEYS = ("K", "R", "t", "extrinsics")


def _atomic_path(path: str) -> str:
    d, base = os.path.split(path)
    fd, tmp = tempfile.mkstemp(prefix="." + base + ".", suffix=".tmp", dir=d or ".")
    os.close(fd)
    return tmp


def _write_npz(path: str, arrays: Mapping[str, NDArray[Any]]) -> None:
    """np.savez's format with fixed timestamps (the same bytes every run),
    written to a temporary file and renamed into place."""
    tmp = _atomic_path(path)
    try:
        with zipfile.ZipFile(tmp, "w", zipfile.ZIP_STORED) as z:
            for name, array in arrays.items():
                info = zipfile.ZipInfo(name + ".npy", date_time=(1980, 1, 1, 0, 0, 0))
                with z.open(info, "w") as f:
                    np.save(f, np.ascontiguousarray(array), allow_pickle=False)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


@functools.lru_cache(maxsize=8)
def _cached_load(loader: Callable[[str], SceneLike], path: str) -> SceneLike:
    return loader(path)


def _default_loader(path: str) -> SceneLike:
    from ._scene import load_mesh
    return load_mesh(path)


def shard_name(index: int) -> str:
    """The npz file of shard ``index``."""
    return f"shard-{index:06d}.npz"


def view_name(job: int) -> str:
    """The PNG file of the view in row ``job`` of the table."""
    return f"view-{job:08d}.png"


def render_shard(jobs: Sequence[Mapping[str, Any]], first_job: int, shard_index: int,
                 out_dir: _Dir, *, width: int, height: int,
                 outputs: Sequence[OutputName] = ("depth", "triangle_id"), threads: int = 0,
                 mesh_loader: Optional[Callable[[str], SceneLike]] = None,
                 **render_kwargs: Any) -> ShardManifest:
    """Render ``jobs`` (rows ``first_job`` onwards of the table) as shard
    ``shard_index`` in ``out_dir``; returns its manifest: ``{"shard": index,
    "jobs": [rows], "files": [names]}``.  What a task of :func:`shard_tasks`
    runs; call it in a loop for a run without Dask."""
    loader = mesh_loader or _default_loader
    names = _render._outputs(outputs)
    stacked: Dict[str, List[NDArray[Any]]] = {name: [] for name in names}
    for job in jobs:
        scene = job["mesh"]
        if isinstance(scene, (str, bytes, os.PathLike)):
            scene = _cached_load(loader, os.fspath(scene))
        camera = {k: job[k] for k in _CAMERA_KEYS if k in job}
        out = _render.render(scene, width=width, height=height, outputs=names, threads=threads,
                             **camera, **render_kwargs)
        for name in names:
            stacked[name].append(out[name])
    rows = list(range(first_job, first_job + len(jobs)))
    files = []
    if "color" in names:
        for row, image in zip(rows, stacked["color"]):
            write_png(os.path.join(out_dir, view_name(row)), image)
            files.append(view_name(row))
    arrays = {"job": np.array(rows, np.int64)}
    arrays.update({name: np.stack(v) for name, v in stacked.items() if name != "color"})
    _write_npz(os.path.join(out_dir, shard_name(shard_index)), arrays)
    files.append(shard_name(shard_index))
    return {"shard": shard_index, "jobs": rows, "files": files}


def shard_tasks(jobs: Iterable[Mapping[str, Any]], out_dir: _Dir, *, width: int, height: int,
                outputs: Sequence[OutputName] = ("depth", "triangle_id"),
                views_per_shard: int = 16, threads: int = 0,
                mesh_loader: Optional[Callable[[str], SceneLike]] = None,
                **render_kwargs: Any) -> List[Delayed]:
    """One ``dask.delayed`` task per ``views_per_shard`` consecutive jobs,
    each calling :func:`render_shard`.  Compute them (``dask.compute(*tasks)``,
    ``client.compute(tasks)``) to write the shards into ``out_dir`` (made if
    missing); each task returns its shard's manifest.

    The arguments after ``out_dir`` are :func:`softrast.render`'s (checked
    here, before anything is sent to a worker), ``views_per_shard`` and
    ``mesh_loader`` (a picklable function from a path to what ``render``
    takes)."""
    from dask.delayed import delayed

    jobs = list(jobs)
    if not isinstance(views_per_shard, int) or views_per_shard < 1:
        raise ValueError(f"views_per_shard: must be a positive int, got {views_per_shard!r}")
    _render._outputs(outputs)
    for i, job in enumerate(jobs):
        if not hasattr(job, "keys") or "mesh" not in job or "K" not in job:
            raise TypeError(f"jobs[{i}]: expected a mapping with 'mesh', 'K' and 'R', 't' "
                            "or 'extrinsics'")
        _, _, batched = _render._cameras(job["K"], job.get("R"), job.get("t"),
                                         job.get("extrinsics"))
        if batched:
            raise ValueError(f"jobs[{i}]: one camera a job, not a batch")
    os.makedirs(out_dir, exist_ok=True)
    task = delayed(render_shard, pure=True)
    return [task(jobs[first:first + views_per_shard], first, index, out_dir, width=width,
                 height=height, outputs=outputs, threads=threads, mesh_loader=mesh_loader,
                 **render_kwargs)
            for index, first in enumerate(range(0, len(jobs), views_per_shard))]
