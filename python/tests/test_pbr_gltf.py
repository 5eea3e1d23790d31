"""shading="pbr" on loaded glTF files as softrast render draws them: the
file's cameras, alpha modes (mask, blend sorted back to front), every
texture of the material (normal maps with generated tangents, emissive,
occlusion, metallic-roughness), image-based light and the key light's
shadow; and the same pictures as the command's for the file's camera."""

import os
import subprocess

import numpy as np
import pytest
import softrast

import gltf_build as gb
from conftest import load_gltf

BACKGROUND = (0x1d / 255, 0x22 / 255, 0x30 / 255)   # softrast render's default
CLI = os.environ.get("SR_CLI")


def mat(color=(0.8, 0.8, 0.8, 1.0), metallic=0.0, roughness=0.6, **extra):
    m = {"pbrMetallicRoughness": {"baseColorFactor": list(color), "metallicFactor": metallic,
                                  "roughnessFactor": roughness}}
    m.update(extra)
    return m


load = load_gltf


def front(scene, w=48, h=48, **kw):
    """The scene from (0, 0, 3) looking down -z, y up."""
    K, R, t = softrast.look_at(eye=(0, 0, 3), target=(0, 0, 0), width=w, height=h, fov_y=0.9)
    kw.setdefault("outputs", ("color",))
    return softrast.render(scene, K=K, R=R, t=t, width=w, height=h, shading="pbr",
                           background=BACKGROUND, **kw)


def solid(rgba, size=8):
    return np.tile(np.asarray(rgba, np.uint8), (size, size, 1))


