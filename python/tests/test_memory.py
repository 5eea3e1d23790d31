"""Calls repeated many times keep memory flat: no reference the extension
takes is left behind, on success or on error."""

import gc
import os
import tracemalloc

import numpy as np
import pytest
import softrast
from conftest import MODELS

SUZANNE = os.path.join(MODELS, "suzanne.obj")
V = np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 3]], np.float64)
F = np.array([[0, 1, 2]], np.int64)
K = np.array([[40.0, 0, 15.5], [0, 40.0, 11.5], [0, 0, 1]])


def expect_error(call, error):
    def run():
        with pytest.raises(error):
            call()
    return run


CALLS = {
    "load_mesh": lambda: softrast.load_mesh(SUZANNE),
    "load": lambda: softrast.load(SUZANNE),
    "read_image": lambda: softrast.read_image(os.path.join(MODELS, "spot_texture.png")),
    "missing file": expect_error(lambda: softrast.load_mesh(SUZANNE + ".missing"), FileNotFoundError),
    "render": lambda: softrast.render(softrast.Mesh(V, F), K=K, R=np.eye(3), t=np.zeros(3),
                                      width=32, height=24, outputs=softrast.OUTPUTS, threads=1),
    "bad render": expect_error(lambda: softrast.render(softrast.Mesh(V, F), K=-K, R=np.eye(3),
                                                       t=np.zeros(3), width=32, height=24), ValueError),
}


def traced_here(snapshot):
    """Bytes held by allocations made under this file's frames: the calls'
    own, not those of other threads of the run (Dask's, the pool's)."""
    mine = snapshot.filter_traces([tracemalloc.Filter(True, __file__, all_frames=True)])
    return sum(stat.size for stat in mine.statistics("filename"))


def grown_over(call, calls):
    tracemalloc.start(64)
    try:
        before = traced_here(tracemalloc.take_snapshot())
        for _ in range(calls):
            call()
        gc.collect()
        return traced_here(tracemalloc.take_snapshot()) - before
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("name", sorted(CALLS))
def test_repeated_calls_keep_memory_flat(name):
    call = CALLS[name]
    for _ in range(20):      # caches fill, warnings registries settle
        call()
    gc.collect()
    # A leak keeps its bytes in every round; what the interpreter caches now
    # and then while other tests' threads run shows in one round, not all.
    grown = min(grown_over(call, 500) for _ in range(3))
    # An object kept a call is 32 bytes or more.
    assert grown < 16 * 500, f"{name}: {grown} bytes kept after 500 calls, in each of 3 rounds"


def test_a_kept_object_is_seen():
    kept = []
    assert grown_over(lambda: kept.append(object()), 500) >= 16 * 500
