"""softrast.Canvas: 2D drawing with the library's paths, fills, strokes and
paints.  Each drawing is held to the bytes render_svg gives for the same
SVG document (the reader paints through the same C calls), drawn in place
into the caller's array, and every bad argument is refused with its name."""

import base64
import pathlib
import re
import threading

import numpy as np
import pytest
import softrast
from softrast import _softrast

needs_svg = pytest.mark.skipif(not _softrast.have_svg, reason="this build reads no SVG (expat)")

W, H = 96, 64
TRIANGLE = "M8 6 L88 10 L50 58 Z"
# A path with every kind of segment: lines, a quadratic and a cubic
# Bezier, an arc; two subpaths, the second open.
CURVES = "M10 50 Q20 4 40 30 C50 50 70 0 86 20 A20 14 30 0 1 60 58 Z M12 10 L40 12 L20 26"
STOPS = [(0.0, "#ff0000"), (0.35, "rgba(0, 200, 0, 0.5)"), (1.0, "navy")]


def path_of(d, tolerance=0.1):
    """A Path from the subset of path data above (absolute M L Q C A Z)."""
    path = softrast.Path(tolerance)
    tokens = re.findall(r"[MLQCAZ]|-?[0-9.]+", d)
    calls = {"M": path.move_to, "L": path.line_to, "Q": path.quad_to, "C": path.cubic_to,
             "A": path.arc_to, "Z": path.close}
    sizes = {"M": 2, "L": 2, "Q": 4, "C": 6, "A": 7, "Z": 0}
    i = 0
    while i < len(tokens):
        cmd, n = tokens[i], sizes[tokens[i]]
        args = [float(t) for t in tokens[i + 1:i + 1 + n]]
        if cmd == "A":
            args[3:5] = [bool(args[3]), bool(args[4])]
        calls[cmd](*args)
        i += 1 + n
    return path


def svg(body, defs=""):
    return (f'<svg xmlns="http://www.w3.org/2000/svg" '
            f'xmlns:xlink="http://www.w3.org/1999/xlink" width="{W}" height="{H}">'
            f"<defs>{defs}</defs>{body}</svg>")


def stops_svg(stops):
    out = []
    for offset, color in stops:
        r, g, b, a = _softrast.parse_color(color)
        out.append(f'<stop offset="{offset}" stop-color="rgb({r * 255:g},{g * 255:g},{b * 255:g})"'
                   f' stop-opacity="{a:g}"/>')
    return "".join(out)


def matrix(t):
    """A 2x3 transform [[a, c, e], [b, d, f]] as SVG's matrix(a b c d e f)."""
    (a, c, e), (b, d, f) = t
    return f"matrix({a} {b} {c} {d} {e} {f})"


def assert_same_as_svg(canvas, document, background=None):
    theirs = softrast.render_svg(document, background=background)
    assert canvas.image.shape == theirs.shape
    differ = np.argwhere(np.any(canvas.image != theirs, axis=2))
    assert differ.size == 0, f"{len(differ)} pixels differ, first at {differ[:3].tolist()}"
    # not a blank picture that matches a blank picture
    assert len(np.unique(theirs.reshape(-1, 4), axis=0)) >= 2


@needs_svg
@pytest.mark.parametrize("d", [TRIANGLE, CURVES])
@pytest.mark.parametrize("rule", ["nonzero", "evenodd"])
@pytest.mark.parametrize("antialias", [True, False])
def test_solid_fill_is_the_svg_fill(d, rule, antialias):
    canvas = softrast.Canvas(W, H, background="white")
    canvas.fill(path_of(d), "#1e90ff", rule=rule, antialias=antialias, opacity=0.75)
    crisp = "" if antialias else ' shape-rendering="crispEdges"'
    assert_same_as_svg(canvas, svg(f'<path d="{d}" fill="#1e90ff" fill-rule="{rule}" '
                                   f'fill-opacity="0.75"{crisp}/>'), background="white")


@needs_svg
@pytest.mark.parametrize("spread", ["pad", "reflect", "repeat"])
def test_linear_gradient_is_the_svg_gradient(spread):
    transform = [[1.0, 0.3, 4.0], [0.2, 0.9, -3.0]]
    canvas = softrast.Canvas(W, H)
    canvas.fill(path_of(CURVES), softrast.LinearGradient((30, 10), (50, 30), STOPS, spread=spread,
                                                         transform=transform), opacity=0.9)
    defs = (f'<linearGradient id="g" gradientUnits="userSpaceOnUse" x1="30" y1="10" x2="50" '
            f'y2="30" spreadMethod="{spread}" gradientTransform="{matrix(transform)}">'
            f"{stops_svg(STOPS)}</linearGradient>")
    assert_same_as_svg(canvas, svg(f'<path d="{CURVES}" fill="url(#g)" fill-opacity="0.9"/>',
                                   defs))