def halves(top, bottom, size=16):
    img = solid(top, size)
    img[size // 2:] = bottom
    return img


def save(name, image):
    out = os.environ.get("SR_TEST_OUT")
    if out:
        softrast.write_png(os.path.join(out, name), image)


def test_file_cameras(tmp_path):
    path = gb.write(tmp_path / "cam.gltf", [(gb.box((0, 0, 0), 1.0), 0)], [mat()],
                    camera=((2.0, 1.5, 3.0), (0, 0, 0), 0.7))
    scene = load(path)
    assert len(scene.cameras) == 1
    cam = scene.cameras[0]
    assert isinstance(cam, softrast.Camera) and cam.type == "perspective"
    assert cam.yfov == pytest.approx(0.7) and cam.znear == pytest.approx(0.05)
    K = cam.intrinsics(64, 48)
    assert K[1, 1] == pytest.approx(24 / np.tan(0.35)) and K[0, 0] == K[1, 1]
    assert K[0, 2] == 31.5 and K[1, 2] == 23.5
    # The eye maps to the camera's origin and the target lies ahead on the axis.
    assert np.allclose(cam.R @ np.array([2.0, 1.5, 3.0]) + cam.t, 0, atol=1e-5)
    ahead = cam.R @ np.zeros(3) + cam.t
    assert ahead[2] > 0 and np.allclose(ahead[:2], 0, atol=1e-5)
    # camera= is the same as its K, R, t; a list of cameras is a batch.
    a = softrast.render(scene, camera=cam, width=64, height=48, outputs=("depth",))
    b = softrast.render(scene, K=K, R=cam.R, t=cam.t, near=cam.znear, width=64, height=48,
                        outputs=("depth",))
    assert np.array_equal(a["depth"], b["depth"]) and np.isfinite(a["depth"]).sum() > 300
    batch = softrast.render(scene, camera=[cam, cam], width=64, height=48, outputs=("depth",))
    assert batch["depth"].shape == (2, 48, 64) and np.array_equal(batch["depth"][1], a["depth"])
    with pytest.raises(TypeError, match="camera"):
        softrast.render(scene, camera=cam, K=K, R=cam.R, t=cam.t, width=8, height=8)
    with pytest.raises(TypeError, match="camera"):
        softrast.render(scene, camera="front", width=8, height=8)
    assert softrast.load(path).cameras[0].index == 0


def test_mask_cuts_out_and_blend_mixes(tmp_path):
    # A quad whose upper half is opaque red and lower half red at alpha 64/255.
    tex = {"baseColorTexture": {"index": 0}}
    masked = mat(alphaMode="MASK", alphaCutoff=0.5)
    masked["pbrMetallicRoughness"].update(tex)
    path = gb.write(tmp_path / "mask.gltf", [(gb.quad((0, 0, 0), 2.0), 0)], [masked],
                    images=[halves((255, 0, 0, 255), (255, 0, 0, 64))])
    out = front(load(path), outputs=("color", "rgba", "mask"))
    save("pbr_mask.png", out["color"])
    bg = np.round(np.array(BACKGROUND) * 255).astype(np.uint8)
    upper, lower = out["color"][14:22, 18:30], out["color"][27:34, 18:30]
    assert np.all(out["mask"][27:34, 18:30]), "the geometry outputs still see the quad"
    assert np.all(lower == bg), "alpha 0.25 < cutoff 0.5: cut out, the background shows"
    assert np.all(out["rgba"][27:34, 18:30, 3] == 0)
    assert np.all(upper[..., 0] > 100) and np.all(upper[..., 0] > upper[..., 2] + 60)

    # A half-transparent red quad in front of an opaque blue one, listed
    # first: blended after it, over it.
    prims = [(gb.quad((0, 0, 0.5), 1.6), 0), (gb.quad((0, 0, 0), 2.0), 1)]
    red = mat((1, 0, 0, 0.5), alphaMode="BLEND")
    path = gb.write(tmp_path / "blend.gltf", prims, [red, mat((0, 0, 1, 1))])
    mixed = front(load(path))["color"].astype(int)
    path = gb.write(tmp_path / "red.gltf", prims[:1], [mat((1, 0, 0, 1))])
    only_red = front(load(path))["color"].astype(int)
    path = gb.write(tmp_path / "blue.gltf", [(prims[1][0], 0)], [mat((0, 0, 1, 1))])
    only_blue = front(load(path))["color"].astype(int)
    save("pbr_blend.png", mixed.astype(np.uint8))
    c = (slice(20, 28), slice(20, 28))
    # Blending happens on the encoded values: half of each.
    assert np.abs(mixed[c] - (only_red[c] + only_blue[c]) / 2).max() <= 2
    assert mixed[c][..., 0].min() > 40 and mixed[c][..., 2].min() > 40


def test_blend_sorted_back_to_front(tmp_path):
    # Two half-transparent quads: whichever order the file lists them in,
    # the nearer (green) is blended last, over the farther (red).
    near, far = (gb.quad((0, 0, 0.5), 1.6), 0), (gb.quad((0, 0, 0), 2.0), 1)
    mats = [mat((0, 1, 0, 0.5), alphaMode="BLEND"), mat((1, 0, 0, 0.5), alphaMode="BLEND")]
    a = front(load(gb.write(tmp_path / "a.gltf", [near, far], mats)))["color"]
    b = front(load(gb.write(tmp_path / "b.gltf", [(far[0], 0), (near[0], 1)], mats[::-1])))["color"]
    assert np.array_equal(a, b)
    c = a[24, 24].astype(int)
    assert c[1] > c[0] > 0, "green over red: green dominates"


def tilted_normal_map(dx):
    n = np.array([dx, 0.0, 1.0])
    n /= np.linalg.norm(n)
    return solid(list(np.round((n + 1) / 2 * 255).astype(np.uint8)) + [255])


def test_normal_map_lights_from_the_right_side(tmp_path):
    # The key light comes from the viewer's upper left: a normal map that
    # turns the surface towards the left is brighter, towards the right
    # darker.  The file has no tangents: they are generated.
    def quad_with(dx):
        m = mat()
        if dx is not None:
            m["normalTexture"] = {"index": 0}
        images = [tilted_normal_map(dx)] if dx is not None else []
        path = gb.write(tmp_path / f"n{dx}.gltf", [(gb.quad((0, 0, 0), 2.0), 0)], [m], images)
        return front(load(path))["color"][18:30, 18:30].astype(float).mean()
    left, flat, right = quad_with(-0.6), quad_with(None), quad_with(0.6)
    # (Brighter is near the tone curve's shoulder: a smaller step up.)
    assert left > flat + 2 and flat > right + 10, (left, flat, right)
    assert abs(quad_with(0.0) - flat) < 1.5, "a flat normal map changes nothing"


def test_emissive_occlusion_and_metallic_roughness_textures(tmp_path):
    def draw(images, **extra):
        m = mat((0.5, 0.5, 0.5, 1), **{k: v for k, v in extra.items() if k != "pbr"})
        m["pbrMetallicRoughness"].update(extra.get("pbr", {}))
        path = gb.write(tmp_path / "t.gltf", [(gb.quad((0, 0, 0), 2.0), 0)], [m], images)
        return front(load(path))["color"].astype(int)
    plain = draw([])
    glow = draw([halves((255, 0, 0, 255), (0, 0, 0, 255))], emissiveTexture={"index": 0},
                emissiveFactor=[1, 1, 1])
    assert glow[16, 24, 0] > plain[16, 24, 0] + 60, "the emissive image's red top glows"
    assert np.abs(glow[30, 24] - plain[30, 24]).max() <= 1, "its black bottom adds nothing"
    dark = draw([solid((0, 0, 0, 255))], occlusionTexture={"index": 0})
    assert dark[24, 24].sum() < plain[24, 24].sum(), "occlusion darkens the ambient light"
    # Metallic from the blue channel: a full metal of gray base color.
    metal = draw([solid((0, 255, 255, 255))],
                 pbr={"metallicRoughnessTexture": {"index": 0}, "metallicFactor": 1.0,
                      "roughnessFactor": 1.0})
    assert np.abs(metal[24, 24] - plain[24, 24]).max() > 10


def write_hdr(path, rgb, w=16, h=8):
    """An uncompressed Radiance picture of one color."""
    rgb = np.asarray(rgb, np.float64)
    e = int(np.floor(np.log2(rgb.max()))) + 1
    mant = np.round(rgb / 2.0 ** e * 256).astype(np.uint8)
    px = bytes(list(mant) + [e + 128]) * (w * h)
    path.write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" +
                     f"-Y {h} +X {w}\n".encode() + px)
    return path


