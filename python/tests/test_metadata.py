"""Scene.metadata: what a glTF file says about itself (sr_scene.metadata),
for datasets that keep the licence and authors of their models: the
asset's copyright and generator, the KHR_xmp_json_ld packet the asset
references as the file gives it, and its licence and authorship
properties as text (tests/data/gltf, which test_gltf_metadata.c and
test_cli.c read too)."""

import json
import os

import pytest
import softrast

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "gltf")


def test_load_gives_the_assets_metadata_and_xmp_packet():
    scene = softrast.load(os.path.join(DATA, "xmp_metadata.gltf"))
    m = scene.metadata
    assert m["version"] == "2.0" and m["min_version"] is None
    assert m["generator"] == "tests/data/gltf (written by hand)"
    assert m["copyright"] == "2026 Ada Example, CC BY 4.0"
    assert m["xmp_packet"] == 0
    with open(os.path.join(DATA, "xmp_metadata.gltf"), encoding="utf-8") as f:
        doc = json.load(f)
    # the packet as the file gives it (the asset's, not the mesh's)
    assert m["xmp"] == doc["extensions"]["KHR_xmp_json_ld"]["packets"][0]
    assert m["xmp"]["dc:creator"] == {"@list": ["Ada Example", "Bo Sample <bo@example.org>"]}
    assert m["xmp_properties"] == {
        "dc:title": "Corner triangle [en-us], Triangolo d'angolo [it-it]",
        "dc:creator": "Ada Example, Bo Sample <bo@example.org>",
        "dc:rights": "CC BY 4.0",
        "xmpRights:UsageTerms": 'Attribution required: "Corner triangle" by Ada Example',
        "xmpRights:Marked": "true",
    }
    # posing again keeps it; a scene made by hand has none
    assert scene.pose().metadata == m
    assert softrast.Scene().metadata == {}


def test_a_reference_to_no_packet_keeps_the_rest_and_the_model():
    with pytest.warns(softrast.SoftrastWarning, match="/asset/extensions/KHR_xmp_json_ld/packet"):
        scene = softrast.load(os.path.join(DATA, "xmp_bad_packet.gltf"))
    m = scene.metadata
    assert m["xmp"] is None and m["xmp_packet"] is None and m["xmp_properties"] == {}
    assert m["copyright"] == "2026 Ada Example, CC BY 4.0"
    assert len(scene.instances) == 1


def test_other_formats_have_no_metadata(tmp_path):
    path = tmp_path / "t.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    assert softrast.load(path).metadata == {}


@pytest.mark.parametrize("asset", [{"copyright": 7}, {"generator": ["x"]}])
def test_a_copyright_or_generator_that_is_not_text_is_left_out(tmp_path, asset):
    with open(os.path.join(DATA, "xmp_metadata.gltf"), encoding="utf-8") as f:
        doc = json.load(f)
    doc["asset"].update(asset)
    path = tmp_path / "m.gltf"
    path.write_text(json.dumps(doc))
    key = next(iter(asset))
    with pytest.warns(softrast.SoftrastWarning, match=f"/asset/{key}: not a string, left out"):
        m = softrast.load(path).metadata
    assert m[key] is None
    assert m["xmp_packet"] == 0
