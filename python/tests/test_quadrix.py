"""Tests of the quadrix Python module (docs/python.md).

Geometry is checked against analytic answers. The sphere scene: a sphere of radius R at the
origin, seen by a parallel view along +z (dop 0 0 -1: the viewer is at -z) whose window has
half-height WHH, in an image of N×N pixels. The window fit (flatten/window_fit.h) gives
k = N / (2 WHH) pixels per unit and device coordinates x_dev = k x + N/2, y_dev = -k y + N/2,
z_dev = k z (view_setup.h: y points down, z away from the viewer). At the centre of pixel (i, j),
x = (i + 1/2 - N/2) / k and y = -(j + 1/2 - N/2) / k; the visible point is z = -sqrt(R² - x² - y²),
so depth = k z, and the world normal facing the viewer is (x, y, z) / R.
"""
import os
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import quadrix

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PART = os.path.join(ROOT, "examples", "machined_part.uq")

N = 65  # odd: the centre pixel's centre is on the axis
R = 1.0
WHH = 1.25
K = N / (2 * WHH)  # 26 pixels per unit
SPHERE = f"""
quadric ball <1 1 1 0 0 0 0 0 0 {-R * R}>;
body ball (ball);
view side vrp 0 0 0 dop 0 0 -1 whh {WHH};
"""


def analytic_sphere(n=N, k=K, r=R):
    c = (np.arange(n) + 0.5 - n / 2) / k
    x = c[np.newaxis, :].repeat(n, 0)
    y = -c[:, np.newaxis].repeat(n, 1)
    q = r * r - x * x - y * y
    inside = q > 0
    z = -np.sqrt(np.where(inside, q, 0))
    return inside, x, y, z


def test_sphere_depth_and_normals_are_analytic():
    f = quadrix.render(text=SPHERE, size=(N, N))
    assert f.depth.shape == (N, N) and f.depth.dtype == np.float32
    assert f.normals.shape == (N, N, 3)
    inside, x, y, z = analytic_sphere()
    covered = f.surface >= 0
    # Pixels whose centre is within 1e-6 of the silhouette may go either way; no others.
    rim = np.abs(np.sqrt(x * x + y * y) - R) < 1e-6
    assert np.array_equal(covered[~rim], inside[~rim])
    c = N // 2
    # The centre pixel: depth -k R, normal (0, 0, -1) (toward the viewer at -z). The raycast
    # engine solves the quadratic in double precision; the Frame keeps depth as the float nearest
    # to it (half a float ulp) and the normal packed (exact along the axes, about 4e-5 radians
    # elsewhere).
    half_ulp = 0.5 * float(np.spacing(np.float32(K * R)))
    assert abs(float(f.depth[c, c]) + K * R) <= half_ulp * (1 + 1e-6) + 1e-9 * K
    np.testing.assert_array_equal(f.normals[c, c], [0, 0, -1])
    sel = covered & inside
    np.testing.assert_allclose(f.depth[sel], K * z[sel], rtol=0, atol=half_ulp + 1e-9 * K)
    expected_normals = np.stack([x, y, z], axis=-1) / R
    np.testing.assert_allclose(f.normals[sel], expected_normals[sel], atol=1e-4)
    # Background: +inf depth, zero normal, id -1.
    assert np.all(np.isinf(f.depth[~covered])) and np.all(f.depth[~covered] > 0)
    assert np.all(f.normals[~covered] == 0)
    assert np.all(f.solid[~covered] == -1) and np.all(f.body[~covered] == -1)


def test_antialiasing_changes_only_the_rim():
    plain = quadrix.render(text=SPHERE, size=(N, N))
    smooth = quadrix.render(text=SPHERE, size=(N, N), aa=16)
    _, x, y, _ = analytic_sphere()
    from_rim = np.abs(np.sqrt(x * x + y * y) - R) * K  # pixels
    changed = np.any(plain.image != smooth.image, axis=-1)
    assert changed.sum() > 50  # the rim is about 2 pi R K = 163 pixels long
    assert np.all(from_rim[changed] < 1.5)
    with pytest.raises(ValueError):
        quadrix.render(text=SPHERE, size=(N, N), aa=5)


