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
TEXTURE = os.path.join(MODELS, "spot_texture.png")
V = np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 3]], np.float64)
F = np.array([[0, 1, 2]], np.int64)
K = np.array([[40.0, 0, 15.5], [0, 40.0, 11.5], [0, 0, 1]])


def expect_error(call, error):
    def run():
        with pytest.raises(error):
            call()
    return run


# The calls that read the shared models, skipped in a clone without them.
READS = {"load_mesh": SUZANNE, "load": SUZANNE, "read_image": TEXTURE}

CALLS = {
    "load_mesh": lambda: softrast.load_mesh(SUZANNE),
    "load": lambda: softrast.load(SUZANNE),
    "read_image": lambda: softrast.read_image(TEXTURE),
    "missing file": expect_error(lambda: softrast.load_mesh(SUZANNE + ".missing"), FileNotFoundError),
    "render": lambda: softrast.render(softrast.Mesh(V, F), K=K, R=np.eye(3), t=np.zeros(3),
                                      width=32, height=24, outputs=softrast.OUTPUTS, threads=1),
    "bad render": expect_error(lambda: softrast.render(softrast.Mesh(V, F), K=-K, R=np.eye(3),
                                                       t=np.zeros(3), width=32, height=24), ValueError),
}


def kept_by_one_site(before, after):
    """The most blocks one allocation site (a traceback under this file's
    frames: the calls' own, not other threads') holds after that it did not
    before.  A leak keeps a block per call at the same site, however small
    or large it is; the interpreter's and numpy's bounded caches, and the
    frames another thread's sampler holds (Dask's profiler, descheduled more
    often on a loaded machine), spread a few dozen blocks over many sites,
    in every round, while their bytes pass what a byte count allows."""
    mine = [tracemalloc.Filter(True, __file__, all_frames=True)]
    diff = after.filter_traces(mine).compare_to(before.filter_traces(mine), "traceback")
    return max([stat.count_diff for stat in diff], default=0)


def kept_over(call, calls):
    tracemalloc.start(64)
    try:
        before = tracemalloc.take_snapshot()
        for _ in range(calls):
            call()
        gc.collect()
        return kept_by_one_site(before, tracemalloc.take_snapshot())
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("name", sorted(CALLS))
def test_repeated_calls_keep_memory_flat(name):
    if name in READS and not os.path.exists(READS[name]):
        pytest.skip(f"{READS[name]} is missing")
    call = CALLS[name]
    for _ in range(20):      # caches fill, warnings registries settle
        call()
    gc.collect()
    # What the interpreter caches now and then shows in one round, not all.
    kept = min(kept_over(call, 500) for _ in range(3))
    assert kept < 500 // 4, f"{name}: one site kept {kept} blocks after 500 calls, in each of 3 rounds"


def test_a_kept_object_is_seen():
    kept = []
    assert kept_over(lambda: kept.append(object()), 500) >= 500


def test_an_object_kept_every_other_call_is_seen():
    kept, calls = [], [0]

    def every_other():
        calls[0] += 1
        if calls[0] % 2:
            kept.append(object())
    assert kept_over(every_other, 500) >= 500 // 4
