"""render() keeps its context (and so the pool's threads), framebuffer and
scratch from one call to the next while the thread count and SR_THREADS,
SR_SIMD stay the same (python/src/context_cache.c)."""

import functools
import os

import numpy as np
import pytest
import softrast
from softrast import _softrast
from conftest import default_camera, random_triangles

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


def test_views_of_other_sizes_in_between():
    """The kept scratch holds the visibility pass's per-pixel words and,
    after them, its per-vertex arrays: a smaller view's arrays lie where
    a larger view's words go, and must not show in the next larger view."""
    rng = np.random.default_rng(21)
    verts, faces = random_triangles(rng, 500, size=0.8)
    mesh = softrast.Mesh(verts.astype(np.float32), faces.astype(np.int32))
    outputs = ("depth", "triangle_id", "normal")

    def draw(w, h, **kw):
        K, R, t = default_camera(w, h)
        return softrast.render(mesh, K=K, R=R, t=t, width=w, height=h, outputs=outputs,
                               threads=2, **kw)

    orig = _softrast.render
    _softrast.render = functools.partial(orig, general=True)
    try:
        want = draw(96, 72)
    finally:
        _softrast.render = orig
    for size in [(96, 72), (16, 12), (96, 72), (8, 6), (40, 30), (96, 72)]:
        got = draw(*size)
        if size == (96, 72):
            for name in outputs:
                assert got[name].tobytes() == want[name].tobytes(), name
