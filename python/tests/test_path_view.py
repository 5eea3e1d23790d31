"""softrast.PathView and the Path methods that take one (sr_path_view,
sr_path_cull_curves, sr_path_length_in_view, sr_path_dash_in_view), held to
the C library's results; and strokes of paths far larger than the canvas,
which Canvas.stroke dashes within the image as the SVG reader does."""

import numpy as np
import pytest
import softrast

P = softrast.Path
V = softrast.PathView


def line(x0, x1, y):
    return P().move_to(x0, y).line_to(x1, y)


def test_a_view_keeps_what_it_was_given():
    v = V((0, -1, 100, 1), transform=(2, 0, 0, 2, 10, 0))
    assert v.rect == (0.0, -1.0, 100.0, 1.0)
    assert v.transform == (2.0, 0.0, 0.0, 2.0, 10.0, 0.0)
    assert V([0, 0, 5, 5]).transform == (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)
    assert repr(V((0, 0, 1, 1))) == ("PathView(rect=(0.0, 0.0, 1.0, 1.0), "
                                     "transform=(1.0, 0.0, 0.0, 1.0, 0.0, 0.0))")
    with pytest.raises(AttributeError):
        v.rect = (0, 0, 1, 1)


@pytest.mark.parametrize("call, error, message", [
    (lambda: V((0, 0, 1)), ValueError, "rect: expected 4 numbers, got 3"),
    (lambda: V("abcd"), TypeError, "rect: expected a sequence of 4 numbers, got str"),
    (lambda: V((0, "0", 1, 1)), TypeError, r"rect\[1\]: expected a number, got str"),
    (lambda: V((0, 0, float("nan"), 1)), ValueError, r"rect\[2\]: must be finite"),
    (lambda: V((0, 0, 1, True)), TypeError, r"rect\[3\]: expected a number, got bool"),
    (lambda: V((2, 0, 1, 1)), ValueError, r"rect: \(x0, y0, x1, y1\) is empty"),
    (lambda: V((0, 3, 1, 1)), ValueError, "rect: .* is empty"),
    (lambda: V((0, 0, 1, 1), (1, 0, 0, 1, 0)), ValueError, "transform: expected 6 numbers"),
    (lambda: V((0, 0, 1, 1), (1, 0, 0, 1, 0, float("inf"))), ValueError,
     r"transform\[5\]: must be finite"),
    (lambda: V((0, 0, 1, 1), 7), TypeError, "transform: expected a sequence of 6 numbers"),
    (lambda: V(), TypeError, "rect"),
    (lambda: line(0, 1, 0).length("view"), TypeError,
     "view: expected a softrast.PathView or None, got str"),
    (lambda: line(0, 1, 0).cull_curves((0, 0, 1, 1)), TypeError, "view: expected a softrast.PathView"),
    (lambda: line(0, 1, 0).cull_curves(), TypeError, "view"),
    (lambda: line(0, 1, 0).dash([1, 1], view=[0, 0, 1, 1]), TypeError, "view: expected"),
    (lambda: line(0, 1, 0).dash(5), TypeError, "dashes: expected a sequence of lengths, got int"),
    (lambda: line(0, 1, 0).dash("12"), TypeError, "dashes: expected a sequence of lengths"),
    (lambda: line(0, 1, 0).dash([1] * 33), ValueError, "dashes: at most 32 values, got 33"),
    (lambda: line(0, 1, 0).dash([1, -1]), ValueError, r"dashes\[1\]: must be >= 0, got -1"),
    (lambda: line(0, 1, 0).dash([1, "a"]), TypeError, r"dashes\[1\]: expected a number"),
    (lambda: line(0, 1, 0).dash([1, float("nan")]), ValueError, r"dashes\[1\]: must be finite"),
    (lambda: line(0, 1, 0).dash([1, 1], float("inf")), ValueError, "offset: must be finite"),
    (lambda: line(0, 1, 0).dash([1, 1], "2"), TypeError, "offset: expected a number"),
    (lambda: line(0, 1, 0).dash([1, 1], 0, V((0, 0, 1, 1))), TypeError, "at most 2 positional"),
    # the library's limit, named: a pattern along the whole of a 2e9 px line
    (lambda: line(-1e9, 1e9, 0).dash([10, 10]), ValueError,
     "dashes: sr_path_dash: a pattern of period 20 along a path of length 2e.09 makes about"),
])
def test_bad_view_arguments_are_named(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_length_within_a_view_is_the_part_inside():
    square = P().add_polygon([[0, 0], [10, 0], [10, 10], [0, 10]])
    assert square.length() == 40.0  # the closing side counted
    assert P().length() == 0.0
    # as tests/test_draw2d_dash.c: x' = 2x + 10 keeps x in [-5, 45] in [0, 100]
    long = line(-1000, 1000, 0)
    assert long.length(V((0, -1, 100, 1), (2, 0, 0, 2, 10, 0))) == pytest.approx(50, abs=1e-9)
    assert long.length(None) == 2000.0
    assert long.length(V((0, 5, 100, 6))) == 0.0  # the line passes below the rectangle


def test_dashes_within_a_view_are_the_full_walks_dashes_there():
    path = line(0, 1000, 5)
    full = path.dash([7, 3], 2)
    seen = path.dash([7, 3], 2, view=V((0, 0, 100, 10)))
    assert isinstance(seen, P) and seen.tolerance == path.tolerance
    inside = [d for d in full.to_polygons() if d[:, 0].max() <= 100]
    assert len(full.to_polygons()) == 101  # 0..5 (2 into the first dash), then 8..15, ...
    got = seen.to_polygons()
    # the full walk's dashes inside, then the one the edge at x = 100 cuts
    assert len(got) == len(inside) + 1
    for a, b in zip(got, inside):
        np.testing.assert_allclose(a, b, atol=1e-9)
    np.testing.assert_allclose(got[-1], [[98, 5], [100, 5]], atol=1e-9)
    # a pattern far too fine for the whole line is cut where it is seen
    far = line(-1e9, 1e9, 50.5).dash([10, 10], view=V((0, 0, 100, 100)))
    starts = sorted(d[0, 0] for d in far.to_polygons())
    np.testing.assert_allclose(starts, [0, 20, 40, 60, 80, 100], atol=1e-6)
    assert path.dash([]).to_polygons()[0].tolist() == [[0, 5], [1000, 5]]  # no list: a copy


def test_culled_curves_fill_the_same_pixels_with_fewer_points():
    view = V((-4, -4, 68, 68))

    def blob(culled):
        path = P()
        if culled:
            path.cull_curves(view)
        # a cubic reaching a million pixels out and back, then closed
        return path.move_to(8, 32).cubic_to(8, -2e6, 2e6, 2e6, 56, 32).line_to(8, 56).close()

    full, cut = blob(False), blob(True)
    n_full = sum(len(c) for c in full.to_polygons())
    n_cut = sum(len(c) for c in cut.to_polygons())
    assert n_cut < n_full / 10, (n_cut, n_full)
    a, b = softrast.Canvas(64, 64), softrast.Canvas(64, 64)
    a.fill(full, "navy")
    b.fill(cut, "navy")
    assert (a.image[..., 3] > 0).sum() > 500  # the curve crosses the canvas
    assert np.abs(a.image.astype(int) - b.image).max() <= 2  # the chords of the halves differ
    # cull_curves(None) turns it off again, and returns the path
    again = P()
    assert again.cull_curves(view) is again and again.cull_curves(None) is again
    again.move_to(8, 32).cubic_to(8, -2e6, 2e6, 2e6, 56, 32).line_to(8, 56).close()
    assert sum(len(c) for c in again.to_polygons()) == n_full


def test_dashed_stroke_of_a_line_far_larger_than_the_canvas():
    # Canvas.stroke dashes within the image grown by the stroke's reach:
    # a 2e9 px line draws the dashes seen, at the phase of the whole walk
    # (refused before: 200000001 dashes).
    far = softrast.Canvas(120, 20, background="white")
    far.stroke(line(-1e9, 1e9, 10.5), "black", width=3, dashes=[10, 10])
    near = softrast.Canvas(120, 20, background="white")
    near.stroke(line(-20, 140, 10.5), "black", width=3, dashes=[10, 10])
    assert np.abs(far.image.astype(int) - near.image).max() <= 1
    assert tuple(far.image[10, 5]) == (0, 0, 0, 255) and tuple(far.image[10, 15]) == (255,) * 4
    # under a transform the view is in pixels: 1024 x wider, 1/1024 dashes
    scaled = softrast.Canvas(120, 20, background="white")
    scaled.scale(1024, 1)
    scaled.stroke(line(-2.0 ** 20, 2.0 ** 20, 10.5), "black", width=3,
                  dashes=[10 / 1024, 10 / 1024])
    # 2**30 mod 20 = 4: the pattern's phase at x is that of a walk from -4
    phase = softrast.Canvas(120, 20, background="white")
    phase.stroke(line(-24, 140, 10.5), "black", width=3, dashes=[10, 10])
    assert np.abs(scaled.image.astype(int) - phase.image).max() <= 1
    assert tuple(scaled.image[10, 2]) == (0, 0, 0, 255) and tuple(scaled.image[10, 10]) == (255,) * 4


def test_solid_stroke_far_larger_than_the_canvas():
    far = softrast.Canvas(40, 20, background="white")
    far.stroke(line(-1e12, 1e12, 10), "red", width=4, cap="square")
    assert (far.image[8:12] == (255, 0, 0, 255)).all()
    assert (far.image[:8] == 255).all() and (far.image[12:] == 255).all()