@needs_svg
@pytest.mark.parametrize("spread", ["pad", "reflect", "repeat"])
@pytest.mark.parametrize("focal, fr", [(None, 0.0), ((40, 28), 4.0)])
def test_radial_gradient_is_the_svg_gradient(spread, focal, fr):
    canvas = softrast.Canvas(W, H, background=(0.9, 0.9, 0.8))
    canvas.fill(path_of(TRIANGLE), softrast.RadialGradient(
        (48, 30), 18, STOPS, focal=focal, focal_radius=fr, spread=spread))
    fx, fy = focal or (48, 30)
    defs = (f'<radialGradient id="g" gradientUnits="userSpaceOnUse" cx="48" cy="30" r="18" '
            f'fx="{fx}" fy="{fy}" fr="{fr}" spreadMethod="{spread}">'
            f"{stops_svg(STOPS)}</radialGradient>")
    assert_same_as_svg(canvas, svg(f'<path d="{TRIANGLE}" fill="url(#g)"/>', defs),
                       background=(0.9, 0.9, 0.8))


def tile():
    rng = np.random.default_rng(7)
    image = rng.integers(0, 256, (5, 7, 4), dtype=np.uint8)
    image[..., 3] = np.where(image[..., 3] < 60, 0, 255)
    return image


def data_uri(tmp_path, image):
    png = tmp_path / "tile.png"
    softrast.write_png(png, image)
    return "data:image/png;base64," + base64.b64encode(png.read_bytes()).decode()


@needs_svg
def test_clamped_pattern_is_the_svg_image(tmp_path):
    # <image x=10 y=6 width=70 height=50> stretches the 7x5 picture over
    # that rectangle: a pattern scaled by 10 and moved, its edges clamped.
    canvas = softrast.Canvas(W, H, background="white")
    rect = np.array([[10, 6], [80, 6], [80, 56], [10, 56]])
    canvas.fill(rect, softrast.Pattern(tile(), transform=[[10, 0, 10], [0, 10, 6]], wrap="clamp"))
    body = (f'<image x="10" y="6" width="70" height="50" preserveAspectRatio="none" '
            f'xlink:href="{data_uri(tmp_path, tile())}"/>')
    assert_same_as_svg(canvas, svg(body), background="white")


@needs_svg
def test_repeated_pattern_is_the_svg_pattern(tmp_path):
    # A <pattern> tile 7x5 user units holding the picture at its own size.
    # The reader draws a tile at the device's scale along its axes: under
    # a rotation (3-4-5) and a move that is 7x5 texels, the picture's own,
    # repeated and transformed as the canvas's pattern is.
    canvas = softrast.Canvas(W, H)
    transform = [[0.6, -0.8, 30.0], [0.8, 0.6, 2.0]]
    canvas.fill(path_of(CURVES), softrast.Pattern(tile(), transform=transform), opacity=0.8)
    defs = (f'<pattern id="p" patternUnits="userSpaceOnUse" width="7" height="5" '
            f'patternTransform="{matrix(transform)}">'
            f'<image width="7" height="5" xlink:href="{data_uri(tmp_path, tile())}"/></pattern>')
    assert_same_as_svg(canvas, svg(f'<path d="{CURVES}" fill="url(#p)" fill-opacity="0.8"/>',
                                   defs))


@needs_svg
@pytest.mark.parametrize("join, cap", [("miter", "butt"), ("round", "round"),
                                       ("bevel", "square")])
