"""render() keeps its context (and so the pool's threads), framebuffer and
scratch from one call to the next while the thread count and SR_THREADS,
SR_SIMD stay the same (python/src/context_cache.c)."""

import os

import numpy as np
import pytest
import softrast
from conftest import default_camera

W, H = 32, 24


def pool_threads():
    return set(os.listdir("/proc/self/task"))


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="needs Linux's /proc")
def test_the_pool_is_kept_between_calls(monkeypatch):
    mesh = softrast.Mesh(np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 3.5]], np.float32),
                         np.array([[0, 2, 1]], np.int32))
    K, R, t = default_camera(W, H)
    monkeypatch.delenv("SR_THREADS", raising=False)

    def draw(threads):
        softrast.render(mesh, K=K, R=R, t=t, width=W, height=H, outputs=("depth",),
                        threads=threads)
        return pool_threads()

    first = draw(3)
    assert draw(3) == first   # the same worker threads, none started
    assert draw(3) == first
    other = draw(2)           # another thread count: another pool
    assert other != first
    monkeypatch.setenv("SR_THREADS", "3")   # read by the context: another pool again
    assert draw(2) != other
