"""softrast.Canvas's state: the current transform, the clip, save and
restore.  Each drawing is held to the bytes render_svg gives for the SVG
document that says the same with transform attributes and clipPaths (the
reader composes transforms, maps points and blends clipped layers with
the same arithmetic), and bad arguments are refused with their names."""

import math

import numpy as np
import pytest
import softrast
from softrast import _softrast
from test_canvas import CURVES, STOPS, TRIANGLE, H, W, assert_same_as_svg, needs_svg, path_of, \
    stops_svg, svg

# translate(10.5 4) rotate(20) scale(1.5 0.75), as SVG's transform
# attribute writes it and as the canvas's calls make it.
SVG_TRANSFORM = "translate(10.5 4) rotate(20) scale(1.5 0.75)"
CIRCLE = "M70 32 a18 18 0 1 0 -36 0 a18 18 0 1 0 36 0 z"
RING = "M48 6 a26 26 0 1 0 0.01 0 z M48 18 a14 14 0 1 1 -0.01 0 z"


def transformed(canvas):
    canvas.translate(10.5, 4)
    canvas.rotate(20 * math.pi / 180)  # SVG's rotate(20): degrees * pi / 180
    canvas.scale(1.5, 0.75)


def tolerance(canvas):
    """The flattening tolerance the SVG reader builds a shape with under
    the canvas's transform: 0.1 pixel (0.1 / sqrt|det| user units)."""
    a, b, c, d, _, _ = canvas.get_transform()
    return 0.1 / math.sqrt(abs(a * d - b * c))


def test_transform_calls_compose_and_read_back():
    canvas = softrast.Canvas(8, 8)
    assert canvas.get_transform() == (1, 0, 0, 1, 0, 0)
    canvas.translate(3, 4)
    canvas.scale(2)
    assert canvas.get_transform() == (2, 0, 0, 2, 3, 4)
    canvas.transform(1, 0, 0.5, 1, 0, 0)  # a skew, applied before the scale
    assert canvas.get_transform() == (2, 0, 1, 2, 3, 4)
    canvas.rotate(math.pi / 2)
    a, b, c, d, e, f = canvas.get_transform()
    assert np.allclose((a, b, c, d, e, f), (1, 2, -2, 0, 3, 4))
    m = canvas.get_transform()
    canvas.reset_transform()
    assert canvas.get_transform() == (1, 0, 0, 1, 0, 0)
    canvas.set_transform(*m)
    assert canvas.get_transform() == m


@needs_svg
@pytest.mark.parametrize("antialias", [True, False])
def test_transformed_fill_and_stroke_are_the_svg_group_transform(antialias):
    canvas = softrast.Canvas(W, H, background="white")
    transformed(canvas)
    tol = tolerance(canvas)
    grad = softrast.LinearGradient((20, 10), (60, 40), STOPS, spread="reflect")
    canvas.fill(path_of(CURVES, tol), grad, antialias=antialias, opacity=0.8)
    # A stroke's width and dashes are in user units: the transform maps
    # the outline, so the lines are wider along x than along y.
    canvas.stroke(path_of(TRIANGLE, tol), "rgba(128, 0, 64, 0.8)", width=3, join="round",
                  dashes=[9, 4], dash_offset=2, antialias=antialias)
    crisp = "" if antialias else ' shape-rendering="crispEdges"'
    defs = (f'<linearGradient id="g" gradientUnits="userSpaceOnUse" x1="20" y1="10" x2="60" '
            f'y2="40" spreadMethod="reflect">{stops_svg(STOPS)}</linearGradient>')
    body = (f'<g transform="{SVG_TRANSFORM}">'
            f'<path d="{CURVES}" fill="url(#g)" fill-opacity="0.8"{crisp}/>'
            f'<path d="{TRIANGLE}" fill="none" stroke="rgba(128, 0, 64, 0.8)" stroke-width="3" '
            f'stroke-linejoin="round" stroke-dasharray="9 4" stroke-dashoffset="2"{crisp}/></g>')
    assert_same_as_svg(canvas, svg(body, defs), background="white")


@needs_svg
@pytest.mark.parametrize("rule", ["nonzero", "evenodd"])
def test_clip_is_the_svg_clip_path(rule):
    canvas = softrast.Canvas(W, H, background="white")
    canvas.fill(path_of(TRIANGLE), "#dddddd")
    with canvas.save():
        canvas.clip(softrast.Path.from_svg(RING), rule=rule)
        canvas.fill(path_of(CURVES), "navy", opacity=0.9)
        canvas.stroke(path_of(TRIANGLE), "crimson", width=4)
    canvas.fill([[0, 0], [10, 0], [10, 10]], "green")  # after restore: not clipped
    defs = f'<clipPath id="c"><path d="{RING}" clip-rule="{rule}"/></clipPath>'
    body = (f'<path d="{TRIANGLE}" fill="#dddddd"/>'
            f'<path d="{CURVES}" fill="navy" fill-opacity="0.9" clip-path="url(#c)"/>'
            f'<path d="{TRIANGLE}" fill="none" stroke="crimson" stroke-width="4" '
            f'clip-path="url(#c)"/><path d="M0 0 L10 0 L10 10 Z" fill="green"/>')
    assert_same_as_svg(canvas, svg(body, defs), background="white")


