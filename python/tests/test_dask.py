"""softrast.dask on a LocalCluster of 2 worker processes: the shards hold
exactly what a single-process run writes, and a worker killed mid-run is
retried without losing or duplicating a shard."""

import os
import sys

import numpy as np
import pytest
import softrast

distributed = pytest.importorskip("distributed", reason="needs python3-distributed")
cloudpickle = pytest.importorskip("cloudpickle")
import softrast.dask as srdask  # noqa: E402

# The workers cannot import this file: its functions travel by value.
cloudpickle.register_pickle_by_value(sys.modules[__name__])

W, H = 48, 32


def make_jobs(model_path, count=10):
    jobs = []
    for i in range(count):
        angle = 2 * np.pi * i / count
        eye = (3 * np.sin(angle), 0.5, 3 * np.cos(angle))
        K, R, t = softrast.look_at(eye=eye, target=(0, 0, 0), width=W, height=H, fov_y=0.9)
        jobs.append({"mesh": model_path, "K": K, "R": R, "t": t})
    return jobs


@pytest.fixture(scope="module")
def model(tmp_path_factory):
    path = tmp_path_factory.mktemp("model") / "box.obj"
    corners = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    quads = [(1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)]
    path.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in corners) +
                    "".join("f " + " ".join(map(str, q)) + "\n" for q in quads))
    return str(path)


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


OUTPUTS = ("depth", "triangle_id", "normal", "color")


def single_process(jobs, out_dir):
    os.makedirs(out_dir)
    return [srdask.render_shard(jobs[i:i + 3], i, n, str(out_dir), width=W, height=H,
                                outputs=OUTPUTS, threads=1)
            for n, i in enumerate(range(0, len(jobs), 3))]


def files(directory):
    return {name: open(os.path.join(directory, name), "rb").read()
            for name in sorted(os.listdir(directory))}


def test_cluster_shards_equal_a_single_process_run(tmp_path, model, client):
    jobs = make_jobs(model)
    want = single_process(jobs, tmp_path / "single")
    tasks = srdask.shard_tasks(jobs, str(tmp_path / "cluster"), width=W, height=H,
                               outputs=OUTPUTS, views_per_shard=3, threads=1)
    got = client.compute(tasks, sync=True)
    assert got == want
    assert files(tmp_path / "cluster") == files(tmp_path / "single")
    shard = np.load(tmp_path / "cluster" / srdask.shard_name(1))
    assert list(shard["job"]) == [3, 4, 5]
    assert shard["depth"].shape == (3, H, W) and shard["triangle_id"].dtype == np.int32
    one = softrast.render(softrast.load_mesh(model), width=W, height=H, outputs=("depth",),
                          **{k: jobs[4][k] for k in ("K", "R", "t")})
    assert np.array_equal(shard["depth"][1], one["depth"])


def dying_loader(path):
    """Kills its worker process the first time any worker calls it."""
    try:
        fd = os.open(path + ".killed", os.O_CREAT | os.O_EXCL | os.O_WRONLY)
    except FileExistsError:
        return softrast.load_mesh(path)
    os.close(fd)
    os._exit(1)


def test_killed_worker_is_retried(tmp_path, model, client):
    killed_model = str(tmp_path / "box.obj")
    with open(model) as src, open(killed_model, "w") as dst:
        dst.write(src.read())
    jobs = make_jobs(killed_model)
    want = single_process(jobs, tmp_path / "single")
    tasks = srdask.shard_tasks(jobs, str(tmp_path / "cluster"), width=W, height=H,
                               outputs=OUTPUTS, views_per_shard=3, threads=1,
                               mesh_loader=dying_loader)
    got = client.compute(tasks, sync=True)
    assert os.path.exists(killed_model + ".killed"), "a worker was killed"
    assert got == want
    assert files(tmp_path / "cluster") == files(tmp_path / "single")


def test_bad_jobs(tmp_path, model):
    with pytest.raises(TypeError, match=r"jobs\[0\]"):
        srdask.shard_tasks([{"K": np.eye(3)}], str(tmp_path), width=W, height=H)
    jobs = make_jobs(model, 2)
    jobs[1]["R"] = np.full((3, 3), np.nan)
    with pytest.raises(ValueError, match="R"):
        srdask.shard_tasks(jobs, str(tmp_path), width=W, height=H)
    with pytest.raises(ValueError, match="views_per_shard"):
        srdask.shard_tasks(jobs[:1], str(tmp_path), width=W, height=H, views_per_shard=0)
