"""softrast.features: the optional parts of this build, as the library and
the softrast command name them."""

import subprocess

import softrast
from softrast import _softrast
from conftest import CLI, needs_cli

KNOWN = ("png", "jpeg", "webp", "gltf", "meshopt", "draco", "svg", "svgz", "text", "bidi",
         "assimp")


def test_features_are_known_names_in_order():
    f = softrast.features
    assert isinstance(f, tuple) and all(isinstance(n, str) for n in f)
    assert list(f) == [n for n in KNOWN if n in f]
    assert "png" in f  # libpng is required outside the embedded and wasm builds


def test_features_agree_with_the_flags():
    assert _softrast.have_svg == ("svg" in softrast.features)
    assert _softrast.have_text == ("text" in softrast.features)


@needs_cli
def test_features_are_the_commands():
    out = subprocess.run([CLI, "--version"], capture_output=True, text=True, check=True).stdout
    assert out.splitlines()[1] == "built with: " + " ".join(softrast.features)
