"""Shared helpers of the softrast Python tests (run by CTest's python_package)."""

import os
import subprocess

import numpy as np
import pytest

softrast = pytest.importorskip("softrast", reason="softrast is not importable: build it with CMake "
                               "(PYTHONPATH=build/python) or pip install ./python")

MODELS = os.environ.get("SR_SHARED_MODELS_DIR",
                        os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "models"))


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """A test that meets a missing library's refusal, "(softrast was built
    without X; ...)" from the package or from the tool's standard error,
    is skipped with that reason: a build without the optional libraries
    (SR_WITH_*=OFF) runs the suite, as the C tests skip (tests/sr_test.h)."""
    outcome = yield
    report = outcome.get_result()
    if not report.failed or call.excinfo is None:
        return
    error = call.excinfo.value
    stderr = getattr(error, "stderr", None)
    if isinstance(stderr, bytes):
        stderr = stderr.decode("utf-8", "replace")
    text = f"{error} {stderr or ''}"
    at = text.find("(softrast was built without")
    if at >= 0:
        report.outcome = "skipped"
        report.longrepr = (str(item.path), item.location[1] or 0,
                           "Skipped: " + text[at + 1:].split(";")[0].split(")")[0])


def pixel_rays(K, width, height):
    """(H, W, 3) float64 camera-space directions through the pixel centres, z = 1."""
    u, v = np.meshgrid(np.arange(width, dtype=np.float64), np.arange(height, dtype=np.float64))
    uv1 = np.stack([u, v, np.ones_like(u)], axis=-1)
    return uv1 @ np.linalg.inv(K).T


def random_triangles(rng, count, depth_range=(2.0, 6.0), size=0.6):
    """Separate triangles in front of a camera at the origin looking down +z:
    (3 * count, 3) float64 vertices, (count, 3) int64 faces."""
    centres = np.column_stack([rng.uniform(-1.5, 1.5, count), rng.uniform(-1.0, 1.0, count),
                               rng.uniform(*depth_range, count)])
    corners = centres[:, None, :] + rng.uniform(-size, size, (count, 3, 3))
    return corners.reshape(-1, 3), np.arange(3 * count, dtype=np.int64).reshape(-1, 3)


def default_camera(width, height, fov_y=1.0):
    return softrast.look_at(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, 1.0), up=(0.0, -1.0, 0.0),
                            fov_y=fov_y, width=width, height=height)


def ray_plane_depth(rays, p0, p1, p2):
    """Camera z where each ray (z = 1) meets the plane through p0, p1, p2."""
    n = np.cross(p1 - p0, p2 - p0)
    return (n @ p0) / (rays @ n)


def load_gltf(path):
    """softrast.load of a glTF file, the test skipped in a build that reads no glTF."""
    try:
        return softrast.load(path)
    except ValueError as e:
        if "jansson" in str(e) or "not supported" in str(e):
            pytest.skip("this build reads no glTF")
        raise


CLI = os.environ.get("SR_CLI")
needs_cli = pytest.mark.skipif(not CLI, reason="SR_CLI (the softrast command) is not set")


def assert_matches_command(tmp_path, path, name, cli_args, width=160, height=120, **render_kw):
    """render() of the glTF file's camera 0 against softrast render
    --camera-index 0 with cli_args: within 2 codes on all but 0.5% of the
    pixels (rounding of the model's world transform, which the command
    applies to the vertices and render in the program).  The two side by
    side go to $SR_TEST_OUT/name.png when it is set."""
    png = tmp_path / "cli.png"
    subprocess.run([CLI, "render", str(path), "--camera-index", "0", "--size",
                    f"{width}x{height}", *cli_args, "-o", str(png)],
                   check=True, capture_output=True)
    scene = load_gltf(path)
    ours = softrast.render(scene, camera=scene.cameras[0], width=width, height=height,
                           outputs=("color",), **render_kw)["color"]
    theirs = softrast.read_image(png)[..., :3]
    out = os.environ.get("SR_TEST_OUT")
    if out:
        softrast.write_png(os.path.join(out, f"{name}.png"), np.concatenate([ours, theirs], 1))
    diff = np.abs(ours.astype(int) - theirs).max(-1)
    assert (diff > 2).mean() <= 0.005, f"{(diff > 2).mean():.2%} of the pixels differ"