def test_environment(tmp_path):
    path = gb.write(tmp_path / "q.gltf", [(gb.quad((0, 0, 0), 2.0), 0)], [mat((1, 1, 1, 1))])
    scene = load(path)
    red = front(scene, environment=write_hdr(tmp_path / "red.hdr", (1.0, 0.02, 0.02)),
                environment_intensity=1.0)["color"][24, 24].astype(int)
    blue = front(scene, environment=write_hdr(tmp_path / "blue.hdr", (0.02, 0.02, 1.0)),
                 environment_intensity=1.0)["color"][24, 24].astype(int)
    hemi = front(scene, environment="hemisphere")["color"][24, 24].astype(int)
    studio = front(scene, environment="studio")["color"][24, 24].astype(int)
    default = front(scene)["color"][24, 24].astype(int)
    assert red[0] > red[2] + 30 and blue[2] > blue[0] + 30, (red, blue)
    assert np.abs(studio - hemi).max() > 3
    assert (default == studio).all(), "the default light is the studio, as softrast render's"
    with pytest.raises(FileNotFoundError, match="environment"):
        front(scene, environment=tmp_path / "missing.hdr")
    with pytest.raises(ValueError, match="environment_intensity"):
        front(scene, environment="studio", environment_intensity=0)
    with pytest.raises(ValueError, match="pbr"):
        softrast.render(scene, K=np.eye(3), R=np.eye(3), t=(0, 0, 3), width=4, height=4,
                        environment="studio")


def shadow_scene(tmp_path):
    return gb.write(tmp_path / "shadow.gltf",
                    [(gb.quad((0, 0, 0), 4.0, "y", uv=False), 0), (gb.box((0, 0.6, 0), 0.8), 1)],
                    [mat(), mat((0.8, 0.2, 0.1, 1))], camera=((2.5, 2.2, 3.0), (0, 0.3, 0), 0.8))


def test_shadows_darken_the_ground(tmp_path):
    scene = load(shadow_scene(tmp_path))
    args = dict(camera=scene.cameras[0], width=96, height=72, shading="pbr",
                outputs=("color", "instance_id"))
    lit = softrast.render(scene, **args)
    shaded = softrast.render(scene, shadows=True, **args)
    save("pbr_shadow.png", shaded["color"])
    ground = lit["instance_id"] == 0
    darker = (lit["color"].astype(int).sum(-1) - shaded["color"].astype(int).sum(-1)) > 30
    assert (darker & ground).sum() > 60, "a shadow falls on the ground"
    # The key light comes from the viewer's upper left: the shadow falls to
    # the box's right on the image.
    cols = np.nonzero(darker & ground)[1]
    box_cols = np.nonzero(lit["instance_id"] == 1)[1]
    assert cols.mean() > box_cols.mean()
    assert np.array_equal(softrast.render(scene, shadows=True, threads=1, **args)["color"],
                          shaded["color"]), "the same bytes on one thread"


