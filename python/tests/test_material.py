"""glTF materials through softrast.load: base color factor and texture
(from a data: URI, a GLB's binary chunk, a file next to the model), the
texture transform, alpha in the rgba output, and OBJ textures."""

import base64
import json
import struct

import numpy as np
import pytest
import softrast

from conftest import load_gltf

W = H = 32
# A quad filling the view's middle: x, y in [-1, 1], facing +z.
QUAD = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], np.float32)
QUAD_UV = np.array([[0, 1], [1, 1], [1, 0], [0, 0]], np.float32)   # glTF's: v down
QUAD_FACES = np.array([0, 1, 2, 0, 2, 3], np.uint16)


def png_bytes(tmp_path, image):
    path = tmp_path / "tex.png"
    softrast.write_png(path, image)
    return path.read_bytes()


def halves(top, bottom, size=16):
    """An RGBA texture: its upper rows `top`, its lower rows `bottom`."""
    img = np.empty((size, size, 4), np.uint8)
    img[:size // 2] = top
    img[size // 2:] = bottom
    return img


def gltf_doc(materials, textures=(), images=(), image_bytes=None, primitive_material=0):
    """One quad with TEXCOORD_0 drawn with material `primitive_material`
    (None: no material).  With image_bytes, the data are a GLB's: buffer 0
    has no URI and images[0] is its bufferView 3."""
    data = QUAD.tobytes() + QUAD_UV.tobytes() + QUAD_FACES.tobytes() + b"\0\0"
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
             {"buffer": 0, "byteOffset": 48, "byteLength": 32},
             {"buffer": 0, "byteOffset": 80, "byteLength": 12}]
    buffer = {"byteLength": len(data)}
    if image_bytes is not None:
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(image_bytes)})
        data += image_bytes + b"\0" * (-len(image_bytes) % 4)
        buffer["byteLength"] = len(data)
    else:
        buffer["uri"] = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    prim = {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2}
    if primitive_material is not None:
        prim["material"] = primitive_material
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [prim]}], "materials": list(materials),
        "buffers": [buffer], "bufferViews": views,
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [-1, -1, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                      {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    }
    if textures:
        doc["textures"], doc["images"] = list(textures), list(images)
    return doc, data


def write_glb(path, doc, data):
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    body = (struct.pack("<II", len(js), 0x4E4F534A) + js +
            struct.pack("<II", len(data), 0x004E4942) + data)
    path.write_bytes(b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body)


load = load_gltf


def draw(scene, outputs=("color",), **kw):
    K, R, t = softrast.look_at(eye=(0, 0, 3), target=(0, 0, 0), width=W, height=H, fov_y=0.8)
    return softrast.render(scene, K=K, R=R, t=t, width=W, height=H, outputs=outputs,
                           shading="unlit", **kw)


def mean_rgb(color, rows):
    return color[rows, W // 2 - 4:W // 2 + 4].reshape(-1, color.shape[-1]).mean(0)


TOP, BOTTOM = slice(H // 2 - 6, H // 2 - 2), slice(H // 2 + 2, H // 2 + 6)


def textured(tmp_path, alpha_mode="OPAQUE", factor=(1, 1, 1, 1), transform=None):
    info = {"index": 0}
    if transform:
        info["extensions"] = {"KHR_texture_transform": transform}
    material = {"pbrMetallicRoughness": {"baseColorFactor": list(factor), "baseColorTexture": info,
                                         "metallicFactor": 0.25, "roughnessFactor": 0.75},
                "alphaMode": alpha_mode}
    image = png_bytes(tmp_path, halves((255, 0, 0, 255), (0, 0, 255, 64)))
    uri = "data:image/png;base64," + base64.b64encode(image).decode()
    doc, _ = gltf_doc([material], [{"source": 0}], [{"uri": uri}])
    if transform:
        doc["extensionsUsed"] = ["KHR_texture_transform"]
    path = tmp_path / "quad.gltf"
    path.write_text(json.dumps(doc))
    return path


def test_base_color_texture_and_factors(tmp_path):
    scene = load(textured(tmp_path, factor=(1, 1, 1, 1)))
    inst = scene.instances[0]
    m = inst.material
    assert isinstance(m, softrast.Material)
    assert m.metallic == pytest.approx(0.25) and m.roughness == pytest.approx(0.75)
    assert m.alpha_mode == "opaque" and m.base_color_texture.shape == (16, 16, 4)
    color = draw(scene)["color"]
    top, bottom = mean_rgb(color, TOP), mean_rgb(color, BOTTOM)
    assert top[0] > 200 and top[2] < 40, "the image's top rows (red) show at the quad's top"
    assert bottom[2] > 200 and bottom[0] < 40, "its bottom rows (blue) at the bottom"


def test_base_color_factor_without_texture(tmp_path):
    materials = [{"pbrMetallicRoughness": {"baseColorFactor": [0, 1, 0, 1]}}]
    path = tmp_path / "green.gltf"
    path.write_text(json.dumps(gltf_doc(materials)[0]))
    color = draw(load(path))["color"]
    assert np.array_equal(color[H // 2, W // 2], [0, 255, 0])
    path.write_text(json.dumps(gltf_doc([], primitive_material=None)[0]))
    scene = load(path)
    assert np.array_equal(scene.instances[0].material.base_color, [1, 1, 1, 1])
    assert np.array_equal(draw(scene)["color"][H // 2, W // 2], [255, 255, 255]), \
        "glTF's default material is white"


def test_rgba_alpha(tmp_path):
    opaque = draw(load(textured(tmp_path, "OPAQUE")), outputs=("rgba", "color", "mask"))
    assert opaque["rgba"].shape == (H, W, 4) and opaque["rgba"].dtype == np.uint8
    assert np.array_equal(opaque["rgba"][..., :3], opaque["color"])
    assert np.all(opaque["rgba"][..., 3][~opaque["mask"]] == 0), "nothing drawn: transparent"
    assert np.all(opaque["rgba"][..., 3][opaque["mask"]] == 255), "opaque drops the image's alpha"
    blend = draw(load(textured(tmp_path, "BLEND", factor=(1, 1, 1, 0.5))),
                 outputs=("rgba",))["rgba"]
    assert mean_rgb(blend, TOP)[3] == pytest.approx(128, abs=2), "factor alpha 0.5 times 255"
    assert mean_rgb(blend, BOTTOM)[3] == pytest.approx(32, abs=2), "times the texel's 64"


def test_texture_transform_offset(tmp_path):
    plain = draw(load(textured(tmp_path)))["color"]
    moved = draw(load(textured(tmp_path, transform={"offset": [0, 0.5]})))["color"]
    # v + 1/2 in glTF's frame (v down) moves the image up by half: the
    # quad's top half now reads the image's bottom (blue).
    assert mean_rgb(plain, TOP)[0] > 200 and mean_rgb(moved, TOP)[2] > 200


def test_glb_image_in_buffer_view_and_file_image(tmp_path):
    reference = draw(load(textured(tmp_path)))["color"]
    material = {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}
    image = png_bytes(tmp_path, halves((255, 0, 0, 255), (0, 0, 255, 64)))
    doc, data = gltf_doc([material], [{"source": 0}], [{"bufferView": 3, "mimeType": "image/png"}],
                         image_bytes=image)
    write_glb(tmp_path / "quad.glb", doc, data)
    assert np.array_equal(draw(load(tmp_path / "quad.glb"))["color"], reference)
    doc, _ = gltf_doc([material], [{"source": 0}], [{"uri": "tex%20file.png"}])
    (tmp_path / "tex file.png").write_bytes(image)
    (tmp_path / "files.gltf").write_text(json.dumps(doc))
    assert np.array_equal(draw(load(tmp_path / "files.gltf"))["color"], reference)


def test_load_obj_keeps_its_texture(tmp_path):
    png_bytes(tmp_path, halves((255, 0, 0, 255), (0, 0, 255, 255)))
    (tmp_path / "quad.mtl").write_text("newmtl m\nKd 1 1 1\nmap_Kd tex.png\n")
    (tmp_path / "quad.obj").write_text(
        "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3 4/4\n")
    scene = softrast.load(tmp_path / "quad.obj")
    assert scene.instances[0].mesh.texture is not None
    color = draw(scene)["color"]
    assert mean_rgb(color, TOP)[0] > 200 and mean_rgb(color, BOTTOM)[2] > 200


def one_material(tmp_path, **pbr):
    """The quad with one untextured material of the given glTF members."""
    material = {"pbrMetallicRoughness": {k: v for k, v in pbr.items() if k != "emissiveFactor"}}
    if "emissiveFactor" in pbr:
        material["emissiveFactor"] = pbr["emissiveFactor"]
    path = tmp_path / "material.gltf"
    path.write_text(json.dumps(gltf_doc([material])[0]))
    return load(path)


def test_pbr_shading_draws_the_geometry_pass_faces_and_the_factors(tmp_path):
    red = one_material(tmp_path, baseColorFactor=[0.8, 0.05, 0.05, 1], metallicFactor=0,
                       roughnessFactor=0.6)
    K, R, t = softrast.look_at(eye=(0.5, 0.4, 3), target=(0, 0, 0), width=W, height=H, fov_y=0.8)
    args = dict(K=K, R=R, t=t, width=W, height=H)
    out = softrast.render(red, outputs=("rgba", "color", "mask", "depth"), shading="pbr",
                          background=(0.2, 0.4, 0.6), **args)
    lit = softrast.render(red, outputs=("color", "mask", "depth"), **args)
    assert out["mask"].sum() > 200
    assert np.array_equal(out["mask"], lit["mask"]) and np.array_equal(out["depth"], lit["depth"])
    assert np.array_equal(out["rgba"][..., 3], np.where(out["mask"], 255, 0)), \
        "the color pass covers exactly the geometry pass's pixels"
    assert np.all(out["color"][~out["mask"]] == [51, 102, 153]), "the background elsewhere"
    inside = out["color"][out["mask"]].astype(int)
    assert np.all(inside[:, 0] > inside[:, 1] + 30), "red base color"
    assert not np.array_equal(out["color"], lit["color"]), "not the headlight look"
    for threads in (1, 3):
        again = softrast.render(red, outputs=("rgba",), shading="pbr", background=(0.2, 0.4, 0.6),
                                threads=threads, **args)
        assert np.array_equal(again["rgba"], out["rgba"]), f"the same bytes on {threads} threads"
    glowing = one_material(tmp_path, baseColorFactor=[0, 0, 0, 1], emissiveFactor=[1, 1, 1])
    dark = one_material(tmp_path, baseColorFactor=[0, 0, 0, 1])
    assert glowing.instances[0].material.emissive.tolist() == [1, 1, 1]
    bright = softrast.render(glowing, outputs=("color",), shading="pbr", **args)["color"]
    black = softrast.render(dark, outputs=("color",), shading="pbr", **args)["color"]
    m = out["mask"]
    assert bright[m].min() > 200 and black[m].max() < 60, "emissive is drawn"
    glowing.instances[0].material.emissive_strength = 0.0
    off = softrast.render(glowing, outputs=("color",), shading="pbr", **args)["color"]
    assert np.array_equal(off, black), "a strength of 0 is no emission, not the default 1"
    metal = softrast.render(one_material(tmp_path, baseColorFactor=[0.8, 0.05, 0.05, 1],
                                         metallicFactor=1, roughnessFactor=0.6),
                            outputs=("color",), shading="pbr", **args)["color"]
    assert np.abs(metal[m].astype(int) - out["color"][m]).max() > 10, "metallic is drawn"


def test_material_arguments():
    m = softrast.Material(base_color=(1, 0, 0, 1), metallic=0.0, roughness=0.3)
    assert m.alpha_mode == "opaque" and m.base_color.dtype == np.float32
    for kw, name in [({"metallic": 1.5}, "metallic"), ({"roughness": -1}, "roughness"),
                     ({"base_color": (1, 1, 1)}, "base_color"),
                     ({"emissive": (np.nan, 0, 0)}, "emissive")]:
        with pytest.raises(ValueError, match=name):
            softrast.Material(**kw)
    with pytest.raises(TypeError, match="base_color_texture"):
        softrast.Material(base_color_texture=np.zeros((4, 4, 4), np.float32))
    with pytest.raises(TypeError, match="material"):
        softrast.Instance(softrast.Mesh(QUAD, QUAD_FACES.reshape(-1, 3).astype(np.int32)),
                          material="red")