@needs_svg
def test_clip_under_a_transform_stays_where_it_was_set():
    # The clip is set under one transform and the shape drawn under a
    # further scale: SVG's clip-path on a group whose child has its own
    # transform.
    canvas = softrast.Canvas(W, H)
    transformed(canvas)
    canvas.clip(softrast.Path.from_svg(CIRCLE, tolerance(canvas)))
    canvas.scale(1.25)
    canvas.fill(path_of(CURVES, tolerance(canvas)),
                softrast.RadialGradient((40, 30), 30, STOPS), opacity=0.7)
    defs = f'<clipPath id="c"><path d="{CIRCLE}"/></clipPath>'
    body = (f'<g transform="{SVG_TRANSFORM}" clip-path="url(#c)">'
            f'<path transform="scale(1.25)" d="{CURVES}" fill="url(#g)" fill-opacity="0.7"/></g>')
    defs += (f'<radialGradient id="g" gradientUnits="userSpaceOnUse" cx="40" cy="30" r="30">'
             f"{stops_svg(STOPS)}</radialGradient>")
    assert_same_as_svg(canvas, svg(body, defs))


@needs_svg
def test_nested_clips_multiply_as_a_clipped_clip_path():
    canvas = softrast.Canvas(W, H, background="white")
    canvas.clip(softrast.Path.from_svg(CIRCLE))
    canvas.save()
    canvas.translate(6, -3)
    canvas.clip(path_of(TRIANGLE), rule="evenodd")
    canvas.reset_transform()
    canvas.fill([[0, 0], [W, 0], [W, H], [0, H]], "rgba(0, 90, 200, 0.85)")
    canvas.restore()
    canvas.fill([[0, 30], [W, 30], [W, 40], [0, 40]], "orange")  # the circle's clip only
    defs = (f'<clipPath id="a"><path d="{CIRCLE}"/></clipPath>'
            f'<clipPath id="b" clip-path="url(#a)"><path transform="translate(6 -3)" '
            f'd="{TRIANGLE}" clip-rule="evenodd"/></clipPath>')
    body = (f'<rect width="{W}" height="{H}" fill="rgba(0, 90, 200, 0.85)" clip-path="url(#b)"/>'
            f'<rect y="30" width="{W}" height="10" fill="orange" clip-path="url(#a)"/>')
    assert_same_as_svg(canvas, svg(body, defs), background="white")


def test_save_restore_and_the_with_statement():
    canvas = softrast.Canvas(16, 16)
    canvas.translate(2, 3)
    with canvas.save() as same:
        assert same is canvas
        canvas.scale(4)
        canvas.clip([[0, 0], [1, 0], [1, 1], [0, 1]])
        canvas.save()  # left unrestored: the with statement's end drops it
        canvas.rotate(1.0)
    assert canvas.get_transform() == (1, 0, 0, 1, 2, 3)
    canvas.fill([[-2, -3], [14, -3], [14, 13], [-2, 13]], "white")  # unclipped: every pixel
    assert np.all(canvas.image == 255)
    canvas.clip([[0, 0], [4, 0], [4, 4], [0, 4]])
    canvas.fill([[-2, -3], [14, -3], [14, 13], [-2, 13]], "black")
    lit = np.argwhere(canvas.image[..., 0] == 0)
    assert lit.min(axis=0).tolist() == [3, 2] and lit.max(axis=0).tolist() == [6, 5]
    canvas.reset_clip()
    canvas.clear("white")
    canvas.fill([[-2, -3], [14, -3], [14, 13], [-2, 13]], "black")
    assert np.all(canvas.image[..., :3] == 0)


def test_clip_outside_hides_everything_and_clear_ignores_the_clip():
    canvas = softrast.Canvas(8, 8)
    canvas.clip([[100, 100], [110, 100], [110, 110]])
    canvas.fill([[0, 0], [8, 0], [8, 8], [0, 8]], "red")
    assert not canvas.image.any()
    canvas.clear("blue")
    assert np.all(canvas.image[..., 2] == 255)


C = softrast.Canvas


def restored(c):
    c.restore()