def materials_scene(tmp_path):
    """A floor, a normal-mapped box with an emissive image (no tangents in
    the file), a masked and a blended quad, and a camera."""
    boxy = mat((0.6, 0.6, 0.7, 1), normalTexture={"index": 0}, emissiveTexture={"index": 1},
               emissiveFactor=[1, 1, 1])
    cut = mat((1, 1, 1, 1), alphaMode="MASK", doubleSided=True)
    cut["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 2}
    glass = mat((0.2, 0.4, 1.0, 0.4), alphaMode="BLEND", doubleSided=True)
    box = gb.box((0.4, 0.5, -0.4), 0.8)
    box["uvs"] = np.tile(np.array([[0, 1], [1, 1], [1, 0], [0, 0]], np.float32), (6, 1))
    return gb.write(tmp_path / "materials.gltf",
                    [(gb.quad((0, 0, 0), 4.0, "y", uv=False), 0), (box, 1),
                     (gb.quad((-0.9, 0.6, 0.3), 0.9), 2), (gb.quad((0.2, 0.5, 0.9), 0.8), 3)],
                    [mat(), boxy, cut, glass],
                    images=[tilted_normal_map(0.5), halves((40, 40, 0, 255), (0, 0, 0, 255)),
                            halves((0, 200, 0, 255), (0, 200, 0, 30))],
                    camera=((2.0, 2.0, 3.2), (0, 0.4, 0), 0.8))


@pytest.mark.skipif(not CLI, reason="SR_CLI (the softrast command) is not set")
@pytest.mark.parametrize("shadows", [False, True])
@pytest.mark.parametrize("make", [shadow_scene, materials_scene])
def test_file_camera_matches_the_command(tmp_path, shadows, make):
    # The command's --camera-index picture of the same file, without
    # antialiasing (render has none): the same pixels, within 2 codes on
    # all but 0.5% of them (rounding of the model's world transform, which
    # the command applies to the vertices and render in the program).
    path = make(tmp_path)
    png = tmp_path / "cli.png"
    subprocess.run([CLI, "render", str(path), "--camera-index", "0", "--aa", "none",
                    "--size", "160x120", "--shadows", "on" if shadows else "off", "-o", str(png)],
                   check=True, capture_output=True)
    scene = load(path)
    ours = softrast.render(scene, camera=scene.cameras[0], width=160, height=120, shading="pbr",
                           shadows=shadows, background=BACKGROUND, outputs=("color",))["color"]
    theirs = softrast.read_image(png)[..., :3]
    save(f"pbr_vs_cli_{make.__name__}_{shadows}.png", np.concatenate([ours, theirs], 1))
    diff = np.abs(ours.astype(int) - theirs).max(-1)
    assert (diff > 2).mean() <= 0.005, f"{(diff > 2).mean():.2%} of the pixels differ"


def test_own_mesh_with_a_material(tmp_path):
    # A Mesh of one's own: the Material's base color times the vertex
    # colors, its alpha mode, and back faces culled unless double-sided.
    v = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], np.float32)
    f = np.array([[0, 1, 2], [0, 2, 3]], np.int32)
    mesh = softrast.Mesh(v, f, normals=np.tile(np.float32([0, 0, 1]), (4, 1)))
    white = front(softrast.Instance(mesh, material=softrast.Material(metallic=0, roughness=0.6)))
    red = front(softrast.Instance(mesh, material=softrast.Material((1, 0, 0, 1), metallic=0,
                                                                  roughness=0.6)))
    c = red["color"][24, 24].astype(int)
    assert c[0] > c[1] + 60 and white["color"][24, 24, 1] > 100
    flipped = softrast.Mesh(v, f[:, ::-1].copy(), normals=-mesh.normals)
    bg = np.round(np.array(BACKGROUND) * 255).astype(np.uint8)
    one_sided = front(softrast.Instance(flipped, material=softrast.Material()))
    assert np.all(one_sided["color"][24, 24] == bg), "its back faces the camera: culled"
    two_sided = front(softrast.Instance(flipped, material=softrast.Material(double_sided=True)))
    assert np.any(two_sided["color"][24, 24] != bg)
    half = front(softrast.Instance(mesh, material=softrast.Material((1, 1, 1, 0.3),
                                                                   alpha_mode="mask")))
    assert np.all(half["color"][24, 24] == bg), "alpha 0.3 under the cutoff 0.5: cut out"


