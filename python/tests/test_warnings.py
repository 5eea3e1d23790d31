"""The readers' warnings as Python warnings: one softrast.SoftrastWarning
per line the reader gives, with the text the softrast tool prints, issued
at the user's call; a filter that makes them errors raises out of the call
and leaves nothing half made."""

import base64
import gc
import json
import os
import struct
import subprocess
import warnings

import pytest
import softrast

from conftest import CLI, needs_cli

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "gltf")
pytestmark = pytest.mark.skipif("gltf" not in softrast.features,
                                reason="this build reads no glTF")


def triangle_gltf(path, **extra):
    """A one-triangle glTF file with `extra` members merged into its JSON."""
    data = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64,"
                            + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteLength": len(data)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    for key, value in extra.items():
        if key == "material":
            doc["meshes"][0]["primitives"][0]["material"] = value
        else:
            doc[key] = value
    with open(path, "w", encoding="utf-8") as f:
        json.dump(doc, f)
    return str(path)


def unknown_extension(tmp_path):
    return triangle_gltf(tmp_path / "ext.gltf", extensionsUsed=["EXT_whatever"])


def textureless_texture(tmp_path):
    # A texture with no source (a KHR_texture_basisu one, say): dropped.
    return triangle_gltf(tmp_path / "tex.gltf", material=0, textures=[{}],
                         materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])


def loaded(path, call=None):
    """(result, [warnings]) of call(path) (softrast.load), every warning kept."""
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        result = (call or softrast.load)(path)
    return result, record


@pytest.mark.parametrize("make, text", [
    (unknown_extension,
     "ext.gltf: warning: not read, the scene is drawn without them: /extensionsUsed/0 "
     "(EXT_whatever)"),
    (textureless_texture,
     "tex.gltf: warning: /textures/0: no PNG or JPEG source, texture dropped"),
    (lambda tmp_path: os.path.join(DATA, "xmp_bad_packet.gltf"),
     "xmp_bad_packet.gltf: warning: /asset/extensions/KHR_xmp_json_ld/packet: "),
])
@pytest.mark.parametrize("call", [softrast.load, softrast.load_mesh])
def test_a_reader_warning_is_a_softrast_warning_at_the_callers_line(tmp_path, make, text, call):
    path = make(tmp_path)
    result, record = loaded(path, call)
    assert result is not None
    assert len(record) == 1, [str(w.message) for w in record]
    w = record[0]
    assert w.category is softrast.SoftrastWarning and issubclass(w.category, UserWarning)
    assert str(w.message).startswith(os.path.dirname(path)) or str(w.message).startswith(path)
    assert text in str(w.message)
    # stacklevel: the line of loaded() that called load, not softrast's own
    assert w.filename == __file__


def test_a_clean_file_gives_no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        scene = softrast.load(os.path.join(DATA, "xmp_metadata.gltf"))
        softrast.load_mesh(os.path.join(DATA, "xmp_metadata.gltf"))
        scene.pose()
    assert len(scene.instances) == 1


def test_a_name_of_an_animation_warns_once(tmp_path):
    # Read at rest, then posed by the name: the file is read once.
    path = triangle_gltf(tmp_path / "anim.gltf", extensionsUsed=["EXT_whatever"])
    with pytest.raises(ValueError, match="no animation named 'walk'"):
        loaded(path, lambda p: softrast.load(p, animation="walk"))
    _, record = loaded(path)
    assert len(record) == 1


@needs_cli
@pytest.mark.parametrize("make", [unknown_extension, textureless_texture])
def test_the_text_is_the_one_the_tool_prints(tmp_path, make):
    path = make(tmp_path)
    _, record = loaded(path)
    run = subprocess.run([CLI, "info", path], capture_output=True, text=True, check=True)
    printed = [line for line in run.stderr.splitlines() if ": warning: " in line]
    assert printed and [str(w.message) for w in record] == printed


def count_objects(kind):
    gc.collect()
    return sum(1 for o in gc.get_objects() if isinstance(o, kind))


def test_an_error_filter_raises_and_keeps_nothing(tmp_path):
    path = textureless_texture(tmp_path)
    before = [count_objects(k) for k in (softrast.Scene, softrast.Instance, softrast.Material)]
    with warnings.catch_warnings():
        warnings.filterwarnings("error", category=softrast.SoftrastWarning)
        for _ in range(20):
            with pytest.raises(softrast.SoftrastWarning, match="no PNG or JPEG source"):
                softrast.load(path)
            with pytest.raises(softrast.SoftrastWarning, match="no PNG or JPEG source"):
                softrast.load_mesh(path)
    after = [count_objects(k) for k in (softrast.Scene, softrast.Instance, softrast.Material)]
    assert after == before
    # The reader is left as it was: the next load reads and warns again.
    scene, record = loaded(path)
    assert len(scene.instances) == 1 and len(record) == 1


def test_an_obj_texture_not_read_is_one_warning(tmp_path):
    (tmp_path / "m.mtl").write_text("newmtl a\nmap_Kd missing.png\n")
    (tmp_path / "m.obj").write_text("mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                    "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
    for call in (softrast.load, softrast.load_mesh):
        _, record = loaded(str(tmp_path / "m.obj"), call)
        assert [w.category for w in record] == [softrast.SoftrastWarning]
        assert "texture not kept" in str(record[0].message)
        assert "missing.png" in str(record[0].message)
        assert record[0].filename == __file__


def test_svg_warnings_are_softrast_warnings():
    assert issubclass(softrast.SvgWarning, softrast.SoftrastWarning)
    with pytest.warns(softrast.SoftrastWarning, match="'foreignObject'"):
        softrast.render_svg(b'<svg xmlns="http://www.w3.org/2000/svg" width="4" '
                            b'height="4"><foreignObject/></svg>')
