"""pyrt/images.py: the three files of a saved image, written whole, and the course's
tonemapper against OpenCV's."""
import os
import stat

import cv2
import matplotlib.pyplot as plt
import numpy as np
import pytest

import pyrt.images
from helpers import PNG_TOLERANCE, read_png, run_python
from PyRT_Core import Camera, Scene


# ------------------------------------------------------------------------------------------
# Saving images
# ------------------------------------------------------------------------------------------
def scene_with_image(image):
    scene = Scene()
    height, width = image.shape[:2]
    scene.set_camera(Camera(width, height, 60))
    scene.rendered_image[...] = image
    return scene


def sample_image():
    image = np.random.default_rng(7).uniform(0.05, 4.0, size=(5, 6, 3))
    image[0, 0] = (5.0, 0.0, 0.0)   # pure red: a swapped channel order shows up here
    image[4, 5] = (0.0, 0.0, 0.25)  # pure blue
    return image


@pytest.fixture
def saved(tmp_path):
    image = sample_image()
    base = tmp_path / "new" / "folder" / "picture"
    scene_with_image(image).save_image(str(base))
    return image, base


def test_save_image_creates_missing_folders_and_three_files(saved):
    _, base = saved
    for suffix in (".png", ".npy", ".hdr"):
        assert base.with_name(base.name + suffix).is_file()


def test_saved_npy_is_exactly_the_rendered_image(saved):
    image, base = saved
    np.testing.assert_array_equal(np.load(str(base) + ".npy"), image)


def test_saved_hdr_is_rgb_float_within_rgbe_precision(saved):
    image, base = saved
    bgr = cv2.imread(str(base) + ".hdr", cv2.IMREAD_ANYDEPTH | cv2.IMREAD_COLOR)
    assert bgr.dtype == np.float32 and bgr.shape == image.shape
    read = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)
    # RGBE keeps 8 bits of mantissa under the largest channel of each pixel
    tolerance = image.max(axis=2, keepdims=True) / 128
    assert np.all(np.abs(read - image) <= tolerance)
    assert read[0, 0, 0] == pytest.approx(5.0, rel=1e-2) and read[0, 0, 2] == 0.0
    assert read[4, 5, 2] == pytest.approx(0.25, rel=1e-2) and read[4, 5, 0] == 0.0


def test_saved_png_is_the_tonemapped_image(saved):
    image, base = saved
    png = plt.imread(str(base) + ".png")
    assert png.shape[:2] == image.shape[:2]
    expected = pyrt.images.tonemap_image(image)
    np.testing.assert_allclose(png[:, :, :3], expected, atol=1.01 / 255)


def test_saved_png_without_tonemapping_shows_the_linear_values_clipped_to_0_1(tmp_path):
    # as Figure 2's: v in [0, 1] as floor(255 v) / 255, below 0 black, above 1 white
    image = np.array([[[-0.5, 0.5, 2.0], [0.2, -3.0, 1.5]]])
    scene_with_image(image).save_image(str(tmp_path / "picture"), tonemap=False)
    expected = np.array([[[0.0, 127.0, 255.0], [51.0, 0.0, 255.0]]]) / 255.0
    assert read_png(tmp_path / "picture.png") == pytest.approx(expected, abs=1e-6)


def test_save_image_before_set_camera_says_to_set_the_camera_and_render(tmp_path):
    with pytest.raises(RuntimeError, match=r"^Scene\.save_image: the scene has no image yet; "
                                           r"call scene\.set_camera\(camera\) and render "
                                           r"first$"):
        Scene().save_image(str(tmp_path / "image"))
    assert list(tmp_path.iterdir()) == []


def test_save_image_says_when_opencv_cannot_encode_the_hdr_file(tmp_path, monkeypatch):
    monkeypatch.setattr(pyrt.images.cv2, "imencode", lambda *args: (False, None))
    with pytest.raises(RuntimeError, match=r"^Scene\.save_image: OpenCV could not encode the "
                                           r"HDR image$"):
        scene_with_image(sample_image()).save_image(str(tmp_path / "image"))
    assert not (tmp_path / "image.hdr").exists()


def test_save_image_overwrites_previous_files(tmp_path):
    base = str(tmp_path / "picture")
    scene_with_image(np.ones((2, 2, 3))).save_image(base)
    scene_with_image(np.full((2, 2, 3), 3.0)).save_image(base)
    np.testing.assert_array_equal(np.load(base + ".npy"), np.full((2, 2, 3), 3.0))