def test_pickled_scene_keeps_the_files_materials(tmp_path):
    # A loaded scene goes to Dask workers pickled: the file's materials
    # are read again there, so the picture is the same.
    import pickle
    scene = load(materials_scene(tmp_path))
    args = dict(camera=scene.cameras[0], width=64, height=48, shading="pbr", outputs=("color",))
    again = pickle.loads(pickle.dumps(scene))
    assert np.array_equal(softrast.render(again, **args)["color"],
                          softrast.render(scene, **args)["color"])
    path = tmp_path / "materials.gltf"
    data = pickle.dumps(scene)
    path.rename(tmp_path / "moved.gltf")
    with pytest.warns(UserWarning, match="materials are not kept"):
        lost = pickle.loads(data)
    assert softrast.render(lost, **args)["color"].shape == (48, 64, 3), "drawn from its Meshes"


def test_layer_extensions_reach_the_material_and_the_picture(tmp_path):
    # KHR_materials_clearcoat and _sheen (and ior, specular) come with the
    # loaded Material's factors and draw as softrast render does; a
    # Material made in Python carries them too, the defaults drawing as
    # without them.
    plain = mat((0.7, 0.1, 0.1, 1), roughness=1.0)
    coated = mat((0.7, 0.1, 0.1, 1), roughness=1.0,
                 extensions={"KHR_materials_clearcoat": {"clearcoatFactor": 1.0,
                                                         "clearcoatRoughnessFactor": 0.05},
                             "KHR_materials_ior": {"ior": 1.8}})
    pictures = []
    for i, m in enumerate((plain, coated)):
        path = gb.write(tmp_path / f"c{i}.gltf", [(gb.quad((0, 0, 0), 2.0), 0)], [m], [])
        scene = load(path)
        pictures.append(front(scene)["color"].astype(int))
        got = scene.instances[0].material
        if i == 1:
            assert got.clearcoat == 1.0 and abs(got.ior - 1.8) < 1e-6
            assert abs(got.clearcoat_roughness - 0.05) < 1e-6
            assert got.specular == 1.0 and list(got.specular_color) == [1, 1, 1]
    assert np.abs(pictures[1] - pictures[0]).max() > 10, "the coat changes the picture"
    m = softrast.Material((0.5, 0.5, 0.5, 1), sheen_color=(1, 1, 1), sheen_roughness=0.5)
    assert m.ior == 1.5 and m.clearcoat == 0.0 and list(m.sheen_color) == [1, 1, 1]
    with pytest.raises(ValueError, match="ior"):
        softrast.Material(ior=0.5)
    with pytest.raises(ValueError, match="clearcoat"):
        softrast.Material(clearcoat=2.0)




def test_anisotropy_and_iridescence_reach_the_material_and_the_picture(tmp_path):
    # KHR_materials_anisotropy and _iridescence come with the loaded
    # Material (the extensions' defaults where the file gives none) and
    # change the picture; set to zero on the Material they draw the plain
    # material's bytes; a Material made in Python carries them too.
    plain = mat((0.8, 0.8, 0.8, 1), metallic=1.0, roughness=0.3)
    film = mat((0.8, 0.8, 0.8, 1), metallic=1.0, roughness=0.3,
               extensions={"KHR_materials_anisotropy": {"anisotropyStrength": 0.7,
                                                        "anisotropyRotation": 0.5},
                           "KHR_materials_iridescence": {"iridescenceFactor": 1.0,
                                                         "iridescenceThicknessMaximum": 500}})
    pictures, scenes = [], []
    for i, m in enumerate((plain, film)):
        path = gb.write(tmp_path / f"f{i}.gltf", [(gb.quad((0, 0, 0), 2.0), 0)], [m], [])
        scenes.append(load(path))
        pictures.append(front(scenes[-1])["color"].astype(int))
    got = scenes[1].instances[0].material
    assert abs(got.anisotropy_strength - 0.7) < 1e-6 and abs(got.anisotropy_rotation - 0.5) < 1e-6
    assert got.iridescence == 1.0 and abs(got.iridescence_ior - 1.3) < 1e-6
    assert got.iridescence_thickness_min == 100.0 and got.iridescence_thickness_max == 500.0
    assert np.abs(pictures[1] - pictures[0]).max() > 10, "the film changes the picture"
    got.anisotropy_strength = 0.0
    got.iridescence = 0.0
    assert np.array_equal(front(scenes[1])["color"].astype(int), pictures[0])
    # A film 0 nm thick is no film, not the extension's default 100 to 400 nm.
    got.iridescence = 1.0
    got.iridescence_thickness_min = got.iridescence_thickness_max = 0.0
    assert np.array_equal(front(scenes[1])["color"].astype(int), pictures[0])
    m = softrast.Material(anisotropy_strength=0.5, iridescence=1.0)
    assert abs(m.iridescence_ior - 1.3) < 1e-6 and m.iridescence_thickness_max == 400.0
    with pytest.raises(ValueError, match="iridescence_ior"):
        softrast.Material(iridescence_ior=0.5)
    with pytest.raises(ValueError, match="anisotropy_strength"):
        softrast.Material(anisotropy_strength=2.0)