def test_stroke_is_the_svg_stroke(join, cap):
    canvas = softrast.Canvas(W, H, background="white")
    path = path_of(CURVES)
    canvas.stroke(path, "rgba(128, 0, 64, 0.8)", width=5, join=join, cap=cap, miter_limit=2.5)
    grad = softrast.LinearGradient((0, 0), (W, H), STOPS, spread="reflect")
    canvas.stroke(path_of(TRIANGLE), grad, width=3.5, join=join, cap=cap, opacity=0.6)
    defs = (f'<linearGradient id="g" gradientUnits="userSpaceOnUse" x1="0" y1="0" x2="{W}" '
            f'y2="{H}" spreadMethod="reflect">{stops_svg(STOPS)}</linearGradient>')
    body = (f'<path d="{CURVES}" fill="none" stroke="rgba(128, 0, 64, 0.8)" stroke-width="5" '
            f'stroke-linejoin="{join}" stroke-linecap="{cap}" stroke-miterlimit="2.5"/>'
            f'<path d="{TRIANGLE}" fill="none" stroke="url(#g)" stroke-width="3.5" '
            f'stroke-linejoin="{join}" stroke-linecap="{cap}" stroke-opacity="0.6"/>')
    assert_same_as_svg(canvas, svg(body, defs), background="white")


# Every command of path data, relative ones, implicit repeats, S and T
# reflecting, compact numbers and arc flags; a closed and an open subpath.
EVERY_COMMAND = ("m10 8 20 2h30v6 c10 0 20 10 10 20 s-10 10-20 0q-10-10-20 0t-10 0 "
                 "a8 6 20 1 0-10-12zM70 40L86 44 88 58H60a6 6 0 01-8-8")


@needs_svg
def test_svg_path_data_is_the_svg_path():
    canvas = softrast.Canvas(W, H, background="white")
    path = softrast.Path.from_svg(EVERY_COMMAND)
    canvas.fill(path, "#1e90ff", rule="evenodd", opacity=0.7)
    canvas.stroke(path, "navy", width=1.5, join="round")
    assert_same_as_svg(canvas, svg(
        f'<path d="{EVERY_COMMAND}" fill="#1e90ff" fill-rule="evenodd" fill-opacity="0.7" '
        f'stroke="navy" stroke-width="1.5" stroke-linejoin="round"/>'), background="white")
    # the subset path_of reads gives the same points as the calls
    ours, theirs = softrast.Path.from_svg(CURVES).to_polygons(), path_of(CURVES).to_polygons()
    assert len(ours) == len(theirs) == 2
    assert all(np.array_equal(a, b) for a, b in zip(ours, theirs))


@needs_svg
def test_svg_path_data_in_error_draws_up_to_it_when_not_strict():
    broken = "M10 10 L80 12 L50 50 Z M20 40 L30 x 60"
    with pytest.raises(ValueError, match="d: path data: expected a number at offset 34"):
        softrast.Path.from_svg(broken)
    path = softrast.Path.from_svg(broken, strict=False)
    assert [len(c) for c in path.to_polygons()] == [3, 1]
    canvas = softrast.Canvas(W, H)
    canvas.stroke(path, "black", width=2)
    with pytest.warns(softrast.SvgWarning, match="offset 34; drawn up to there"):
        document = svg(f'<path d="{broken}" fill="none" stroke="black" stroke-width="2"/>')
        assert_same_as_svg(canvas, document)


@needs_svg
@pytest.mark.parametrize("dashes, offset, cap, join", [
    ([6, 3], 0, "butt", "miter"),
    ([5, 2, 1], 2.5, "round", "round"),   # odd: repeated once
    ([8, 4], -3, "square", "bevel"),      # backward
    ([0, 6], 40, "round", "miter"),       # dots, offset past a period
    ([30, 0.5], 0, "butt", "miter"),      # dashes over the closed subpath's start
])
def test_dashed_stroke_is_the_svg_dashed_stroke(dashes, offset, cap, join):
    canvas = softrast.Canvas(W, H, background="white")
    canvas.stroke(path_of(CURVES), "rgba(128, 0, 64, 0.8)", width=3, cap=cap, join=join,
                  dashes=dashes, dash_offset=offset)
    circle = softrast.Path.from_svg("M70 32 a18 18 0 1 0 -36 0 a18 18 0 1 0 36 0 z")
    canvas.stroke(circle, "teal", width=2, cap=cap, dashes=dashes, dash_offset=offset)
    array = ",".join(str(d) for d in dashes)
    attrs = (f'fill="none" stroke-dasharray="{array}" stroke-dashoffset="{offset}" '
             f'stroke-linecap="{cap}"')
    body = (f'<path d="{CURVES}" {attrs} stroke="rgba(128, 0, 64, 0.8)" stroke-width="3" '
            f'stroke-linejoin="{join}"/>'
            f'<path d="M70 32 a18 18 0 1 0 -36 0 a18 18 0 1 0 36 0 z" {attrs} stroke="teal" '
            f'stroke-width="2"/>')
    assert_same_as_svg(canvas, svg(body), background="white")


