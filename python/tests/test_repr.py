"""repr() of the package's objects says what they hold."""

import numpy as np
import softrast

import gltf_build

V = np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 3]], np.float32)
F = np.array([[0, 1, 2]], np.int32)


def test_camera_repr_names_its_lens_and_placement():
    cam = softrast.Camera.perspective((0, 0, 3), (0, 0, 0), yfov=0.8, znear=0.01)
    assert repr(cam) == ("Camera(type='perspective', yfov=0.8, znear=0.01, eye=(0, 0, 3), "
                         "forward=(0, 0, -1))")
    ortho = softrast.Camera.orthographic((2, 0, 0), (0, 0, 0), ymag=1.5)
    assert repr(ortho) == ("Camera(type='orthographic', ymag=1.5, znear=0, eye=(2, 0, 0), "
                           "forward=(-1, 0, 0))")


def test_file_camera_repr_names_its_index_and_node(tmp_path):
    path = tmp_path / "cam.gltf"
    gltf_build.write(path, [(gltf_build.quad((0, 0, 0), 1.0), 0)], [{}],
                     camera=((0, 0, 4), (0, 0, 0), 0.5))
    scene = softrast.load(path)
    text = repr(scene.cameras[0])
    assert text.startswith("Camera(index=0, node=1, type='perspective', yfov=0.5, "), text
    assert "eye=(0, 0, 4), forward=(0, 0, -1))" in text, text


def test_scene_repr_counts_instances_meshes_faces_and_cameras():
    mesh = softrast.Mesh(V, F)
    assert repr(softrast.Scene([mesh])) == "Scene(1 instance of 1 mesh, 1 face drawn, 0 cameras)"
    two = softrast.Scene([mesh, (mesh, np.eye(4)), softrast.Mesh(V, np.tile(F, (4, 1)))],
                         cameras=[softrast.Camera.perspective((0, 0, 3), (0, 0, 0))])
    assert repr(two) == "Scene(3 instances of 2 meshes, 6 faces drawn, 1 camera)"


def test_paint_and_canvas_reprs_say_what_they_hold():
    stops = [(0, "red"), (0.5, "#00ff00"), (1, "blue")]
    assert (repr(softrast.LinearGradient((0, 0), (64, 0.5), stops, spread="reflect"))
            == "LinearGradient(start=(0, 0), end=(64, 0.5), 3 stops, spread='reflect')")
    assert (repr(softrast.RadialGradient((8, 8), 4, stops[:1]))
            == "RadialGradient(center=(8, 8), radius=4, 1 stop, spread='pad')")
    assert (repr(softrast.RadialGradient((8, 8), 4, stops, focal=(6, 7), focal_radius=1,
                                         spread="repeat"))
            == "RadialGradient(center=(8, 8), radius=4, focal=(6, 7), focal_radius=1, "
               "3 stops, spread='repeat')")
    tile = np.zeros((3, 5, 4), np.uint8)
    assert repr(softrast.Pattern(tile, wrap="clamp")) == "Pattern(5x3 image, wrap='clamp')"
    assert repr(softrast.Canvas(640, 480)) == "Canvas(640x480)"
    assert softrast.Canvas.width.__doc__ and softrast.Canvas.height.__doc__