def test_transmission_shows_what_is_behind(tmp_path):
    # Clear glass (KHR_materials_transmission, white, smooth) in front of a
    # red and a blue square: it shows each, near the colour the squares
    # have without it (less what the glass reflects, plus its highlight),
    # where an opaque white quad would hide them.
    back = [(gb.quad((-0.5, 0, 0), 1.0), 0), (gb.quad((0.5, 0, 0), 1.0), 1)]
    colors = [mat((1, 0, 0, 1)), mat((0, 0, 1, 1))]
    glass = mat((1, 1, 1, 1), roughness=0.0,
                extensions={"KHR_materials_transmission": {"transmissionFactor": 1}})
    scene = load(gb.write(tmp_path / "glass.gltf", back + [(gb.quad((0, 0, 0.5), 1.6), 2)],
                          colors + [glass]))
    m = scene.instances[-1].material
    assert m.transmission == 1.0 and m.thickness == 0.0 and m.attenuation_distance == 0.0
    assert list(m.attenuation_color) == [1.0, 1.0, 1.0]
    seen = front(scene)["color"].astype(int)
    save("pbr_transmission.png", seen.astype(np.uint8))
    bare = front(load(gb.write(tmp_path / "bare.gltf", back, colors)))["color"].astype(int)
    for x in (14, 34):
        c = (slice(20, 28), slice(x - 3, x + 3))
        assert np.abs(seen[c] - bare[c]).max() <= 24
    assert seen[24, 14, 0] > seen[24, 14, 2] + 80, "red through the glass on the left"
    assert seen[24, 34, 2] > seen[24, 34, 0] + 80, "blue on the right"
    # The same Material with no transmission is the old opaque white.
    m.transmission = 0.0
    opaque = front(scene)["color"].astype(int)
    assert opaque[24, 14].min() > 120 and abs(opaque[24, 14, 0] - opaque[24, 14, 2]) < 20
    with pytest.raises(ValueError, match="transmission"):
        softrast.Material(transmission=1.5)


def test_dispersion_and_diffuse_transmission_reach_the_material_and_the_picture(tmp_path):
    # KHR_materials_dispersion and _diffuse_transmission come with the
    # loaded Material (the color's default white where the file gives
    # none); diffuse transmission changes the picture of a quad the
    # default lights reach from behind too (their rim light), and set to
    # zero on the Material draws the plain material's bytes; a Material
    # made in Python carries them and refuses values out of range.
    plain = mat((0.2, 0.6, 0.1, 1), roughness=0.6)
    leaf = mat((0.2, 0.6, 0.1, 1), roughness=0.6,
               extensions={"KHR_materials_diffuse_transmission": {
                   "diffuseTransmissionFactor": 1.0,
                   "diffuseTransmissionColorFactor": [1.0, 0.2, 0.2]},
                   "KHR_materials_dispersion": {"dispersion": 0.5}})
    pictures, scenes = [], []
    for i, m in enumerate((plain, leaf)):
        path = gb.write(tmp_path / f"l{i}.gltf", [(gb.quad((0, 0, 0), 2.0), 0)], [m], [])
        scenes.append(load(path))
        pictures.append(front(scenes[-1])["color"].astype(int))
    got = scenes[1].instances[0].material
    assert got.diffuse_transmission == 1.0 and abs(got.dispersion - 0.5) < 1e-6
    assert np.allclose(got.diffuse_transmission_color, [1.0, 0.2, 0.2])
    assert scenes[0].instances[0].material.diffuse_transmission == 0.0
    assert list(scenes[0].instances[0].material.diffuse_transmission_color) == [1, 1, 1]
    assert np.abs(pictures[1] - pictures[0]).max() > 10, "diffuse transmission changes it"
    got.diffuse_transmission = 0.0
    got.dispersion = 0.0
    assert np.array_equal(front(scenes[1])["color"].astype(int), pictures[0])
    m = softrast.Material(diffuse_transmission=0.5, diffuse_transmission_color=(1, 0.5, 0),
                          dispersion=2.0)
    assert m.dispersion == 2.0 and list(m.diffuse_transmission_color) == [1.0, 0.5, 0.0]
    assert list(softrast.Material().diffuse_transmission_color) == [1.0, 1.0, 1.0]
    with pytest.raises(ValueError, match="diffuse_transmission"):
        softrast.Material(diffuse_transmission=1.5)
    with pytest.raises(ValueError, match="diffuse_transmission_color"):
        softrast.Material(diffuse_transmission_color=(1, 2, 0))
    with pytest.raises(ValueError, match="dispersion"):
        softrast.Material(dispersion=-1.0)