def test_save_image_leaves_no_temporary_files(tmp_path):
    scene_with_image(np.ones((2, 2, 3))).save_image(str(tmp_path / "picture"))
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "picture.hdr", "picture.npy", "picture.png"]


@pytest.mark.skipif(os.name == "nt", reason="Windows has no umask permission bits")
def test_saved_files_are_readable_by_others_as_the_umask_allows(tmp_path):
    previous = os.umask(0o022)
    try:
        scene_with_image(np.ones((2, 2, 3))).save_image(str(tmp_path / "picture"))
    finally:
        os.umask(previous)
    for path in tmp_path.iterdir():
        assert stat.S_IMODE(path.stat().st_mode) == 0o644, path.name


def test_failed_save_keeps_the_previous_file_whole(tmp_path, monkeypatch):
    base = str(tmp_path / "picture")
    scene_with_image(np.ones((2, 2, 3))).save_image(base)
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir()}

    def crash(source, target):  # the machine stops between writing and renaming
        raise OSError("disk full")

    monkeypatch.setattr(pyrt.images.os, "replace", crash)
    with pytest.raises(OSError, match="disk full"):
        scene_with_image(np.full((2, 2, 3), 3.0)).save_image(base)
    assert {p.name: p.read_bytes() for p in tmp_path.iterdir()} == before


def test_save_that_cannot_create_its_file_reports_that_error_alone(tmp_path, monkeypatch):
    def cannot_create(path, mode):  # no temporary file comes to exist
        raise OSError("too many open files")

    monkeypatch.setattr(pyrt.images, "open", cannot_create, raising=False)
    with pytest.raises(OSError, match="too many open files") as error:
        scene_with_image(np.ones((2, 2, 3))).save_image(str(tmp_path / "picture"))
    assert error.value.__context__ is None  # no second error from cleaning up
    assert list(tmp_path.iterdir()) == []


# ------------------------------------------------------------------------------------------
# A broken OpenCV, and file names with Windows's separators
# ------------------------------------------------------------------------------------------
def empty_cv2():
    """cv2 as it is left when one of opencv-python and opencv-python-headless was
    uninstalled while both were installed: a package with nothing in it."""
    module = type(os)("cv2")
    module.__path__ = ["/site-packages/cv2"]
    return module


def test_installed_opencv_has_everything_pyrt_uses():
    assert pyrt.images.opencv_problem() is None


def test_an_empty_cv2_is_named_with_what_it_lacks_and_the_command_that_fixes_it(
        monkeypatch):
    monkeypatch.setattr(pyrt.images, "cv2", empty_cv2())
    assert pyrt.images.opencv_problem() == (
        "OpenCV is broken: the cv2 package (/site-packages/cv2) has no createTonemap, "
        "imencode, imread, cvtColor, utils, as happens when one of opencv-python and "
        "opencv-python-headless is uninstalled while both are installed. Fix it with\n"
        "    pip install --force-reinstall opencv-python-headless\n"
        "(or opencv-python, which also has OpenCV's windows)")


def test_a_save_that_opencv_fails_keeps_the_linear_image_and_names_it(tmp_path, monkeypatch,
                                                                      capsys):
    # as the handout's render() saves: after the whole render
    monkeypatch.setattr(pyrt.images, "cv2", empty_cv2())
    image = sample_image()
    with pytest.raises(RuntimeError, match=r"^Scene\.save_image: OpenCV is broken: .* Fix it "
                                           r"with\n    pip install --force-reinstall "):
        scene_with_image(image).save_image(str(tmp_path / "picture"))
    assert sorted(path.name for path in tmp_path.iterdir()) == ["picture.npy"]
    np.testing.assert_array_equal(np.load(tmp_path / "picture.npy"), image)
    assert capsys.readouterr().err == (
        f"PyRT: the image is saved in {tmp_path / 'picture.npy'} (np.load reads it), but "
        "the PNG or HDR file could not be written:\n")