def test_dashes_of_zeros_or_none_stroke_solid():
    solid = softrast.Canvas(W, H)
    solid.stroke(path_of(CURVES), "black", width=2)
    for dashes in (None, [], [0, 0, 0]):
        canvas = softrast.Canvas(W, H)
        canvas.stroke(path_of(CURVES), "black", width=2, dashes=dashes, dash_offset=3)
        assert np.array_equal(canvas.image, solid.image)
    dashed = softrast.Canvas(W, H)
    dashed.stroke(path_of(CURVES), "black", width=2, dashes=(4, 4))
    assert 0 < dashed.image[..., 3].sum() < solid.image[..., 3].sum()


def test_polygon_fill_is_the_path_fill():
    # Points, a list of contours (a hole, even-odd) and the same as a Path.
    outer = np.array([[5.5, 4.25], [90, 8], [70, 60], [8, 50]])
    hole = [[30, 20], [60, 22], [45, 44]]
    by_points = softrast.Canvas(W, H)
    by_points.fill([outer, hole], "teal", rule="evenodd")
    by_path = softrast.Canvas(W, H)
    path = softrast.Path().add_polygon(outer).add_polygon(np.array(hole, np.int32))
    by_path.fill(path, "teal", rule="evenodd")
    assert np.array_equal(by_points.image, by_path.image)
    assert by_points.image[33, 45, 3] == 0 and by_points.image[33, 20, 3] == 255
    assert [p.shape for p in path.to_polygons()] == [(4, 2), (3, 2)]


def test_draws_in_place_into_the_callers_array():
    image = np.full((H, W, 4), 7, np.uint8)
    canvas = softrast.Canvas.from_array(image)
    assert canvas.image is image and (canvas.width, canvas.height) == (W, H)
    canvas.fill(np.array([[0, 0], [W, 0], [W, 10], [0, 10]]), (1.0, 0.0, 0.0))
    assert np.all(image[:10] == [255, 0, 0, 255]) and np.all(image[10:] == 7)
    # The array stays the truth: a change made between draws is kept.
    image[40:] = 200
    canvas.fill(np.array([[0, 30], [W, 30], [W, 50], [0, 50]]), (0.0, 0.0, 1.0, 0.5))
    assert np.all(image[50:] == 200) and np.all(image[20:30] == 7)
    over = softrast.Canvas.from_array(np.full((H, W, 4), 200, np.uint8))
    over.fill(np.array([[0, 30], [W, 30], [W, 50], [0, 50]]), (0.0, 0.0, 1.0, 0.5))
    assert np.array_equal(image[40:50], over.image[40:50])
    assert np.all(image[40:50] != 200)
    # a view into a larger buffer, the caller's memory itself
    big = np.zeros((H, W * 2, 4), np.uint8)
    softrast.Canvas.from_array(big[:H // 2]).clear("white")
    assert np.all(big[:H // 2] == 255) and np.all(big[H // 2:] == 0)


@needs_svg
def test_draws_over_a_render_svg_result():
    image = softrast.render_svg(svg(f'<path d="{TRIANGLE}" fill="gold"/>'))
    softrast.Canvas.from_array(image).stroke(path_of(TRIANGLE), "black", width=2)
    assert_same_as_svg(softrast.Canvas.from_array(image), svg(
        f'<path d="{TRIANGLE}" fill="gold" stroke="black" stroke-width="2"/>'))


def test_threads_draw_the_same_bytes():
    # Large shapes are drawn without the GIL; several threads drawing
    # into several canvases, and into one, give the bytes of one thread.
    rng = np.random.default_rng(3)
    shapes = [rng.uniform(-20, 500, (300, 2)) for _ in range(16)]

    def draw(canvas, i):
        canvas.fill(shapes[i], (i / 16, 0.5, 1 - i / 16, 0.5), rule="evenodd")

    alone = [softrast.Canvas(480, 480) for _ in shapes]
    for i, c in enumerate(alone):
        draw(c, i)
    together = [softrast.Canvas(480, 480) for _ in shapes]
    threads = [threading.Thread(target=draw, args=(c, i)) for i, c in enumerate(together)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(a.image, b.image) for a, b in zip(alone, together))
    # One canvas shared: each draw is whole (the lock), and the same
    # polygon at the same opacity gives the same bytes in any order.
    shared, one = softrast.Canvas(480, 480), softrast.Canvas(480, 480)
    threads = [threading.Thread(target=shared.fill, args=(shapes[0], "red"),
                                kwargs=dict(opacity=0.5)) for _ in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for _ in range(8):
        one.fill(shapes[0], "red", opacity=0.5)
    assert np.array_equal(shared.image, one.image)


@pytest.mark.parametrize("call, error, message", [
    (lambda: softrast.Canvas(0, 4), ValueError, "width: must be in 1..8192"),
    (lambda: softrast.Canvas(4, 9000), ValueError, "height: must be in 1..8192"),
    (lambda: softrast.Canvas(4.0, 4), TypeError, "width: expected an int"),
    (lambda: softrast.Canvas(4, 4, background="nope"), ValueError, "background: not a CSS color"),
    (lambda: softrast.Canvas(4, 4).clear((1, 1)), ValueError, "color: expected 3 or 4 numbers"),
    (lambda: softrast.Canvas.from_array(np.zeros((4, 4, 4), np.float32)), TypeError,
     "image: dtype must be uint8"),
    (lambda: softrast.Canvas.from_array(np.zeros((4, 4, 3), np.uint8)), ValueError,
     "image: shape must be"),
    (lambda: softrast.Canvas.from_array(np.zeros((4, 8, 4), np.uint8)[:, ::2]), ValueError,
     "image: array must be C-contiguous"),
    (lambda: softrast.Canvas.from_array(READONLY), ValueError, "image: array is read-only"),
    (lambda: softrast.Canvas.from_array([[[0, 0, 0, 0]]]), TypeError,
     "image: expected a numpy array"),
])
def test_bad_canvas_arguments_are_named(call, error, message):
    with pytest.raises(error, match=message.replace("(", r"\(")):
        call()


READONLY = np.zeros((4, 4, 4), np.uint8)
READONLY.flags.writeable = False

TRI = np.array([[1, 1], [9, 1], [5, 9]])


@pytest.mark.parametrize("call, error, message", [
    (lambda c: c.fill(TRI, "nope"), ValueError, "paint: not a CSS color: 'nope'"),
    (lambda c: c.fill(TRI, (1, 0)), ValueError, "paint: expected 3 or 4 numbers"),
    (lambda c: c.fill(TRI, (2, 0, 0)), ValueError, r"paint: components must be in \[0, 1\]"),
    (lambda c: c.fill(TRI, 3), TypeError, "paint: expected a color"),
    (lambda c: c.fill(TRI, "red", rule="odd"), ValueError, "rule: expected one of"),
    (lambda c: c.fill(TRI, "red", rule=1), TypeError, "rule: expected one of"),
    (lambda c: c.fill(TRI, "red", antialias="yes"), TypeError, "antialias: expected a bool"),
    (lambda c: c.fill(TRI, "red", opacity=1.5), ValueError, r"opacity: must be in \[0, 1\]"),
    (lambda c: c.fill(TRI, "red", opacity=float("nan")), ValueError, "opacity: must be finite"),
    (lambda c: c.fill(np.array([[1.0, np.nan], [4, 4], [2, 8]]), "red"), ValueError,
     "shape: point 0 is NaN or infinite"),
    (lambda c: c.fill(np.zeros((3, 3)), "red"), ValueError, r"shape: shape must be \(N, 2\)"),
    (lambda c: c.fill(TRI.astype(complex), "red"), TypeError, "shape: dtype must be a real"),
    (lambda c: c.fill("M 0 0", "red"), TypeError, "shape: dtype must be a real"),
    (lambda c: c.stroke(TRI, "red"), TypeError, "path: expected a softrast.Path"),
    (lambda c: c.stroke(softrast.Path(), "red", width=0), ValueError, "width: must be in"),
    (lambda c: c.stroke(softrast.Path(), "red", width="2"), TypeError, "width: expected a number"),
    (lambda c: c.stroke(softrast.Path(), "red", join="mitre"), ValueError, "join: expected one"),
    (lambda c: c.stroke(softrast.Path(), "red", cap="flat"), ValueError, "cap: expected one"),
    (lambda c: c.stroke(softrast.Path(), "red", miter_limit=0.5), ValueError,
     "miter_limit: must be >= 1"),
    (lambda c: c.stroke(softrast.Path(), "red", dashes="4 2"), TypeError,
     "dashes: expected a sequence of lengths, got str"),
    (lambda c: c.stroke(softrast.Path(), "red", dashes=4), TypeError,
     "dashes: expected a sequence of lengths, got int"),
    (lambda c: c.stroke(softrast.Path(), "red", dashes=[4, -1]), ValueError,
     r"dashes\[1\]: must be >= 0"),
    (lambda c: c.stroke(softrast.Path(), "red", dashes=[4, float("nan")]), ValueError,
     r"dashes\[1\]: must be finite"),
    (lambda c: c.stroke(softrast.Path(), "red", dashes=[4, None]), TypeError,
     r"dashes\[1\]: expected a number"),
    (lambda c: c.stroke(softrast.Path(), "red", dashes=[1] * 33), ValueError,
     "dashes: at most 32 values, got 33"),
    (lambda c: c.stroke(softrast.Path(), "red", dashes=[1, 1], dash_offset=float("inf")),
     ValueError, "dash_offset: must be finite"),
    (lambda c: c.stroke(softrast.Path(), "red", dashes=[1, 1], dash_offset="2"), TypeError,
     "dash_offset: expected a number"),
    # too fine where it is seen (only that part is dashed: test_path_view.py)
    (lambda c: c.stroke(P().move_to(0, 5).line_to(10, 5), "red", dashes=[1e-7, 1e-7]),
     ValueError, "sr_path_dash: a pattern of period 2e-07"),
    (lambda c: c._core.stroke(P(), ("red",) * 9, 1.0, 0, 0, 4.0, True, (1.0, "2"), 0.0,
                              (1.0, 0.0, 0.0, 1.0, 0.0, 0.0), None),
     TypeError, r"dashes\[1\]: expected a number"),
])
def test_bad_draw_arguments_are_named(call, error, message):
    canvas = softrast.Canvas(10, 10)
    with pytest.raises(error, match=message):
        call(canvas)
    assert not canvas.image.any()


LG = softrast.LinearGradient


@pytest.mark.parametrize("call, error, message", [
    (lambda: LG((0, 0), (1, 0), []), ValueError, r"stops: 0 stops, the library takes 1..256"),
    (lambda: LG((0, 0), (1, 0), [(i / 256, "red") for i in range(257)]), ValueError,
     "stops: 257 stops, the library takes 1..256"),
    (lambda: LG((0, 0), (1, 0), "red"), TypeError, "stops: expected a sequence"),
    (lambda: LG((0, 0), (1, 0), [(0.5, "red"), (0.2, "blue")]), ValueError,
     r"stops\[1\] offset: 0.2 is below"),
    (lambda: LG((0, 0), (1, 0), [(1.5, "red")]), ValueError, r"stops\[0\] offset: must be in"),
    (lambda: LG((0, 0), (1, 0), [(float("nan"), "red")]), ValueError,
     r"stops\[0\] offset: must be finite"),
    (lambda: LG((0, 0), (1, 0), [(0, "bogus")]), ValueError, r"stops\[0\] color: not a CSS"),
    (lambda: LG((0, 0), (1, 0), [0.5]), TypeError, r"stops\[0\]: expected an \(offset, color\)"),
    (lambda: LG((0, float("inf")), (1, 0), [(0, "red")]), ValueError, r"start\[1\]: must be fin"),
    (lambda: LG((0, 0, 0), (1, 0), [(0, "red")]), TypeError, "start: expected a point"),
    (lambda: LG((0, 0), (1, 0), [(0, "red")], spread="mirror"), ValueError, "spread: expected"),
    (lambda: LG((0, 0), (1, 0), [(0, "red")], transform=[[1, 0], [0, 1]]), ValueError,
     r"transform: shape must be \(2, 3\)"),
    (lambda: LG((0, 0), (1, 0), [(0, "red")], transform=[[1, 2, 0], [2, 4, 0]]), ValueError,
     "transform: the matrix is singular"),
    (lambda: LG((0, 0), (1, 0), [(0, "red")], transform=[[1, 0, np.nan], [0, 1, 0]]),
     ValueError, "transform: contains NaN"),
    (lambda: LG((0, 0), (1, 0), [(0, "red")], transform=[["a", 0, 0], [0, 1, 0]]), TypeError,
     "transform: expected a 2x3 matrix"),
    (lambda: softrast.RadialGradient((0, 0), 0, [(0, "red")]), ValueError,
     "radius: must be > 0"),
    (lambda: softrast.RadialGradient((0, 0), 1, [(0, "red")], focal_radius=-1), ValueError,
     "focal_radius: must be >= 0"),
    (lambda: softrast.RadialGradient((0, 0), 1, [(0, "red")], focal=(1, None)), TypeError,
     r"focal\[1\]: expected a number"),
    (lambda: softrast.Pattern(np.zeros((2, 2, 4), np.float64)), TypeError,
     "image: dtype must be uint8"),
    (lambda: softrast.Pattern(np.zeros((2, 2, 3), np.uint8)), ValueError,
     r"image: shape must be \(H, W, 4\)"),
    (lambda: softrast.Pattern([[[0, 0, 0, 0]]]), TypeError, "image: expected a numpy array"),
    (lambda: softrast.Pattern(np.zeros((2, 2, 4), np.uint8), wrap="mirror"), ValueError,
     "wrap: expected one of 'repeat', 'clamp'"),
])
def test_bad_paint_arguments_are_named(call, error, message):
    with pytest.raises(error, match=message):
        call()


P = softrast.Path


@pytest.mark.parametrize("call, error, message", [
    (lambda: P().move_to(float("nan"), 0), ValueError, "x: must be finite"),
    (lambda: P().move_to(0, "1"), TypeError, "y: expected a number, got str"),
    (lambda: P().quad_to(0, 0, float("inf"), 0), ValueError, "x: must be finite"),
    (lambda: P().cubic_to(0, 0, 1, None, 0, 0), TypeError, "y2: expected a number"),
    (lambda: P().arc_to(-1, 1, 0, False, True, 5, 5), ValueError, "rx: must be within 0.."),
    (lambda: P().arc_to(1, 1, float("nan"), False, True, 5, 5), ValueError,
     "rotation: must be finite"),
    (lambda: P().arc_to(1, 1, 0, 2, True, 5, 5), ValueError, "large_arc: must be 0 or 1"),
    (lambda: P().arc_to(1, 1, 0, False, "yes", 5, 5), TypeError, "sweep: expected a bool"),
    (lambda: P(tolerance=0), ValueError, "tolerance: must be > 0"),
    (lambda: P(tolerance=float("nan")), ValueError, "tolerance: must be finite"),
    (lambda: P().add_polygon([[0, 0], [1]]), ValueError, r"points: expected an \(N, 2\) array"),
    (lambda: P().add_polygon(np.zeros((4, 3))), ValueError, r"points: shape must be \(N, 2\)"),
    (lambda: P().add_polygon(np.array([[0, 0], [np.inf, 1]])), ValueError,
     "points: point 1 is NaN or infinite"),
    (lambda: P().move_to(1), TypeError, "missing required argument 'y'"),
    (lambda: P.from_svg(b"M0 0"), TypeError, "d: expected a str of SVG path data, got bytes"),
    (lambda: P.from_svg("M0 0\0L1 1"), ValueError, "d: contains a NUL character at offset 4"),
    (lambda: P.from_svg("M0 0 X"), ValueError, "d: path data: unknown command 'X' at offset 5"),
    (lambda: P.from_svg("L0 0"), ValueError, "d: path data: no moveto first at offset 0"),
    (lambda: P.from_svg("M0 0 L1e999 0"), ValueError, "d: path data: expected a number at "),
    (lambda: P.from_svg("M1e308 0 l1e308 0"), ValueError,
     r"d: sr_path_line_to: point is not finite \(the command at offset 9\)"),
    (lambda: P().arc_to(3e5, 1, 0, False, True, 5, 5), ValueError, "rx: must be within 0..262144"),
    (lambda: P.from_svg("M0 0", tolerance=0), ValueError, "tolerance: must be > 0"),
    (lambda: P.from_svg("M0 0", 0.1, True), TypeError, "at most 2 positional"),
])
def test_bad_path_arguments_are_named(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_path_methods_chain_and_flatten():
    path = softrast.Path(tolerance=0.25)
    assert path.move_to(0, 0).line_to(10, 0).quad_to(10, 10, 0, 10).close() is path
    (poly,) = path.to_polygons()
    assert path.tolerance == 0.25 and poly.dtype == np.float64
    assert np.array_equal(poly[:2], [[0, 0], [10, 0]]) and np.array_equal(poly[-1], [0, 10])
    assert len(poly) > 5  # the curve flattened into several lines
    assert path.clear().to_polygons() == []


def test_paints_are_immutable():
    grad = softrast.LinearGradient((0, 0), (8, 0), [(0, "red"), (1, "blue")])
    with pytest.raises(AttributeError, match="LinearGradient is immutable"):
        grad.spread = "repeat"
    assert grad.spread == "pad" and grad.start == (0.0, 0.0)
    assert np.array_equal(grad.stops, [[0, 1, 0, 0, 1], [1, 0, 0, 1, 1]])
    with pytest.raises(ValueError, match="read-only"):
        grad.stops[0, 0] = 0.5


def test_opacity_zero_and_shapes_outside_draw_nothing():
    canvas = softrast.Canvas(10, 10)
    canvas.fill(TRI, "red", opacity=0)
    canvas.fill(TRI + 100, "red")
    canvas.fill(np.zeros((0, 2)), "red")
    canvas.stroke(softrast.Path(), "red")
    assert not canvas.image.any()
    canvas.fill(TRI - 5, "red", antialias=False)  # partly outside: clipped
    assert canvas.image[:, :, 0].any()


def test_the_docs_example_draws_the_docs_image(tmp_path, monkeypatch):
    # The example of docs/python.md, run as written, gives its picture.
    root = pathlib.Path(__file__).resolve().parents[2]
    text = (root / "docs" / "python.md").read_text()
    (code,) = [b for b in re.findall(r"```python\n(.*?)```", text, re.S) if "Canvas(" in b
               and "python-canvas.png" in b]
    monkeypatch.chdir(tmp_path)
    scope = {}
    exec(code, scope)
    drawn = scope["canvas"].image
    assert np.array_equal(drawn, softrast.read_image(root / "docs" / "images" / "python-canvas.png"))
    assert np.array_equal(softrast.read_image(tmp_path / "canvas.png"), drawn)


needs_text = pytest.mark.skipif(not (_softrast.have_svg and _softrast.have_text),
                                reason="this build lays out no text (fontconfig, HarfBuzz, FreeType)")


@needs_text
@pytest.mark.parametrize("anchor", ["start", "middle", "end"])
def test_text_is_the_svg_text(anchor):
    canvas = softrast.Canvas(W, H, background="white")
    path = softrast.Path().text("Ta fi", 48, 40, size=22, family="DejaVu Sans", weight=700,
                                anchor=anchor)
    canvas.fill(path, "teal")
    assert_same_as_svg(canvas, svg(f'<text x="48" y="40" font-family="DejaVu Sans" '
                                   f'font-size="22" font-weight="bold" text-anchor="{anchor}" '
                                   f'fill="teal">Ta fi</text>'), background="white")


@needs_text
def test_text_refuses_bad_arguments():
    path = softrast.Path()
    with pytest.raises(ValueError, match="anchor"):
        path.text("a", 0, 0, anchor="left")
    with pytest.raises(ValueError, match="size"):
        path.text("a", 0, 0, size=0)
    with pytest.raises(ValueError, match="weight"):
        path.text("a", 0, 0, weight=1001)
    with pytest.raises(ValueError, match="nonexistent"):
        path.text("a", 0, 0, font_file="/nonexistent/font.ttf")
    with pytest.raises(TypeError, match="x"):
        path.text("a", "0", 0)
    assert path.to_polygons() == []


def test_shapes_beyond_262144_pixels_are_drawn_clipped():
    # Points beyond the fixed-point budget: cut to a guard band around the
    # image, drawn where they are seen (a path, a polygon, a scaled fill).
    far = softrast.Canvas(40, 40)
    far.fill(softrast.Path.from_svg("M4 4 L 1e9 20 L 4 36 z"), "blue")
    far.fill([[-1e12, 30], [1e12, 30], [1e12, 40], [-1e12, 40]], "red", antialias=False)
    near = softrast.Canvas(40, 40)
    near.fill(softrast.Path.from_svg("M4 4 L 2e5 %r L 2e5 %r L 4 36 z"
                                     % (4 + (2e5 - 4) * 16 / (1e9 - 4),
                                        36 - (2e5 - 4) * 16 / (1e9 - 4))), "blue")
    near.fill([[-2e5, 30], [2e5, 30], [2e5, 40], [-2e5, 40]], "red", antialias=False)
    assert np.abs(far.image.astype(int) - near.image).max() <= 2
    assert tuple(far.image[20, 39]) == (0, 0, 255, 255)
    assert tuple(far.image[35, 0]) == (255, 0, 0, 255)
    scaled = softrast.Canvas(8, 8)
    scaled.scale(1e6)
    scaled.fill([[0, 0], [1, 0], [0, 1]], "red")
    assert (scaled.image == (255, 0, 0, 255)).all()