def test_ids_name_the_solids():
    text = """
    solid sphere left =at -1.5 0 0 =r 1;
    solid sphere right =at 1.5 0 0 =r 1;
    view front vrp 0 0 0 dop 0 0 -1 whw 3;
    """
    f = quadrix.render(text=text, size=(60, 30))
    k = 60 / 6
    # Pixel centres over the two sphere centres: x = ±1.5 → column k·x + 30 - 1/2.
    row = 15
    left, right = int(-1.5 * k + 30), int(1.5 * k + 30)
    assert f.solid_names[f.solid[row, left]] == "left"
    assert f.solid_names[f.solid[row, right]] == "right"
    assert f.body_names[f.body[row, left]].endswith("left")
    assert f.surface.dtype == np.int32 and f.surface[row, left] >= 0
    assert f.solid[0, 0] == -1  # a corner is empty
    assert f.stats["covered_pixels"] == int(np.count_nonzero(f.solid >= 0))


def test_arrays_share_the_frames_memory():
    f = quadrix.render(text=SPHERE, size=(N, N))
    d1, d2 = f.depth, f.depth
    assert np.shares_memory(d1, d2)  # two views of one buffer, no copy
    assert d1.base is f and f.image.base is f and f.normals.base is f
    d1[0, 0] = 42.0
    assert f.depth[0, 0] == 42.0
    # The arrays keep the Frame alive after the last reference to it is dropped.
    image = f.image
    del f, d1, d2
    assert image.shape == (N, N, 3) and image.dtype == np.uint8
    assert image[N // 2, N // 2].max() > 0  # lit


def test_render_acceptance_line():
    f = quadrix.render(PART, size=(320, 240), engine="raycast")
    assert f.depth.shape == (240, 320) and f.image.dtype == np.uint8
    assert f.image.shape == (240, 320, 3)
    assert f.stats["engine"] == "raycast" and f.stats["covered_pixels"] > 10000


def test_read_errors_carry_file_line_column(tmp_path):
    bad = tmp_path / "bad.uq"
    bad.write_text("plane wall <1 0 0 0>;\nbody part (wall nothere);\n")
    with pytest.raises(quadrix.SceneError) as info:
        quadrix.read(str(bad))
    e = info.value
    assert e.file.endswith("bad.uq")
    assert (e.line, e.column) == (2, 17)
    assert "nothere" in e.message
    assert "bad.uq:2:17" in str(e)
    assert all(d[0] == "error" for d in e.diagnostics) and len(e.diagnostics) == 1
    with pytest.raises(quadrix.SceneError) as info:
        quadrix.read(text="plane wall <1 0 0>;", name="inline")
    assert info.value.file == "inline" and info.value.line == 1
    with pytest.raises(quadrix.SceneError):
        quadrix.read(str(tmp_path / "missing.uq"))
    with pytest.raises(ValueError):
        quadrix.render(text=SPHERE, size=(8, 8), engine="nosuchengine")


def test_build_and_edit_a_scene():
    s = quadrix.Scene()
    s.add_solid("sphere", "ball", at=(0, 0, 0), r=R)
    s.add_view("side", vrp=(0, 0, 0), dop=(0, 0, -1), whh=WHH)
    assert [d["id"] for d in s.solids()] == ["ball"] and s.views() == ["side"]
    f = s.render(size=(N, N), view="side")
    assert f.depth[N // 2, N // 2] == pytest.approx(-K * R, rel=1e-12)
    # Statements refer to ids already in the scene; a failed add leaves the scene unchanged.
    s.add("plane cut <0 0 -1 0>; body cap (ball cut);")  # the half z >= 0 of the ball
    with pytest.raises(quadrix.SceneError) as info:
        s.add("body broken (ball nothere);\nsolid sphere extra =r 1;", name="edit")
    assert info.value.file == "edit" and info.value.line == 1
    assert [d["id"] for d in s.solids()] == ["ball", "cap"]
    s.add_light(0.2)
    s.add_light(0.8, direction=(0, 0, -1), id="key")
    assert [(l["id"], l["kind"]) for l in s.lights()][1] == ("key", "parallel")
    # An explicit camera: from +z (dop 0 0 1), the ball's front is now at z = +R.
    cam = dict(vrp=(0, 0, 0), dop=(0, 0, 1), whh=WHH)
    g = s.render(size=(N, N), camera=cam, shading="phong", threads=1)
    assert g.depth[N // 2, N // 2] == pytest.approx(-K * R, rel=1e-12)
    np.testing.assert_allclose(g.normals[N // 2, N // 2], [0, 0, 1], atol=1e-12)


def test_engines_agree_with_raycast():
    s = quadrix.read(text=SPHERE)
    ref = s.render(size=(N, N))
    for engine in quadrix.engines():
        f = s.render(size=(N, N), engine=engine)
        both = (f.surface >= 0) & (ref.surface >= 0)
        assert np.count_nonzero(both) > 0.9 * np.count_nonzero(ref.surface >= 0), engine


def test_render_releases_the_gil():
    # A render of about a second on one thread; the main thread keeps running Python while it
    # goes. Held GIL: the main thread would stall for the whole render.
    s = quadrix.read(PART)
    done = {}

    def work():
        t0 = time.perf_counter()
        done["frame"] = s.render(size=(960, 720), threads=1, engine="raycast")
        done["seconds"] = time.perf_counter() - t0

    t = threading.Thread(target=work)
    ticks, last, worst = 0, time.perf_counter(), 0.0
    t.start()
    while t.is_alive():
        now = time.perf_counter()
        worst = max(worst, now - last)
        last = now
        ticks += 1
    t.join()
    assert done["frame"].depth.shape == (720, 960)
    render = done["seconds"]
    assert render > 0.02, "the render was too quick to tell"
    assert ticks > 1000
    assert worst < 0.5 * render, (worst, render)


def test_save_writes_files(tmp_path):
    f = quadrix.render(text=SPHERE, size=(N, N))
    f.save(str(tmp_path / "ball.png"))
    assert (tmp_path / "ball.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    quadrix.write_png(str(tmp_path / "mask.png"), (f.solid >= 0).astype(np.uint8) * 255)
    assert (tmp_path / "mask.png").stat().st_size > 0
    with pytest.raises(ValueError):
        f.save(str(tmp_path / "ball.xyz"))


def test_views_and_cameras_that_fail_raise_scene_error():
    s = quadrix.read(text=SPHERE, name="ball.uq")
    with pytest.raises(quadrix.SceneError, match="unknown view 'nosuch'"):
        s.render(size=(8, 8), view="nosuch")
    with pytest.raises(quadrix.SceneError, match="zero vector"):
        s.render(size=(8, 8), camera=dict(dop=(0, 0, 0)))
    with pytest.raises(quadrix.SceneError) as info:
        s.add("view bad dop 0 0 0;", name="views.uq")
    assert (info.value.file, info.value.line, info.value.column) == ("views.uq", 1, 10)
    with pytest.raises(TypeError):
        s.render(size=(8, 8), camera=dict(eye=(0, 0, 1)))


def test_without_numpy_the_arrays_are_buffers():
    # An interpreter without NumPy gets quadrix.ArrayView objects over the same memory.
    code = f"""
import sys
sys.modules["numpy"] = None  # import numpy fails
import quadrix
f = quadrix.render(text={SPHERE!r}, size=({N}, {N}))
d = f.depth
m = memoryview(d)
c = {N} // 2
assert (d.shape, d.dtype, f.image.dtype) == (({N}, {N}), "float32", "uint8"), d
assert m.format == "f" and m.shape == ({N}, {N})
assert abs(m[c, c] + {K * R}) < 1e-5, m[c, c]  # the float nearest to -K R
assert memoryview(f.normals)[c, c, 2] == -1.0
assert memoryview(f.solid)[0, 0] == -1
print("ok")
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr
