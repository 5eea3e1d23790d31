"""Arrays as numpy users hand them over: other byte orders, layouts and
scalar types give the same bytes as the plain arrays, or an error naming
the argument."""

import numpy as np
import pytest
import softrast

V = np.array([[-1, -1, 3], [1, -1, 3], [0, 1, 3], [1, 1, 4]], np.float64)
F = np.array([[0, 1, 2], [1, 3, 2]], np.int64)
K = np.array([[40.0, 0, 15.5], [0, 40.0, 11.5], [0, 0, 1]])
R, T = np.eye(3), np.zeros(3)
OUTPUTS = ("depth", "triangle_id", "normal", "color")


def render(mesh):
    return softrast.render(mesh, K=K, R=R, t=T, width=32, height=24, outputs=OUTPUTS, threads=1)


def assert_same(a, b):
    for name in OUTPUTS:
        assert np.array_equal(a[name], b[name]), name


@pytest.mark.parametrize("vdtype", ["<f4", ">f4", "<f8", ">f8"])
@pytest.mark.parametrize("fdtype", ["<i4", ">i4", "<i8", ">i8"])
def test_byte_order_of_vertices_and_faces(vdtype, fdtype):
    native = render(softrast.Mesh(V.astype(np.dtype(vdtype).newbyteorder("=")), F))
    assert (native["triangle_id"] >= 0).any()
    assert_same(render(softrast.Mesh(V.astype(vdtype), F.astype(fdtype))), native)


def test_byte_order_of_normals_colors_and_uvs():
    normals = np.tile([0.0, 0.6, -0.8], (4, 1))
    colors = np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], np.float64)
    uvs = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], np.float64)
    texture = np.arange(4 * 4 * 3, dtype=np.uint8).reshape(4, 4, 3) * 5
    native = render(softrast.Mesh(V, F, normals=normals.astype(np.float32), colors=colors,
                                  uvs=uvs, texture=texture))
    swapped = render(softrast.Mesh(V, F, normals=normals.astype(">f4"), colors=colors.astype(">f4"),
                                   uvs=uvs.astype(">f4"), texture=texture))
    assert_same(swapped, native)


@pytest.mark.parametrize("vdtype", [np.float32, np.float64])
@pytest.mark.parametrize("fdtype", [np.int32, np.int64])
@pytest.mark.parametrize("shading", ["lit", "unlit"])
def test_arrays_changed_after_a_render_show_in_every_output(vdtype, fdtype, shading):
    # The mesh keeps the caller's arrays: a later render draws them as they are then.
    mesh = softrast.Mesh(V.astype(vdtype), F.astype(fdtype))
    first = softrast.render(mesh, K=K, R=R, t=T, width=32, height=24, outputs=OUTPUTS,
                            shading=shading, threads=1)
    mesh.vertices[2] = [0.5, 0.8, 3.5]
    mesh.faces[1] = [0, 3, 1]
    later = softrast.render(mesh, K=K, R=R, t=T, width=32, height=24, outputs=OUTPUTS,
                            shading=shading, threads=1)
    fresh = softrast.render(softrast.Mesh(mesh.vertices.copy(), mesh.faces.copy()), K=K, R=R,
                            t=T, width=32, height=24, outputs=OUTPUTS, shading=shading, threads=1)
    assert not np.array_equal(first["color"], fresh["color"])
    assert_same(later, fresh)