def test_with_an_empty_cv2_package_first_on_the_path_render_stops_before_it_starts(
        tmp_path):
    # a real package, found by import before the installed OpenCV
    (tmp_path / "fake" / "cv2").mkdir(parents=True)
    (tmp_path / "fake" / "cv2" / "__init__.py").write_text("")
    script = ("import sys; sys.path.insert(0, 'fake')\n"
              "from AppRenderer import sphere_test_scene\n"
              "from PyRT_Integrators import LazyIntegrator\n"
              "integrator = LazyIntegrator('out/image')\n"
              "integrator.add_scene(sphere_test_scene(width=4, height=4))\n"
              "integrator.render(progress=False)\n")
    result = run_python(["-c", script], tmp_path)
    assert result.returncode == 1
    assert result.stderr.endswith(
        "RuntimeError: LazyIntegrator.render: OpenCV is broken: the cv2 package ("
        f"{tmp_path / 'fake' / 'cv2' / '__init__.py'}) has no createTonemap, imencode, "
        "imread, cvtColor, utils, as happens when one of opencv-python and "
        "opencv-python-headless is uninstalled while both are installed. Fix it with\n"
        "    pip install --force-reinstall opencv-python-headless\n"
        "(or opencv-python, which also has OpenCV's windows)\n"), result.stderr
    assert not (tmp_path / "out").exists()


def test_without_cv2_the_course_modules_say_how_to_repair_opencv(tmp_path):
    # as opencv-python 5 leaves it: the files both packages share are gone
    result = run_python(["-c", "import sys; sys.modules['cv2'] = None; import PyRT_Common"],
                        tmp_path)
    assert result.returncode == 1
    assert result.stderr.endswith(
        "ImportError: PyRT needs OpenCV, and import cv2 fails (import of cv2 halted; None in "
        "sys.modules), as happens when one of opencv-python and opencv-python-headless is "
        "uninstalled while both are installed. Fix it with\n"
        "    pip install --force-reinstall opencv-python-headless\n"
        "(or opencv-python, which also has OpenCV's windows)\n"), result.stderr