@pytest.mark.parametrize("call, error, message", [
    (lambda c: c.translate(float("nan"), 0), ValueError, "tx: must be finite"),
    (lambda c: c.translate(0, float("inf")), ValueError, "ty: must be finite"),
    (lambda c: c.translate(1e308, 0) or c.translate(1e308, 0), ValueError,
     "translate: the transform would not be finite"),
    (lambda c: c.scale(0), ValueError, "sx: must not be 0"),
    (lambda c: c.scale(2, 0.0), ValueError, "sy: must not be 0"),
    (lambda c: c.scale(1e-200) or c.scale(1e-200), ValueError,
     "scale: the transform would be singular"),
    (lambda c: c.scale("2"), TypeError, "sx: expected a number, got str"),
    (lambda c: c.rotate(float("inf")), ValueError, "angle: must be finite"),
    (lambda c: c.rotate(True), TypeError, "angle: expected a number, got bool"),
    (lambda c: c.transform(1, 2, 2, 4, 0, 0), ValueError,
     r"transform: the transform would be singular \(determinant 0\)"),
    (lambda c: c.transform(1, 0, 0, float("nan"), 0, 0), ValueError, "d: must be finite"),
    (lambda c: c.set_transform(0, 0, 0, 0, 0, 0), ValueError,
     "set_transform: the transform would be singular"),
    (lambda c: c.set_transform(1, 0, 0, 1, 0, float("-inf")), ValueError, "f: must be finite"),
    (lambda c: c.set_transform(1, 0, 0, 1, 0), TypeError, "missing 1 required"),
    (restored, RuntimeError, r"restore: no saved state"),
    (lambda c: c.clip([[0, 0], [1, 0]], rule="odd"), ValueError, "rule: expected one of"),
    (lambda c: c.clip([[0, 0], [1, np.nan]]), ValueError, "shape: point 1 is NaN"),
    (lambda c: c.clip([[0, 0], [1, 0], [0, 1]], antialias=1), TypeError, "antialias"),
    (lambda c: c.clip(np.zeros((3, 2), bool)), TypeError, "shape: dtype"),
    (lambda c: c.clip("M0 0"), TypeError, "shape"),
])
def test_bad_state_arguments_are_named(call, error, message):
    canvas = softrast.Canvas(8, 8)
    with pytest.raises(error, match=message):
        call(canvas)
    # nothing was drawn, and the state is as it was
    assert not canvas.image.any()


def test_a_failed_call_leaves_the_state_as_it_was():
    canvas = softrast.Canvas(8, 8)
    canvas.translate(1, 2)
    with pytest.raises(ValueError):
        canvas.scale(0, 1)
    with pytest.raises(ValueError):
        canvas.transform(1, 1, 1, 1, 0, 0)
    assert canvas.get_transform() == (1, 0, 0, 1, 1, 2)


def test_with_block_restored_twice_raises():
    canvas = softrast.Canvas(8, 8)
    with pytest.raises(RuntimeError, match="restored already"):
        with canvas.save():
            canvas.restore()


def test_core_checks_what_it_is_given():
    # Canvas2D (python/src/canvas.c) checks the transform and the clip
    # that softrast.Canvas passes it.
    core = _softrast.Canvas2D(np.zeros((4, 4, 4), np.uint8))
    tri = [np.array([[0.0, 0], [4, 0], [0, 4]])]
    paint = softrast.Canvas(1, 1)._mapped(softrast._draw._paint("red", 1.0))
    ident = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="transform: the matrix is singular"):
        core.fill(tri, paint, 1, True, (1.0, 2.0, 2.0, 4.0, 0.0, 0.0), None)
    with pytest.raises(ValueError, match="transform: contains NaN"):
        core.coverage(tri, 1, True, (1.0, 0.0, 0.0, float("nan"), 0.0, 0.0))
    with pytest.raises(TypeError, match="transform: expected a tuple of 6 numbers"):
        core.fill(tri, paint, 1, True, (1.0, 0.0), None)
    with pytest.raises(ValueError, match=r"clip: shape must be \(4, 4\)"):
        core.fill(tri, paint, 1, True, ident, np.zeros((3, 4), np.uint8))
    with pytest.raises(TypeError, match="clip: dtype must be uint8"):
        core.fill(tri, paint, 1, True, ident, np.zeros((4, 4), np.float32))
    assert not core.image.any()
    cov = core.coverage(tri, 1, False, ident)
    assert cov.shape == (4, 4) and cov.dtype == np.uint8 and cov[0, 0] == 255 and cov[3, 3] == 0


def test_the_docs_state_example_runs():
    # The transform and clip example of docs/python.md, as written: the
    # square frame's hole stays white, the frame is teal, and the
    # vertical stroke is twice as wide as the horizontal one (x scaled 2).
    import pathlib
    import re
    root = pathlib.Path(__file__).resolve().parents[2]
    text = (root / "docs" / "python.md").read_text()
    (code,) = [b for b in re.findall(r"```python\n(.*?)```", text, re.S) if "canvas.clip(" in b]
    scope = {"math": math, "softrast": softrast}
    exec(code, scope)
    image = scope["canvas"].image
    assert image[60, 100].tolist() == [255, 255, 255, 255]  # the hole (the origin)
    assert image[60, 150].tolist() == [0, 128, 128, 255]  # the frame
    gold = np.all(image[..., :3] == [255, 215, 0], axis=2)
    assert 3 <= gold[:, 60:70].sum(axis=0).max() <= 5  # horizontal: 4 px high
    assert 7 <= gold[20:30, :].sum(axis=1).max() <= 10  # vertical: about 8 px wide
    assert image[110, 100, :3].tolist() == [0, 0, 0]  # the unclipped line
