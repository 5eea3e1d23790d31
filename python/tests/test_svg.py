"""softrast.render_svg: the same pixels as `softrast svg`, the document
from a path or from memory, errors naming what is wrong, and the reader's
warnings through the warnings module."""

import array
import gzip
import os
import pathlib
import subprocess
import warnings
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
import softrast
from softrast import _softrast

from conftest import CLI, needs_cli

pytestmark = pytest.mark.skipif(not _softrast.have_svg, reason="this build reads no SVG (expat)")

SVG_DIR = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data" / "svg"
# Drawings without <image> files, so that their bytes render as their path does.
DRAWINGS = ["shapes.svg", "gradients.svg", "markers.svg", "styles.svg", "patterns.svg",
            "masks.svg", "transforms.svg", "dashes.svg"]


def render_quietly(source, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", softrast.SvgWarning)
        return softrast.render_svg(source, **kw)


def command_image(tmp_path, name, args):
    png = tmp_path / (name + ".png")
    subprocess.run([CLI, "svg", str(SVG_DIR / name), *args, "-o", str(png)], check=True,
                   capture_output=True)
    return softrast.read_image(png)


@needs_cli
@pytest.mark.parametrize("name", DRAWINGS + ["images.svg", "svgimage.svg"])
@pytest.mark.parametrize("args, kw", [
    ([], {}),
    (["--size", "96x64"], dict(width=96, height=64)),
    (["--scale", "1.5"], dict(scale=1.5)),
    (["--background", "0.2,0.4,0.6"], dict(background=(0.2, 0.4, 0.6))),
    (["--size", "50x120", "--background", "white"], dict(width=50, height=120,
                                                          background=(1.0, 1.0, 1.0))),
    (["--background", "navy"], dict(background="navy")),
    (["--background", "#1e90ff"], dict(background="#1E90FF")),
    (["--background", "#abc"], dict(background=" #abc ")),
])
def test_same_bytes_as_the_command(tmp_path, name, args, kw):
    ours = render_quietly(str(SVG_DIR / name), **kw)
    theirs = command_image(tmp_path, name, args)
    assert ours.dtype == np.uint8 and ours.shape == theirs.shape
    assert np.array_equal(ours, theirs)


@pytest.mark.parametrize("name", DRAWINGS)
def test_bytes_str_and_path_like_render_as_the_path(name):
    path = SVG_DIR / name
    want = render_quietly(str(path), scale=0.75)
    document = path.read_bytes()
    assert np.array_equal(render_quietly(document, scale=0.75), want)
    assert np.array_equal(render_quietly(bytearray(document), scale=0.75), want)
    assert np.array_equal(render_quietly(memoryview(document), scale=0.75), want)
    # Any bytes-like object: an array of the bytes, a strided view of them.
    assert np.array_equal(render_quietly(np.frombuffer(document, np.uint8), scale=0.75), want)
    assert np.array_equal(render_quietly(array.array("B", document), scale=0.75), want)
    doubled = np.repeat(np.frombuffer(document, np.uint8), 2)[::2]
    assert np.array_equal(render_quietly(memoryview(doubled), scale=0.75), want)
    assert np.array_equal(render_quietly(document.decode("utf-8"), scale=0.75), want)
    assert np.array_equal(render_quietly(path, scale=0.75), want)


@pytest.mark.parametrize("name", DRAWINGS)
def test_gzip_compressed_renders_as_the_document(tmp_path, name):
    """.svgz: known by gzip's first bytes, from memory or from a file."""
    path = SVG_DIR / name
    want = render_quietly(str(path))
    packed = gzip.compress(path.read_bytes())
    assert np.array_equal(render_quietly(packed), want)
    (tmp_path / "drawing.svgz").write_bytes(packed)
    assert np.array_equal(render_quietly(tmp_path / "drawing.svgz"), want)


def test_images_resolve_next_to_the_file_only():
    path = SVG_DIR / "images.svg"
    with warnings.catch_warnings(record=True) as from_file:
        warnings.simplefilter("always")
        on_disk = softrast.render_svg(path)
    assert not [w for w in from_file if "image source" in str(w.message)]
    # From memory, picture.jpg is not read (a warning says so); the data:
    # URIs still are.
    with pytest.warns(softrast.SvgWarning, match=r"^<svg>:\d+: warning: .*image source"):
        in_memory = softrast.render_svg(path.read_bytes())
    assert on_disk.shape == in_memory.shape
    assert not np.array_equal(on_disk, in_memory)
    data_uri_corner = (slice(31, 57), slice(5, 31))
    assert np.array_equal(on_disk[data_uri_corner], in_memory[data_uri_corner])
    assert in_memory[data_uri_corner][..., 3].max() > 0


def test_images_resolve_in_resources_dir():
    for name in ("images.svg", "svgimage.svg"):
        path = SVG_DIR / name
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            on_disk = softrast.render_svg(path)
            in_memory = softrast.render_svg(path.read_bytes(), resources_dir=SVG_DIR)
            as_str = softrast.render_svg(path.read_text(), resources_dir=str(SVG_DIR))
        assert not [w for w in record if "image source" in str(w.message)]
        assert np.array_equal(on_disk, in_memory) and np.array_equal(on_disk, as_str)


def test_resources_dir_is_not_left_and_names_the_document(tmp_path):
    (tmp_path / "inner").mkdir()
    (tmp_path / "picture.jpg").write_bytes((SVG_DIR / "picture.jpg").read_bytes())
    doc = '<svg xmlns="http://www.w3.org/2000/svg" width="8" height="8">' \
          '<image href="{}" width="8" height="8" preserveAspectRatio="none"/></svg>'
    inside = softrast.render_svg(doc.format("picture.jpg"), resources_dir=tmp_path)
    assert inside[..., 3].all()
    with pytest.warns(softrast.SvgWarning, match=r"/inner/<svg>:1: warning: .*image source"):
        above = softrast.render_svg(doc.format("../picture.jpg"), resources_dir=tmp_path / "inner")
    assert not above.any()
    with pytest.raises(ValueError, match=r"^.*/inner/<svg>:1: "):
        softrast.render_svg(b"<svg", resources_dir=tmp_path / "inner")


def test_colors_as_svg_reads_them():
    doc = b'<svg xmlns="http://www.w3.org/2000/svg" width="4" height="2"/>'
    pairs = [("navy", (0.0, 0.0, 128 / 255)), ("#0000FF80", (0.0, 0.0, 1.0, 128 / 255)),
             ("rgba(0, 0, 255, 0.5)", (0.0, 0.0, 1.0, 0.5)), ("#f0f8", (1.0, 0.0, 1.0, 136 / 255)),
             ("hsl(120, 100%, 50%)", (0.0, 1.0, 0.0)), ("transparent", (0.0, 0.0, 0.0, 0.0))]
    for text, numbers in pairs:
        assert np.array_equal(softrast.render_svg(doc, background=text),
                              softrast.render_svg(doc, background=numbers)), text
    assert (softrast.render_svg(doc, background="#0000ff80") == [0, 0, 255, 128]).all()


def test_warnings_come_before_a_failure():
    # <foreignObject> is skipped (a warning), then the use that includes itself
    # fails the render: the warning is not lost.
    doc = b'<svg xmlns="http://www.w3.org/2000/svg" width="8" height="8"><foreignObject/>' \
          b'<use id="u" href="#u"/></svg>'
    with pytest.warns(softrast.SvgWarning, match="'foreignObject'"):
        with pytest.raises(ValueError, match=r"^<svg>:1: .*reference cycle"):
            softrast.render_svg(doc)
    with warnings.catch_warnings():
        warnings.simplefilter("error", softrast.SvgWarning)
        with pytest.raises(softrast.SvgWarning, match="'foreignObject'"):
            softrast.render_svg(doc)


def test_straight_alpha():
    doc = b'<svg xmlns="http://www.w3.org/2000/svg" width="4" height="4">' \
          b'<rect width="4" height="4" fill="#ff0000" fill-opacity="0.5"/></svg>'
    image = softrast.render_svg(doc)
    assert image.shape == (4, 4, 4)
    r, g, b, a = (int(c) for c in image[1, 1])
    assert (r, g, b) == (255, 0, 0) and 126 <= a <= 129


def test_size_scale_and_background():
    doc = b'<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10"/>'
    assert softrast.render_svg(doc).shape == (10, 20, 4)
    assert softrast.render_svg(doc, scale=2.5).shape == (25, 50, 4)
    assert softrast.render_svg(doc, width=7, height=3).shape == (3, 7, 4)
    empty = softrast.render_svg(doc)
    assert not empty.any()
    opaque = softrast.render_svg(doc, background=(0.0, 1.0, 0.0))
    assert (opaque == [0, 255, 0, 255]).all()
    translucent = softrast.render_svg(doc, background=(0, 0, 1, 0.5))
    assert (translucent[..., 2] == 255).all() and (translucent[..., 3] == 128).all()


def test_warnings_go_through_the_warnings_module(capfd):
    path = SVG_DIR / "shapes.svg"
    with pytest.warns(softrast.SvgWarning) as record:
        softrast.render_svg(path)
    messages = [str(w.message) for w in record]
    assert f"{path}:15: warning: unsupported element 'foreignObject' skipped" in messages
    assert len(messages) == len(set(messages))
    assert capfd.readouterr().err == ""
    assert issubclass(softrast.SvgWarning, UserWarning)
    with warnings.catch_warnings():
        warnings.simplefilter("error", softrast.SvgWarning)
        with pytest.raises(softrast.SvgWarning, match="'foreignObject'"):
            softrast.render_svg(path)


def test_malformed_documents_name_file_and_line(tmp_path):
    bad = b'<svg xmlns="http://www.w3.org/2000/svg">\n<g>\n</svg>\n'
    with pytest.raises(ValueError, match=r"^<svg>:3: "):
        softrast.render_svg(bad)
    path = tmp_path / "bad.svg"
    path.write_bytes(bad)
    with pytest.raises(ValueError, match=r"^" + str(path).replace(".", r"\.") + r":3: "):
        softrast.render_svg(path)
    with pytest.raises(ValueError, match=r"^<svg>:\d+: "):
        softrast.render_svg(b"not a document")


@pytest.mark.parametrize("name", ["cycle-a.svg", "cycle-self.svg"])
def test_reference_cycles_are_refused(name):
    # The message names the file where the cycle closes (cycle-a.svg's is
    # cycle-b.svg, the image it includes).
    with pytest.raises(ValueError, match=r"^.*/cycle-[a-z]+\.svg:\d+: .*reference cycle"):
        render_quietly(SVG_DIR / name)


@pytest.mark.parametrize("doc, kw", [
    (b'<svg xmlns="http://www.w3.org/2000/svg" width="1e9" height="10"/>', {}),
    (b'<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10"/>', dict(scale=1e6)),
    (b'<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10"/>',
     dict(width=100000, height=10)),
    (b'<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10"/>',
     dict(width=2**40, height=10)),
])
def test_absurd_sizes_are_refused(doc, kw):
    with pytest.raises(ValueError, match=r"^<svg>:\d+: "):
        softrast.render_svg(doc, **kw)


@pytest.mark.parametrize("attrs, want", [
    ('width="0" height="10"', 'width="0" disables rendering'),
    ('width="10" height="0"', 'height="0" disables rendering'),
    ('viewBox="0 0 0 0"', 'viewBox="0 0 0 0" disables rendering'),
    ('width="-5" height="10"', 'width="-5" is negative'),
])
@pytest.mark.parametrize("kw", [{}, dict(width=16, height=16)])
def test_zero_and_negative_sizes_are_refused(attrs, want, kw):
    # SVG draws nothing of a zero size: no blank image, even of a size asked for.
    doc = ('<svg xmlns="http://www.w3.org/2000/svg" %s><rect width="5" height="5"/></svg>'
           % attrs).encode()
    with pytest.raises(ValueError, match=r"^<svg>:1: " + want):
        softrast.render_svg(doc, **kw)


def test_missing_and_unreadable_files(tmp_path):
    missing = tmp_path / "missing.svg"
    with pytest.raises(FileNotFoundError) as e:
        softrast.render_svg(missing)
    assert e.value.filename == str(missing) and str(missing) in str(e.value)
    with pytest.raises(IsADirectoryError):
        softrast.render_svg(tmp_path)
    if hasattr(os, "mkfifo"):
        fifo = tmp_path / "fifo.svg"
        os.mkfifo(fifo)
        with pytest.raises(OSError, match="not a regular file"):
            softrast.render_svg(fifo)


DOC = b'<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10"/>'


@pytest.mark.parametrize("kw, error, name", [
    (dict(source=12), TypeError, "source"),
    (dict(source=None), TypeError, "source"),
    (dict(width="10", height=10), TypeError, "width"),
    (dict(width=10.0, height=10), TypeError, "width"),
    (dict(width=10, height=True), TypeError, "height"),
    (dict(width=10, height=None), ValueError, "width and height"),
    (dict(width=0, height=10), ValueError, "width"),
    (dict(width=10, height=-1), ValueError, "height"),
    (dict(width=10, height=10, scale=2), ValueError, "scale"),
    (dict(scale="2"), TypeError, "scale"),
    (dict(scale=True), TypeError, "scale"),
    (dict(scale=0), ValueError, "scale"),
    (dict(scale=-1.0), ValueError, "scale"),
    (dict(scale=float("nan")), ValueError, "scale"),
    (dict(scale=float("inf")), ValueError, "scale"),
    (dict(background=b"white"), TypeError, "background"),
    (dict(background="whit"), ValueError, "background: not a CSS color: 'whit'"),
    (dict(background=""), ValueError, "background: not a CSS color: ''"),
    (dict(background="none"), ValueError, "background: not a CSS color: 'none'"),
    (dict(background="url(#g)"), ValueError, "background: not a CSS color"),
    (dict(background="#12345"), ValueError, "background: not a CSS color: '#12345'"),
    (dict(background="red\0blue"), ValueError, "background: not a CSS color"),
    (dict(resources_dir=3), TypeError, "resources_dir"),
    (dict(resources_dir=b"."), TypeError, "resources_dir"),
    (dict(resources_dir="/nonexistent/dir"), NotADirectoryError, "resources_dir"),
    (dict(resources_dir=__file__), NotADirectoryError, "resources_dir"),
    (dict(source=SVG_DIR / "shapes.svg", resources_dir=SVG_DIR), ValueError, "resources_dir"),
    (dict(background=0.5), TypeError, "background"),
    (dict(background=(1, 1)), ValueError, "background"),
    (dict(background=(1, 1, 1, 1, 1)), ValueError, "background"),
    (dict(background=(0, 0, 2)), ValueError, "background"),
    (dict(background=(0, 0, float("nan"))), ValueError, "background"),
])
def test_bad_arguments_name_the_argument(kw, error, name):
    source = kw.pop("source", DOC)
    with pytest.raises(error, match=name):
        softrast.render_svg(source, **kw)


def test_python_threads_render_the_same_bytes():
    """The GIL is released while rendering: drawings rendered by four
    Python threads at once are those rendered one after another."""
    jobs = [(SVG_DIR / name, scale) for name in DRAWINGS for scale in (0.5, 1.25)]
    with warnings.catch_warnings():  # set here: catch_warnings is not thread-safe
        warnings.simplefilter("ignore", softrast.SvgWarning)
        alone = [softrast.render_svg(path, scale=scale) for path, scale in jobs]
        with ThreadPoolExecutor(4) as pool:
            together = list(pool.map(lambda job: softrast.render_svg(job[0], scale=job[1]), jobs))
    for a, b in zip(alone, together):
        assert np.array_equal(a, b)