def test_specular_glossiness_reaches_the_material_and_the_picture(tmp_path):
    # KHR_materials_pbrSpecularGlossiness comes with the loaded Material:
    # its diffuse as base_color (and the diffuse texture as the base color
    # image, not the metallic-roughness fallback's), its specular and
    # glossiness; the picture is the metallic-roughness twin's (metallic
    # 0, roughness 1 - glossiness, base color diffuse (1 - max(specular)),
    # KHR_materials_specular's F0 0.04 color = specular); turning the flag
    # off on the Material draws the fallback; a Material made in Python
    # carries the fields and refuses values out of range.
    diffuse, spec, gloss = (0.2, 0.5, 0.8), (0.3, 0.1, 0.05), 0.7
    sg = mat((1, 0, 0, 1), metallic=1.0, roughness=0.2,
             extensions={"KHR_materials_pbrSpecularGlossiness": {
                 "diffuseFactor": list(diffuse) + [1.0], "specularFactor": list(spec),
                 "glossinessFactor": gloss, "diffuseTexture": {"index": 0}}})
    sg["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 1}
    keep = 1.0 - max(spec)
    twin = mat(tuple(float(np.float32(c) * np.float32(keep)) for c in diffuse) + (1.0,),
               metallic=0.0,
               roughness=float(np.float32(1.0) - np.float32(gloss)),
               extensions={"KHR_materials_specular": {
                   "specularColorFactor": [float(np.float32(c) / np.float32(0.04))
                                           for c in spec]}})
    twin["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    white, red = solid((255, 255, 255, 255)), solid((255, 0, 0, 255))
    scenes = [load(gb.write(tmp_path / f"s{i}.gltf", [(gb.quad((0, 0, 0), 2.0), 0)], [m],
                            [white, red]))
              for i, m in enumerate((sg, twin))]
    got = scenes[0].instances[0].material
    assert got.specular_glossiness and abs(got.glossiness - gloss) < 1e-6
    assert np.allclose(got.base_color, list(diffuse) + [1.0])
    assert np.allclose(got.sg_specular, spec)
    assert got.base_color_texture is not None and got.base_color_texture[0, 0, 1] == 255
    pictures = [front(s)["color"].astype(int) for s in scenes]
    assert np.abs(pictures[0] - pictures[1]).max() <= 1
    got.specular_glossiness = False
    got.base_color = np.array([1, 0, 0, 1], np.float32)
    assert np.abs(front(scenes[0])["color"].astype(int) - pictures[0]).max() > 10
    assert not scenes[1].instances[0].material.specular_glossiness
    m = softrast.Material(specular_glossiness=True, sg_specular=(1, 0.5, 0), glossiness=0.25)
    assert m.specular_glossiness and list(m.sg_specular) == [1.0, 0.5, 0.0]
    assert m.glossiness == 0.25
    with pytest.raises(ValueError, match="sg_specular"):
        softrast.Material(sg_specular=(1, 2, 0))
    with pytest.raises(ValueError, match="glossiness"):
        softrast.Material(glossiness=-0.5)