@pytest.mark.skipif(os.sep != "/", reason="a backslash separates folders here")
def test_a_name_with_windows_separators_is_saved_where_it_means_with_a_note(
        tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    png = scene_with_image(sample_image()).save_image(".\\out\\picture")
    assert str(png) == "out/picture.png"
    assert sorted(path.name for path in (tmp_path / "out").iterdir()) == [
        "picture.hdr", "picture.npy", "picture.png"]
    assert sorted(path.name for path in tmp_path.iterdir()) == ["out"]
    assert capsys.readouterr().err == (
        "PyRT: '.\\\\out\\\\picture' is written with Windows's separators; on this system "
        "it is './out/picture'\n")


# ------------------------------------------------------------------------------------------
# Tonemapping
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_tonemap_is_opencvs_default_tonemapper_bit_for_bit(dtype):
    # A rendered image is double precision; the course gives OpenCV its single-precision
    # copy, and every value must round as there, or PNG pixels one step apart follow
    image = np.random.default_rng(3).uniform(0.0, 20.0, size=(64, 48, 3)).astype(dtype)
    opencv = cv2.createTonemap(gamma=2.5).process(image.astype(np.float32))
    # OpenCV maps the minimum to a tiny negative number and returns its power as NaN;
    # PyRT shows it as 0, the minimum
    expected = np.clip(np.nan_to_num(opencv, nan=0.0), 0.0, 1.0)
    np.testing.assert_array_equal(pyrt.images.tonemap_image(image), expected)


def test_tonemap_maps_an_image_beyond_single_precision_in_double_precision():
    # 1e39 has no single-precision value: OpenCV would see infinity and show NaN
    image = np.array([[[1e39, 0.0, 5e38]], [[2e39, 2e39, 1e39]]])
    np.testing.assert_allclose(pyrt.images.tonemap_image(image),
                               [[[0.5 ** 0.4, 0.0, 0.25 ** 0.4]], [[1.0, 1.0, 0.5 ** 0.4]]],
                               rtol=1e-6)
    assert (pyrt.images.tonemap_image(np.full((1, 2, 3), 1e300)) == 1.0).all()  # flat


def test_tonemap_prints_nothing(tmp_path):
    # OpenCV warns on its first tonemapping in a process; a student must not see it
    script = ("import numpy as np, pyrt.images; "
              "pyrt.images.tonemap_image(np.random.default_rng(1).random((4, 4, 3)))")
    done = run_python(["-c", script], tmp_path)
    assert done.returncode == 0 and done.stdout == done.stderr == "", done.stderr


def test_tonemap_maps_minimum_to_0_and_maximum_to_1():
    image = np.array([[[2.0, 3.0, 6.0], [4.0, 2.5, 5.0]]])
    out = pyrt.images.tonemap_image(image)
    assert out[0, 0, 0] == 0.0 and out[0, 0, 2] == pytest.approx(1.0, abs=1e-15)
    # 4 -> (4 - 2)/(6 - 2) = 0.5, then 0.5 ** (1/2.5), in single precision as in OpenCV
    assert out[0, 1, 0] == pytest.approx(0.5 ** 0.4, rel=1e-6)


@pytest.mark.parametrize("image", [
    np.full((1, 2, 3), 0.25, np.float32),                   # flat: left as it is, 0.25 ** 0.4
    np.array([[[0.0, 2.0 ** -52, 0.0]]], np.float32),       # max - min = DBL_EPSILON: flat
    np.array([[[0.0, 2.0 ** -51, 0.0]]], np.float32),       # twice that: stretched to [0, 1]
    np.array([[[-3.0, 1.0, -1.0]]], np.float32),            # below zero: -3 -> 0, -1 -> 0.5
], ids=["flat", "flat-to-epsilon", "just-not-flat", "negative"])
def test_tonemap_agrees_with_opencv_on_flat_and_negative_images(image):
    opencv = cv2.createTonemap(gamma=2.5).process(image.copy())
    np.testing.assert_allclose(pyrt.images.tonemap_image(image), opencv, rtol=1e-6, atol=1e-7)


@pytest.mark.parametrize("value, shown", [(4.0, 1.0), (-0.5, 0.0)])
def test_tonemap_shows_a_flat_image_outside_0_to_1_clipped(value, shown):
    # OpenCV leaves a flat image as it is; the course clips the result to [0, 1]
    assert (pyrt.images.tonemap_image(np.full((2, 1, 3), value)) == shown).all()


def test_tonemap_shows_nan_as_darkest_in_an_image_below_zero():
    # finite values from -3 to 1: NaN and -inf are shown as -3, 0; +inf as 1, 1
    image = np.array([[[-3.0, 1.0, np.nan], [-1.0, -np.inf, np.inf]]])
    assert pyrt.images.tonemap_image(image) == pytest.approx(
        np.array([[[0.0, 1.0, 0.0], [0.5 ** 0.4, 0.0, 1.0]]]), rel=1e-6)


@pytest.mark.parametrize("image", [
    np.array([[[2.0, 3.0, 6.0]]]),               # a linear image, in double precision
    np.full((1, 2, 3), 4.0),                      # flat: left as it is
    np.array([[[np.nan, np.inf, -np.inf]]]),      # nothing finite: all black
], ids=["linear", "flat", "not-finite"])
def test_tonemap_gives_single_precision_as_opencv_does(image):
    # cv2.createTonemap().process returns float32, whatever the image holds
    assert pyrt.images.tonemap_image(image).dtype == np.float32


def with_non_finite(a, b, c):
    """A 2 x 2 image whose finite values run from 1 to 3, with a, b and c in three of its
    channels, and what the tonemapper shows: finite v as ((v - 1)/(3 - 1)) ** (1/2.5), in
    single precision as in OpenCV; +inf as 1, the brightest; NaN and -inf as 0, the
    darkest."""
    image = np.array([[[1.0, 2.0, 3.0], [2.5, 1.5, 3.0]],
                      [[a, 2.0, b], [c, 1.0, 3.0]]])
    finite = np.isfinite(image)
    shown = np.where(np.isposinf(image), 1.0, 0.0)
    shown[finite] = ((image[finite] - 1.0) / 2.0) ** 0.4
    return image, shown


@pytest.mark.parametrize("bad", [(np.nan,) * 3, (np.inf,) * 3, (-np.inf,) * 3,
                                 (np.inf, -np.inf, np.nan)],
                         ids=["nan", "inf", "-inf", "all"])
def test_tonemap_shows_inf_as_brightest_and_nan_or_minus_inf_as_darkest(bad):
    image, shown = with_non_finite(*bad)
    np.testing.assert_allclose(pyrt.images.tonemap_image(image), shown, rtol=1e-6, atol=1e-7)


def test_saved_png_shows_inf_as_brightest_and_nan_or_minus_inf_as_darkest(tmp_path):
    image, shown = with_non_finite(np.inf, -np.inf, np.nan)
    scene_with_image(image).save_image(str(tmp_path / "picture"))
    assert np.abs(read_png(tmp_path / "picture.png") - shown).max() <= PNG_TOLERANCE
