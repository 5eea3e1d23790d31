"""Images larger than the memory limit (SR_MEMORY_LIMIT, as for the softrast
tool) are refused with a MemoryError naming the sizes, before anything of
their size is allocated: the limit is set small here, and the calls' own
allocations stay far below the images they would have made."""

import tracemalloc

import numpy as np
import pytest
import softrast

V = np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 3]], np.float64)
F = np.array([[0, 1, 2]], np.int64)
SVG = (b"<svg xmlns='http://www.w3.org/2000/svg' width='8' height='8'>"
       b"<rect width='4' height='4'/></svg>")


def peak_bytes(call):
    """The most bytes the call held at once (numpy's arrays are traced too)."""
    tracemalloc.start()
    try:
        call()
    finally:
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    return peak


def batch_of_cameras(n, size):
    K = np.array([[size, 0, size / 2], [0, size, size / 2], [0, 0, 1.0]])
    return np.repeat(K[None], n, axis=0), np.repeat(np.eye(3)[None], n, axis=0), np.zeros((n, 3))


def test_render_beyond_the_limit_raises_before_allocating(monkeypatch):
    monkeypatch.setenv("SR_MEMORY_LIMIT", "64M")
    K, R, t = batch_of_cameras(8, 8192)
    err = {}

    def call():
        with pytest.raises(MemoryError) as e:
            softrast.render(softrast.Mesh(V, F), K=K, R=R, t=t, width=8192, height=8192,
                            outputs=("color", "depth"), antialias="msaa4")
        err["text"] = str(e.value)

    # 8 views of 8192 x 8192 color and depth (7 bytes a pixel) with the
    # 4x MSAA frame: 3.5 GiB of outputs, 2.5 GiB of frames.
    assert peak_bytes(call) < 8 * 2**20
    text = err["text"]
    assert "8 views of 8192 x 8192" in text and "antialias msaa4" in text
    assert "needs about 6.0 GiB" in text and "SR_MEMORY_LIMIT=64M" in text


def test_render_within_the_limit_draws(monkeypatch):
    monkeypatch.setenv("SR_MEMORY_LIMIT", "64M")
    K, R, t = batch_of_cameras(2, 32)
    out = softrast.render(softrast.Mesh(V, F), K=K, R=R, t=t, width=32, height=32)
    assert out["color"].shape == (2, 32, 32, 3)
    # One byte short of what the same call needs is refused.
    monkeypatch.setenv("SR_MEMORY_LIMIT", str(2 * 32 * 32 * 7 + 32 * 32 * 8 - 1))
    with pytest.raises(MemoryError, match="2 views of 32 x 32"):
        softrast.render(softrast.Mesh(V, F), K=K, R=R, t=t, width=32, height=32)


def test_canvas_and_render_svg_beyond_the_limit(monkeypatch):
    monkeypatch.setenv("SR_MEMORY_LIMIT", "1M")
    assert peak_bytes(lambda: pytest.raises(MemoryError, softrast.Canvas, 8192, 8192)) < 2**20
    with pytest.raises(MemoryError, match=r"Canvas: 8192 x 8192 needs about 256 MiB"):
        softrast.Canvas(8192, 8192)
    assert softrast.Canvas(64, 64).width == 64
    if not softrast._softrast.have_svg:
        pytest.skip("this build reads no SVG")
    with pytest.raises(MemoryError, match=r"render_svg: 8192 x 8192 needs about 512 MiB"):
        softrast.render_svg(SVG, width=8192, height=8192)
    assert softrast.render_svg(SVG, width=16, height=16).shape == (16, 16, 4)


@pytest.mark.parametrize("value", ["", "lots", "-5", "8X", "8GBs", "0"])
def test_a_bad_limit_is_named(monkeypatch, value):
    monkeypatch.setenv("SR_MEMORY_LIMIT", value)
    with pytest.raises(ValueError, match="SR_MEMORY_LIMIT: expected a size in bytes"):
        softrast.Canvas(8, 8)


@pytest.mark.parametrize("value", ["1048576", "1M", "1Mi", "1MiB", "1MB", "0.0009765625G"])
def test_limit_spellings(monkeypatch, value):
    monkeypatch.setenv("SR_MEMORY_LIMIT", value)
    softrast.Canvas(512, 512)   # exactly 1 MiB
    with pytest.raises(MemoryError):
        softrast.Canvas(512, 513)


def nested_layers_svg(depth, side):
    """Groups with opacity and a clip path, `depth` deep: each opens a layer
    of the image's size while it is drawn."""
    head = (f"<svg xmlns='http://www.w3.org/2000/svg' width='{side}' height='{side}'>"
            f"<clipPath id='c'><rect width='{side - 4}' height='{side - 4}'/></clipPath>")
    return (head + "<g opacity='0.9' clip-path='url(#c)'>" * depth
            + "<rect width='40' height='40' fill='red'/>" + "</g>" * depth + "</svg>").encode()


def test_svg_layers_past_the_limit_raise_memory_error(monkeypatch):
    # 512 x 512: 1 MiB of image, 1.5 MiB a layer; the drawing and its
    # array fit 8M, eight layers (12 MiB) do not.  The size from the
    # document, then given: the layers get what the image leaves either way.
    doc = nested_layers_svg(8, 512)
    monkeypatch.setenv("SR_MEMORY_LIMIT", "8M")
    for size in ({}, {"width": 512, "height": 512}):
        with pytest.raises(MemoryError, match=r"<svg>:1: layers nested \d deep .* left for them"):
            softrast.render_svg(doc, **size)
    monkeypatch.setenv("SR_MEMORY_LIMIT", "64M")
    image = softrast.render_svg(doc)
    assert image.shape == (512, 512, 4) and image[10, 10, 3] > 0
    # A work budget passed is the document's to answer for, not memory's.
    subpaths = b"<svg width='100' height='100'><path d='" + b"M0 0 1 1" * 20000 + b"'/></svg>"
    with pytest.raises(ValueError, match="subpaths"):
        softrast.render_svg(subpaths)
    monkeypatch.setenv("SR_MEMORY_LIMIT", "lots")
    with pytest.raises(ValueError, match="SR_MEMORY_LIMIT: expected a size"):
        softrast.render_svg(doc)
