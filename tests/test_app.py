"""AppRenderer.py: its scenes hold the course's numbers, the script runs from any folder,
without a display, with the options it documents, each option does what it promises,
--all-figures compares the figures with the course's, the window shows an image pixel for
pixel, and VSCode finds the run configurations and the tests."""
import inspect
import json
import math
import re
import shutil
import sys
from pathlib import Path, PurePosixPath, PureWindowsPath
from types import SimpleNamespace

import cv2
import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.backend_bases import ResizeEvent

import AppRenderer
from AppRenderer import cornell_box_scene, sphere_test_scene
from helpers import APP, REPO, as_tuple, render_image, rgb, run_python
from pyrt.compare import REFERENCE_DIR, compare_with_reference
from pyrt.sampling import ADAPTIVE_TOLERANCE
from PyRT_Core import Parallelogram, Sphere
from PyRT_Integrators import (DepthIntegrator, IntersectionIntegrator, Integrator,
                              LazyIntegrator, NormalIntegrator, PhongIntegrator)


def albedo(primitive):
    """The diffuse colour of a Lambertian primitive: kd * pi."""
    return pytest.approx([channel * math.pi for channel in rgb(primitive.get_BRDF().kd)],
                         abs=1e-12)


def assert_parallelogram(obj, point, s1, s2):
    assert isinstance(obj, Parallelogram)
    assert (as_tuple(obj.point), as_tuple(obj.s1), as_tuple(obj.s2)) == (point, s1, s2)


def file_states(folder):
    return {path.name: path.stat().st_mtime_ns for path in folder.iterdir()}


# ------------------------------------------------------------------------------------------
# Importing
# ------------------------------------------------------------------------------------------
def test_importing_app_renderer_renders_and_writes_nothing(tmp_path):
    out = REPO / "out"
    before = file_states(out)
    result = run_python(["-c", "import AppRenderer; print('imported')"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout == "imported\n"
    assert list(tmp_path.iterdir()) == []
    assert file_states(out) == before


# ------------------------------------------------------------------------------------------
# The scenes' numbers, from the spec
# ------------------------------------------------------------------------------------------
def test_sphere_test_scene_has_the_course_numbers():
    scene = AppRenderer.sphere_test_scene()
    assert rgb(scene.i_a) == (0.5, 0.5, 0.5)
    sphere, floor = scene.object_list
    assert isinstance(sphere, Sphere)
    assert (as_tuple(sphere.origin), sphere.radius) == ((0, 0, -5), 2)
    assert albedo(sphere) == (0.8, 0.8, 0.8)
    assert_parallelogram(floor, (-4, -2, -1), (8, 0, 0), (0, 0, -8))
    assert albedo(floor) == (0.2, 0.8, 0.2)
    assert all(rgb(obj.emission) == (0, 0, 0) for obj in scene.object_list)
    [light] = scene.pointLights
    assert (as_tuple(light.pos), rgb(light.intensity)) == ((0, 5, 0), (80, 80, 80))
    camera = scene.camera
    assert (camera.width, camera.height) == (500, 500)
    assert camera.vertical_fov == pytest.approx(math.radians(60))
    assert scene.rendered_image.shape == (500, 500, 3)


def test_sphere_test_scene_area_light_replaces_the_point_light():
    scene = AppRenderer.sphere_test_scene(areaLS=True)
    assert scene.pointLights == []
    assert len(scene.object_list) == 3
    light = scene.object_list[2]
    assert_parallelogram(light, (-4, 6, -1), (8, 0, 0), (0, 0, -8))
    assert rgb(light.emission) == (3.5, 3.5, 3.5)
    assert rgb(light.get_BRDF().kd) == (0, 0, 0)


def test_sphere_test_scene_environment_map_is_the_one_at_env_map_path(monkeypatch,
                                                                       tmp_path):
    # a 1 x 2 map there: left texel red, right texel blue (OpenCV stores BGR)
    env_map = tmp_path / "environment.hdr"
    cv2.imwrite(str(env_map), np.array([[[0, 0, 2], [4, 0, 0]]], dtype=np.float32))
    monkeypatch.setattr(AppRenderer, "ENV_MAP_PATH", str(env_map))
    scene = AppRenderer.sphere_test_scene(use_env_map=True)
    assert scene.env_map.image.tolist() == [[[2, 0, 0], [0, 0, 4]]]
    assert AppRenderer.sphere_test_scene().env_map is None


def test_sphere_test_scene_without_its_environment_map_names_the_missing_file(monkeypatch,
                                                                              tmp_path):
    # PyRT ships no map, and no Practice 1 scene needs one: use_env_map=True without a
    # file at ENV_MAP_PATH stops where the scene is made, naming the file to put there
    missing = tmp_path / "env_maps" / "environment.hdr"
    monkeypatch.setattr(AppRenderer, "ENV_MAP_PATH", str(missing))
    with pytest.raises(FileNotFoundError) as error:
        AppRenderer.sphere_test_scene(use_env_map=True)
    message = str(error.value)
    assert repr(str(missing.resolve())) in message
    assert "latitude-longitude .hdr image" in message


def test_cornell_box_scene_has_the_course_numbers():
    # dist 0.75, side 2: z_far = -2.75, ll = (-1, -1, -2.75), ur = (1, 1, -2.75).
    scene = AppRenderer.cornell_box_scene(0.75, 2)
    assert rgb(scene.i_a) == (1, 1, 0.3)
    sphere, back, floor, left, ceiling, right = scene.object_list
    assert isinstance(sphere, Sphere)
    assert (as_tuple(sphere.origin), sphere.radius) == ((0, 0, -1.75), 0.25)
    assert albedo(sphere) == (0.2, 0.2, 0.7)
    ll, ur = (-1, -1, -2.75), (1, 1, -2.75)
    assert_parallelogram(back, ll, (2, 0, 0), (0, 2, 0))
    assert_parallelogram(floor, ll, (2, 0, 0), (0, 0, 2))
    assert_parallelogram(left, ll, (0, 2, 0), (0, 0, 2))
    assert_parallelogram(ceiling, ur, (-2, 0, 0), (0, 0, 2))
    assert_parallelogram(right, ur, (0, -2, 0), (0, 0, 2))
    for wall in (back, floor, ceiling):
        assert albedo(wall) == (0.8, 0.8, 0.8)
    assert albedo(left) == (0.7, 0.2, 0.2)
    assert albedo(right) == (0.2, 0.7, 0.2)
    # Lights at y = side/2 - 0.5 = 0.5, z = -(dist + side/2) = -1.75, x = 0, -0.5, 0.5.
    assert [as_tuple(light.pos) for light in scene.pointLights] == [
        (0, 0.5, -1.75), (-0.5, 0.5, -1.75), (0.5, 0.5, -1.75)]
    assert all(rgb(light.intensity) == (0.5, 0.5, 0.5) for light in scene.pointLights)
    camera = scene.camera
    assert (camera.width, camera.height) == (500, 500)
    assert camera.vertical_fov == pytest.approx(math.radians(70))


def test_cornell_box_area_light_is_a_square_under_the_ceiling():
    # Corner (-side/4, side/2 - 0.0001, -(dist + side/4)) = (-0.5, 0.9999, -1.25).
    scene = AppRenderer.cornell_box_scene(0.75, 2, areaLS=True)
    assert scene.pointLights == []
    assert len(scene.object_list) == 7
    light = scene.object_list[6]
    assert_parallelogram(light, (-0.5, 1 - 0.0001, -1.25), (1, 0, 0), (0, 0, -1))
    assert rgb(light.emission) == (1, 1, 1)
    assert rgb(light.get_BRDF().kd) == (0, 0, 0)


# ------------------------------------------------------------------------------------------
# The 2025-26 handout's sphere_scene(envMap=None)
# ------------------------------------------------------------------------------------------
def write_env_map(path):
    """Writes a 1 x 2 latitude-longitude map at path: left texel red (2, 0, 0), right texel
    blue (0, 0, 4)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    cv2.imwrite(str(path), np.array([[[0, 0, 2], [4, 0, 0]]], dtype=np.float32))  # BGR


@pytest.fixture(scope="session")
def sphere_test_scene_phong(tmp_path_factory):
    """Phong on sphere_test_scene() at its own 500 x 500 pixels: the objects, their
    materials, the light, the ambient light and the camera all show in this image."""
    folder = tmp_path_factory.mktemp("sphere_test_scene")
    return render_image(PhongIntegrator(str(folder / "img")), sphere_test_scene())


@pytest.mark.parametrize("make_scene", [lambda: AppRenderer.sphere_scene(),
                                        lambda: AppRenderer.sphere_scene(envMap=None)],
                         ids=["sphere_scene()", "sphere_scene(envMap=None)"])
def test_sphere_scene_renders_the_image_of_sphere_test_scene(tmp_path, make_scene,
                                                             sphere_test_scene_phong):
    scene = make_scene()
    assert scene.env_map is None
    image = render_image(PhongIntegrator(str(tmp_path / "img")), scene)
    assert image.shape == (500, 500, 3)
    assert np.array_equal(image, sphere_test_scene_phong)


def test_sphere_scene_sets_the_environment_map_at_a_path_from_the_script_folder(
        tmp_path, monkeypatch):
    write_env_map(tmp_path / "env_maps" / "arch_nozero.hdr")
    monkeypatch.chdir(tmp_path)  # the handout's relative path, from the student's folder
    scene = AppRenderer.sphere_scene(envMap="env_maps/arch_nozero.hdr", width=20, height=20)
    assert scene.env_map.image.tolist() == [[[2, 0, 0], [0, 0, 4]]]
    # the rest is the sphere scene: Phong, which never looks at the map, sees no difference
    expected = render_image(PhongIntegrator(str(tmp_path / "expected")),
                            sphere_test_scene(width=20, height=20))
    assert np.array_equal(render_image(PhongIntegrator(str(tmp_path / "img")), scene),
                          expected)


@pytest.mark.parametrize("relative", [True, False], ids=["relative", "absolute"])
def test_sphere_scene_refuses_a_missing_environment_map_naming_its_path(tmp_path,
                                                                       monkeypatch,
                                                                       relative):
    monkeypatch.chdir(tmp_path)
    missing = (tmp_path / "env_maps" / "arch_nozero.hdr").resolve()
    given = "env_maps/arch_nozero.hdr" if relative else str(missing)
    with pytest.raises(FileNotFoundError) as error:
        AppRenderer.sphere_scene(given)  # the handout's first argument, envMap
    message = str(error.value)
    assert repr(str(missing)) in message
    assert "latitude-longitude .hdr image" in message


def test_a_2025_26_student_script_runs_unchanged_and_renders_figure_3(tmp_path):
    # tests/student/render_2025_26.py imports sphere_scene, builds its rays with
    # Ray(direction=...) in its own loop over x and then y, and saves to the handout's
    # '.\\out\\' + 'rendered_image', which names the folder out on Windows, and on Linux
    # and macOS too: there get_filename() gives it with their separators, so that the
    # script reads its PNG back by the same name.
    shutil.copy(REPO / "tests" / "student" / "render_2025_26.py", tmp_path)
    write_env_map(tmp_path / "env_maps" / "arch_nozero.hdr")
    result = run_python(["render_2025_26.py"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    name = "./out/rendered_image_Intersection.png"  # DIRECTORY + FILENAME + suffix
    assert f"Read back {name}: (500, 500, 3)" in result.stdout
    assert "Progress: 100%" in result.stdout
    assert compare_with_reference(tmp_path / name, "figure3_intersection").matches


# ------------------------------------------------------------------------------------------
# Running the script
# ------------------------------------------------------------------------------------------
OPTIONS = ["--integrator", "--scene", "--width", "--height", "--max-depth", "--out",
           "--workers", "--spp", "--adaptive", "--tolerance", "--no-window", "--all-figures"]


def test_help_exits_zero_and_lists_the_options(tmp_path):
    result = run_python([APP, "--help"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    for option in OPTIONS:
        assert option in result.stdout


def test_script_renders_headless_from_another_folder(tmp_path):
    out = tmp_path / "images"
    result = run_python([APP, "--width", 16, "--height", 12, "--out", out], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "No display: the image is saved, not shown." in result.stdout
    for suffix in (".png", ".npy", ".hdr"):
        assert (out / ("rendered_image_Phong" + suffix)).is_file()
    expected = PhongIntegrator(str(tmp_path / "expected"))
    expected.add_scene(AppRenderer.cornell_box_scene(0.75, 2, width=16, height=12))
    expected.render(workers=1, progress=False)
    assert np.array_equal(np.load(out / "rendered_image_Phong.npy"),
                          expected.scene.rendered_image)


def test_default_output_folder_is_out_next_to_the_script(tmp_path):
    # A copy of the script in a folder of its own, so that the test neither touches the
    # renders in the repository's out/ nor depends on them, nor on another run of the tests
    app = tmp_path / "app" / "AppRenderer.py"
    app.parent.mkdir()
    shutil.copyfile(APP, app)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    result = run_python([app, "--integrator", "intersection", "--scene", "sphere",
                         "--width", 8, "--height", 6, "--no-window"], cwd=elsewhere)
    assert result.returncode == 0, result.stderr
    out = app.parent / "out"
    names = ["rendered_image_Intersection" + suffix for suffix in (".png", ".npy", ".hdr")]
    assert sorted(path.name for path in out.iterdir()) == sorted(names)
    assert np.load(out / names[1]).shape == (6, 8, 3)
    assert list(elsewhere.iterdir()) == []


FIGURE_NAMES = ["figure1_phong", "figure2_lazy", "figure3_intersection", "figure4_depth",
                "figure4_normal", "figure5_phong"]


def test_all_figures_at_500_pixels_match_the_course_and_write_the_sheet(all_figures):
    result, out = all_figures
    assert result.returncode == 0, result.stderr
    # one line per figure, in order; a render may lie one 8-bit step from its reference
    lines = [line.split(" (")[0] for line in map(str.strip, result.stdout.splitlines())
             if line.startswith("figure")]
    assert lines == [f"{name}: matches" for name in FIGURE_NAMES]
    sheet = plt.imread(out / "figures_vs_reference.png")
    # six rows of three 500 x 500 panels, with labels between them
    assert sheet.shape[0] > 6 * 500 and sheet.shape[1] > 3 * 500


def test_a_figure_without_a_reference_is_reported_not_raised(tmp_path, capsys):
    # the format of the README: a heading, one indented line per figure, the sheet's path
    png = REFERENCE_DIR / "figure2_lazy.png"
    sheet = AppRenderer.compare_with_course({"figure2_lazy": png, "figure9_extra": png},
                                            tmp_path, (500, 500))
    assert sheet == tmp_path / "figures_vs_reference.png" and sheet.is_file()
    assert capsys.readouterr().out.splitlines() == [
        "Compared with the course's figures (references/):",
        "  figure2_lazy: matches (largest difference 0/255)",
        "  figure9_extra: no reference image to compare with "
        "(references/figure9_extra.png is missing)",
        f"Saved {sheet}: each figure beside the course's, and their difference"]


def test_compare_with_course_warns_that_more_rays_per_pixel_change_the_edges(
        tmp_path, capsys, monkeypatch):
    sheets = []  # the sheet itself is tested in test_compare.py
    monkeypatch.setattr(AppRenderer, "write_sheet",
                        lambda comparisons, path: sheets.append(path) or path)
    renders = {"figure2_lazy": REFERENCE_DIR / "figure2_lazy.png"}
    AppRenderer.compare_with_course(renders, tmp_path, (500, 500), samples_per_pixel=4)
    assert capsys.readouterr().out.splitlines()[:3] == [
        "Compared with the course's figures (references/):",
        "(the figures have one ray per pixel: with more, the edges differ from them)",
        "  figure2_lazy: matches (largest difference 0/255)"]
    assert sheets == [tmp_path / "figures_vs_reference.png"]


def test_compare_with_course_skips_images_of_another_size_and_says_why(tmp_path, capsys):
    renders = {"figure2_lazy": REFERENCE_DIR / "figure2_lazy.png"}
    assert AppRenderer.compare_with_course(renders, tmp_path, (10, 12)) is None
    assert capsys.readouterr().out == (
        "The course's reference images are 500 x 500 pixels and these 10 x 12: not "
        "compared with them (render at the default size to compare).\n")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("arguments, named", [
    (["--integrator", "foo"], "integrator"),
    (["--spp", "0"], "spp"),
    (["--spp", "two"], "spp"),
    (["--workers", "0"], "workers"),
    (["--adaptive"], "adaptive.*--spp"),
    (["--spp", "4", "--tolerance", "0.1"], "tolerance.*--adaptive"),
    (["--width", "0"], "width"),
])
def test_bad_option_exits_with_a_usage_error_naming_it(tmp_path, capsys, arguments, named):
    small = ["--width", "8", "--height", "8"] if "--width" not in arguments else ["--height", "8"]
    with pytest.raises(SystemExit) as exited:
        AppRenderer.main([*small, *arguments, "--out", str(tmp_path / "o"), "--no-window"])
    assert exited.value.code == 2  # argparse's status for a bad command line
    stderr = capsys.readouterr().err
    assert stderr.startswith("usage:")
    assert re.search(named, stderr), stderr
    assert not (tmp_path / "o").exists()


def test_bad_option_ends_the_script_with_status_2_before_rendering(tmp_path):
    # The same, as a student runs the script: the process's own exit status and stderr.
    result = run_python([APP, "--width", 8, "--height", 8, "--spp", "two", "--out",
                         tmp_path / "o", "--no-window"], cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith("usage:")
    assert "--spp" in result.stderr, result.stderr
    assert not (tmp_path / "o").exists()


# ------------------------------------------------------------------------------------------
# The command line, read in this process
# ------------------------------------------------------------------------------------------
HELP_REFERENCE = REPO / "tests" / "data" / "app_help.txt"


@pytest.fixture
def command_line(monkeypatch):
    """parse_args as `python AppRenderer.py` runs it, in a terminal 100 columns wide."""
    monkeypatch.setattr(sys, "argv", ["AppRenderer.py"])
    monkeypatch.setenv("COLUMNS", "100")
    return AppRenderer.parse_args


def test_help_is_the_reference_help(command_line, capsys):
    # tests/data/app_help.txt holds the help a student sees, checked against the
    # README's table of options: the same options, defaults and meanings. The words are
    # compared, not the layout, which differs a little between Python versions.
    with pytest.raises(SystemExit) as exited:
        command_line(["--help"])
    assert exited.value.code == 0
    help_text = capsys.readouterr().out
    assert help_text.split() == HELP_REFERENCE.read_text(encoding="utf-8").split()


def test_no_options_mean_the_defaults_of_the_readme(command_line):
    assert vars(command_line([])) == {
        "integrator": "phong", "scene": "cornell", "width": 500, "height": 500,
        "max_depth": None,  # the depth integrator's own, 10
        "out": AppRenderer.DIRECTORY, "workers": None, "spp": 1, "adaptive": False,
        "tolerance": None,  # ADAPTIVE_TOLERANCE, applied by main
        "no_window": False, "explain": None, "all_figures": False}
    assert Path(AppRenderer.DIRECTORY) == REPO / "out"


def usage_error(command_line, capsys, argv):
    """The last line that parse_args(argv) writes before it exits with status 2."""
    with pytest.raises(SystemExit) as exited:
        command_line(argv)
    assert exited.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("usage: AppRenderer.py ")
    return err.splitlines()[-1]


@pytest.mark.parametrize("argv, message", [
    (["--spp", "two"], "argument --spp: must be a whole number greater than 0, got 'two'"),
    (["--width", "2.5"], "argument --width: must be a whole number greater than 0, got '2.5'"),
    (["--workers", "0"], "argument --workers: must be a whole number greater than 0, got '0'"),
    (["--max-depth", "-3"], "argument --max-depth: must be a number greater than 0, got '-3'"),
    (["--max-depth", "two"], "argument --max-depth: must be a number greater than 0, got 'two'"),
    (["--spp", "4", "--adaptive", "--tolerance", "two"],
     "argument --tolerance: must be a number from 0 to 1, got 'two'"),
    (["--spp", "4", "--adaptive", "--tolerance", "1.5"],
     "argument --tolerance: must be a number from 0 to 1, got '1.5'"),
    (["--adaptive"],
     "argument --adaptive: needs --spp N with N of 2 or more, the rays the pixels at edges get"),
    (["--spp", "4", "--tolerance", "0.1"], "argument --tolerance: only applies with --adaptive"),
])
def test_a_bad_command_line_gets_a_message_that_says_what_to_fix(command_line, capsys, argv,
                                                                 message):
    assert usage_error(command_line, capsys, argv) == f"AppRenderer.py: error: {message}"


def test_adaptive_accepts_two_samples_and_a_tolerance_from_0_to_1(command_line):
    # "N of 2 or more" and "a number from 0 to 1": both ends included
    args = command_line(["--spp", "2", "--adaptive", "--tolerance", "1"])
    assert (args.spp, args.adaptive, args.tolerance) == (2, True, 1.0)
    assert command_line(["--spp", "2", "--adaptive", "--tolerance", "0"]).tolerance == 0.0


# ------------------------------------------------------------------------------------------
# The window
# ------------------------------------------------------------------------------------------
FRAME_WIDTH, FRAME_HEIGHT = AppRenderer.WINDOW_FRAME


@pytest.mark.parametrize("image, screen, scale", [
    ((500, 500), (1280, 1024), 1.0),                                    # fits
    ((1280 - FRAME_WIDTH, 1024 - FRAME_HEIGHT), (1280, 1024), 1.0),     # fits exactly
    ((500, 500), (400, 300), (300 - FRAME_HEIGHT) / 500),               # too tall
    ((2000, 100), (1280, 1024), (1280 - FRAME_WIDTH) / 2000),           # too wide
    ((500, 500), (FRAME_WIDTH - 10, 1024), 1 / 500),  # no room at all: one pixel wide
])
def test_window_scale_is_one_unless_the_image_does_not_fit(image, screen, scale):
    assert AppRenderer.window_scale(image, screen) == pytest.approx(scale)


def shown_figure(monkeypatch, png, screen):
    """The figure AppRenderer.show(png) puts in its window, on a screen of screen pixels
    (a fake screen: the tests run without one)."""
    shown = []
    monkeypatch.setattr(AppRenderer, "_has_display", lambda: True)
    monkeypatch.setattr(AppRenderer, "_screen_size", lambda figure: screen)
    monkeypatch.setattr(plt, "show", lambda: shown.append(plt.gcf()))
    AppRenderer.show(str(png))
    [figure] = shown
    return figure


def size_in_pixels(figure):
    return tuple(round(v) for v in figure.get_size_inches() * figure.dpi)


def image_box_in_pixels(figure):
    """(left, bottom, width, height) of the drawn image in the figure, in pixels."""
    figure.canvas.draw()
    return tuple(round(v) for v in figure.axes[0].get_window_extent().bounds)


@pytest.fixture
def png_500(tmp_path):
    png = tmp_path / "rendered_image_Test.png"
    plt.imsave(png, np.zeros((500, 500, 3)))
    return png


def test_show_draws_the_image_pixel_for_pixel_when_it_fits(monkeypatch, capsys, png_500):
    figure = shown_figure(monkeypatch, png_500, (1280, 1024))
    try:
        assert size_in_pixels(figure) == (500, 500)
        assert image_box_in_pixels(figure) == (0, 0, 500, 500)
        assert figure.get_label() == "rendered_image_Test.png"  # the window's title
        [axes] = figure.axes
        assert not axes.axison
        assert axes.images[0].get_interpolation() == "none"
        assert "scaled" not in capsys.readouterr().out
        # A screen scaled to 125%, known once the window is on it, raises the figure's dots
        # per inch; the next resize brings the figure back to 500 x 500 screen pixels.
        figure.set_dpi(figure.dpi * 1.25)
        assert size_in_pixels(figure) == (625, 625)
        figure.canvas.callbacks.process("resize_event",
                                        ResizeEvent("resize_event", figure.canvas))
        assert size_in_pixels(figure) == (500, 500)
    finally:
        plt.close(figure)


def test_show_scales_an_image_too_large_for_the_screen_and_says_so(monkeypatch, capsys,
                                                                   png_500):
    figure = shown_figure(monkeypatch, png_500, (400, 300))
    try:
        # (300 - 160) / 500 = 0.28 of 500 pixels; the window is as wide as its toolbar
        assert FRAME_HEIGHT == 160
        assert image_box_in_pixels(figure) == (0, 0, 140, 140)
        assert size_in_pixels(figure) == (AppRenderer.MIN_WINDOW_WIDTH, 140)
        output = capsys.readouterr().out
        assert "500 x 500" in output and "400 x 300" in output
        assert "scaled to 28%" in output
        # scaled down, the pixels that share a screen pixel are averaged
        assert figure.axes[0].images[0].get_interpolation() == "antialiased"
    finally:
        plt.close(figure)


def test_show_without_a_display_only_says_that_the_image_is_saved(monkeypatch, capsys,
                                                                  png_500):
    monkeypatch.setattr(AppRenderer, "_has_display", lambda: False)
    monkeypatch.setattr(plt, "show", lambda: pytest.fail("plt.show() without a display"))
    figures = plt.get_fignums()
    AppRenderer.show(str(png_500))
    assert capsys.readouterr().out == "No display: the image is saved, not shown.\n"
    assert plt.get_fignums() == figures


def test_show_creates_its_window_one_pixel_small_so_that_it_can_shrink_to_the_image(
        monkeypatch, png_500):
    # matplotlib's toolbar keeps a window at least as wide as its figure was when the
    # window was created: the screen is measured on a figure one pixel wide and high.
    measured = []

    def screen_size(figure):
        measured.append((figure, size_in_pixels(figure)))
        return (400, 300)

    shown = []
    monkeypatch.setattr(AppRenderer, "_has_display", lambda: True)
    monkeypatch.setattr(AppRenderer, "_screen_size", screen_size)
    monkeypatch.setattr(plt, "show", lambda: shown.append(plt.gcf()))
    AppRenderer.show(str(png_500))
    [figure] = shown
    try:
        assert measured == [(figure, (1, 1))]
        assert size_in_pixels(figure) == (AppRenderer.MIN_WINDOW_WIDTH, 140)
    finally:
        plt.close(figure)


def test_show_draws_the_image_pixel_for_pixel_when_the_screen_size_is_unknown(
        monkeypatch, capsys, png_500):
    figure = shown_figure(monkeypatch, png_500, None)
    try:
        assert size_in_pixels(figure) == (500, 500)
        assert image_box_in_pixels(figure) == (0, 0, 500, 500)
        assert figure.axes[0].images[0].get_interpolation() == "none"
        assert "scaled" not in capsys.readouterr().out
    finally:
        plt.close(figure)


def test_show_keeps_the_whole_image_in_a_window_resized_by_hand(monkeypatch, png_500):
    figure = shown_figure(monkeypatch, png_500, (1280, 1024))
    try:
        # made half as wide by hand: the image shrinks to fit, whole, at the left edge,
        # and the window keeps the size it was given
        figure.set_size_inches(250 / figure.dpi, 500 / figure.dpi)
        figure.canvas.callbacks.process("resize_event",
                                        ResizeEvent("resize_event", figure.canvas))
        assert size_in_pixels(figure) == (250, 500)
        assert image_box_in_pixels(figure) == (0, 125, 250, 250)
    finally:
        plt.close(figure)


def test_show_keeps_one_row_of_an_image_scaled_to_less_than_a_pixel_high(monkeypatch,
                                                                           tmp_path):
    png = tmp_path / "one_row.png"
    plt.imsave(png, np.zeros((1, 4000, 3)))
    # (1280 - 40) / 4000 = 0.31 of 4000 pixels wide, and of one pixel high
    figure = shown_figure(monkeypatch, png, (1280, 1024))
    try:
        assert size_in_pixels(figure) == (1240, 1)
    finally:
        plt.close(figure)


def tk_like_figure(window):
    return SimpleNamespace(canvas=SimpleNamespace(manager=SimpleNamespace(window=window)))


def test_screen_size_is_what_a_tk_window_reports():
    window = SimpleNamespace(winfo_screenwidth=lambda: 1920, winfo_screenheight=lambda: 1080)
    assert AppRenderer._screen_size(tk_like_figure(window)) == (1920, 1080)


def test_screen_size_is_unknown_without_a_tk_window():
    figure = plt.figure()  # the tests' backend, Agg: a window manager without a window
    try:
        assert AppRenderer._screen_size(figure) is None
    finally:
        plt.close(figure)
    assert AppRenderer._screen_size(tk_like_figure(object())) is None  # not Tk's window


# matplotlib's backends that write files, and some that open windows, as
# matplotlib.get_backend() may name them
@pytest.mark.parametrize("backend, display", [
    *[(name, False) for name in ["agg", "Agg", "pdf", "ps", "svg", "pgf", "cairo",
                                 "template"]],
    *[(name, True) for name in ["TkAgg", "tkagg", "QtAgg", "MacOSX", "GTK4Agg", "WXAgg"]],
])
def test_has_display_is_false_exactly_for_backends_without_windows(monkeypatch, backend,
                                                                  display):
    monkeypatch.setattr(matplotlib, "get_backend", lambda: backend)
    assert AppRenderer._has_display() is display


# ------------------------------------------------------------------------------------------
# VSCode
# ------------------------------------------------------------------------------------------
def vscode_settings(name):
    """A file of .vscode/, parsed by the strict json module: VSCode would accept comments
    and trailing commas, but a file without them is plain JSON for every tool."""
    return json.loads((REPO / ".vscode" / name).read_text(encoding="utf-8"))


def strings_in(value):
    """Every string value inside parsed JSON."""
    if isinstance(value, str):
        yield value
    elif isinstance(value, dict):
        for item in value.values():
            yield from strings_in(item)
    elif isinstance(value, list):
        for item in value:
            yield from strings_in(item)


@pytest.mark.parametrize("name", ["launch.json", "settings.json"])
def test_vscode_files_are_json_naming_only_files_of_the_repository(name):
    values = list(strings_in(vscode_settings(name)))
    named = [value for value in values if "${workspaceFolder}" in value]
    for value in named:
        assert value.startswith("${workspaceFolder}"), value
        assert (REPO / value.removeprefix("${workspaceFolder}").lstrip("/")).exists(), value
    # nothing of one machine: no absolute path (an interpreter, say)
    assert not [value for value in values
                if PurePosixPath(value).is_absolute() or PureWindowsPath(value).is_absolute()]


def test_vscode_runs_figure_1_and_all_figures_with_the_selected_interpreter():
    launch = vscode_settings("launch.json")
    assert launch["version"] == "0.2.0"
    configurations = {c["name"]: c for c in launch["configurations"]}
    assert list(configurations) == ["Figure 1", "All figures"]
    for configuration in configurations.values():
        assert configuration["type"] == "debugpy"
        assert configuration["request"] == "launch"
        assert configuration["program"] == "${workspaceFolder}/AppRenderer.py"
        assert configuration["console"] == "integratedTerminal"
        assert "python" not in configuration  # VSCode uses the interpreter selected
    figure1 = AppRenderer.parse_args(configurations["Figure 1"].get("args", []))
    assert (figure1.all_figures, figure1.integrator, figure1.scene) == (False, "phong",
                                                                         "cornell")
    assert AppRenderer.parse_args(configurations["All figures"]["args"]).all_figures


def test_vscode_test_explorer_runs_pytest_on_the_tests_folder():
    settings = vscode_settings("settings.json")
    assert settings["python.testing.pytestEnabled"] is True
    assert settings["python.testing.unittestEnabled"] is False
    assert settings["python.testing.pytestArgs"] == ["tests"]
    assert (REPO / "tests").is_dir()


def test_show_keeps_a_narrow_image_at_its_size_in_a_window_as_wide_as_the_toolbar(
        monkeypatch, tmp_path):
    png = tmp_path / "narrow.png"
    plt.imsave(png, np.zeros((80, 100, 3)))
    figure = shown_figure(monkeypatch, png, (1280, 1024))
    try:
        assert image_box_in_pixels(figure) == (0, 0, 100, 80)
        assert size_in_pixels(figure) == (AppRenderer.MIN_WINDOW_WIDTH, 80)
        assert figure.axes[0].images[0].get_interpolation() == "none"
    finally:
        plt.close(figure)


# ------------------------------------------------------------------------------------------
# Each option does what it promises, in the script's own main()
# ------------------------------------------------------------------------------------------
class App:
    """Runs AppRenderer.main in this process, saving into `out`; the images it would show
    in a window are recorded in `shown` instead."""

    def __init__(self, out):
        self.out = out
        self.shown = []

    def run(self, *options, image="rendered_image_Phong"):
        """main() with these options; returns the linear image saved as `image`.npy."""
        assert AppRenderer.main(["--out", str(self.out), *map(str, options)]) == 0
        return np.load(self.out / (image + ".npy"))


@pytest.fixture
def app(tmp_path, monkeypatch):
    app = App(tmp_path / "out")
    monkeypatch.setattr(AppRenderer, "show", lambda png, on_click=None: app.shown.append(png))
    return app


def library_image(integrator, scene_name, width, height, **render_options):
    """What the library renders with this integrator on the course scene of that name (the
    Cornell box with dist 0.75 and side 2), in one process."""
    if scene_name == "cornell":
        scene = cornell_box_scene(0.75, 2, width=width, height=height)
    else:
        scene = sphere_test_scene(width=width, height=height)
    return render_image(integrator, scene, workers=1, **render_options)


INTEGRATOR_CLASSES = {"lazy": LazyIntegrator, "intersection": IntersectionIntegrator,
                      "depth": DepthIntegrator, "normal": NormalIntegrator,
                      "phong": PhongIntegrator}


@pytest.mark.parametrize("scene", ["cornell", "sphere"])
@pytest.mark.parametrize("name", INTEGRATOR_CLASSES)
def test_integrator_scene_width_and_height_options_choose_the_image(app, tmp_path, name,
                                                                    scene):
    integrator = INTEGRATOR_CLASSES[name](str(tmp_path / "library" / "rendered_image"))
    expected = library_image(integrator, scene, 9, 7)
    image = app.run("--integrator", name, "--scene", scene, "--width", 9, "--height", 7,
                    "--no-window", image=Path(integrator.get_filename()).name)
    assert image.shape == (7, 9, 3)
    assert np.array_equal(image, expected)


@pytest.mark.parametrize("options, max_depth, centre", [
    ([], 10, 0.7), (["--max-depth", 4], 4, 0.25), (["--max-depth", 7.5], 7.5, 0.6)])
def test_max_depth_option_sets_the_distance_drawn_black(app, tmp_path, options, max_depth,
                                                        centre):
    # The centre pixel of a 9 x 9 image looks straight at the sphere's front, 3 away:
    # grey 1 - 3/max_depth.
    image = app.run("--integrator", "depth", "--scene", "sphere", "--width", 9,
                    "--height", 9, "--no-window", *options, image="rendered_image_Depth")
    assert image[4, 4] == pytest.approx([centre] * 3, abs=1e-12)
    integrator = DepthIntegrator(str(tmp_path / "library" / "img"), max_depth)
    assert np.array_equal(image, library_image(integrator, "sphere", 9, 9))


def test_spp_option_averages_that_many_samples_per_pixel(app, tmp_path):
    one = app.run("--width", 12, "--height", 12, "--no-window", "--spp", 1)
    sixteen = app.run("--width", 12, "--height", 12, "--no-window", "--spp", 16)
    expected = library_image(PhongIntegrator(str(tmp_path / "library" / "img")),
                             "cornell", 12, 12, samples_per_pixel=16)
    assert np.array_equal(sixteen, expected)
    assert not np.array_equal(sixteen, one)  # the jagged edges are smoothed


@pytest.fixture
def render_calls(monkeypatch):
    """The arguments of every Integrator.render call (the course's integrators inherit it),
    which still renders."""
    calls = []
    original = Integrator.render
    signature = inspect.signature(original)

    def recording(*args, **kwargs):
        bound = signature.bind(*args, **kwargs)
        bound.apply_defaults()
        calls.append({name: value for name, value in bound.arguments.items()
                      if name != "self"})
        return original(*args, **kwargs)

    monkeypatch.setattr(Integrator, "render", recording)
    return calls


@pytest.mark.parametrize("options, workers, samples", [
    ([], None, 1), (["--workers", 1], 1, 1), (["--workers", 2], 2, 1),
    (["--spp", 4], None, 4), (["--workers", 1, "--spp", 9], 1, 9)])
def test_workers_and_spp_options_reach_render(app, render_calls, options, workers, samples):
    app.run("--width", 8, "--height", 8, "--no-window", *options)
    assert [(call["workers"], call["samples_per_pixel"]) for call in render_calls] == [
        (workers, samples)]
    assert render_calls[0]["adaptive"] is False


def test_render_renders_once_with_one_centre_ray_per_pixel_and_says_where_the_image_is(
        tmp_path, capsys, monkeypatch, render_calls):
    # the clock of AppRenderer reads 10 s before the render and 11.25 s after it
    readings = iter([10.0, 11.25])
    monkeypatch.setattr(AppRenderer, "time", SimpleNamespace(perf_counter=lambda: next(readings)))
    integrator = LazyIntegrator(str(tmp_path / "img"))
    png = AppRenderer.render(integrator, sphere_test_scene(width=4, height=3))
    assert [(call["workers"], call["samples_per_pixel"], call["adaptive"])
            for call in render_calls] == [(None, 1, False)]
    assert png == str(tmp_path / "img_Lazy.png") and Path(png).is_file()
    assert capsys.readouterr().out.splitlines() == [
        f"Saved {png} (and .npy, .hdr)", "Rendering time: 1.25 s"]


@pytest.mark.parametrize("options, tolerance", [
    (["--adaptive"], ADAPTIVE_TOLERANCE), (["--adaptive", "--tolerance", "0.1"], 0.1),
    (["--adaptive", "--tolerance", "0"], 0.0)])
def test_adaptive_and_tolerance_options_reach_render(app, render_calls, options, tolerance):
    app.run("--width", 8, "--height", 8, "--no-window", "--spp", 4, *options)
    assert [(call["adaptive"], call["tolerance"]) for call in render_calls] == [
        (True, tolerance)]


def test_adaptive_option_saves_the_accuracy_and_the_map_of_rays(app, tmp_path):
    image = app.run("--width", 12, "--height", 12, "--no-window", "--spp", 16, "--adaptive")
    expected = library_image(PhongIntegrator(str(tmp_path / "library" / "img")),
                             "cornell", 12, 12, samples_per_pixel=16, adaptive=True)
    assert np.array_equal(image, expected)
    accuracy = json.loads((app.out / "rendered_image_Phong_accuracy.json").read_text())
    assert (accuracy["adaptive"], accuracy["samples_per_pixel"]) == (True, 16)
    assert plt.imread(app.out / "rendered_image_Phong_samples.png").shape[:2] == (12, 12)


def test_any_number_of_workers_gives_the_same_image(app):
    default = app.run("--width", 16, "--height", 16, "--no-window")
    one = app.run("--width", 16, "--height", 16, "--no-window", "--workers", 1)
    two = app.run("--width", 16, "--height", 16, "--no-window", "--workers", 2)
    assert default.any()
    assert np.array_equal(one, default) and np.array_equal(two, default)


def test_the_saved_image_is_shown_in_a_window(app):
    app.run("--width", 8, "--height", 8)
    assert [Path(png) for png in app.shown] == [app.out / "rendered_image_Phong.png"]


def test_no_window_saves_without_showing(app):
    app.run("--width", 8, "--height", 8, "--no-window")
    assert app.shown == []
    assert (app.out / "rendered_image_Phong.png").is_file()


# The images of --all-figures (README) and what each shows (the course's Figures 1-5).
FIGURES = {
    "Phong_figure1": (lambda base: PhongIntegrator(base, "_figure1"), "cornell"),
    "Lazy_figure2": (lambda base: LazyIntegrator(base, "_figure2"), "sphere"),
    "Intersection_figure3": (lambda base: IntersectionIntegrator(base, "_figure3"), "sphere"),
    "Depth_figure4": (lambda base: DepthIntegrator(base, 5, "_figure4"), "sphere"),
    "Normal_figure4": (lambda base: NormalIntegrator(base, "_figure4"), "sphere"),
    "Phong_figure5": (lambda base: PhongIntegrator(base, "_figure5"), "sphere"),
}


def test_all_figures_writes_the_six_figure_images(app, tmp_path, capsys):
    app.run("--all-figures", "--width", 10, "--height", 10, "--no-window",
            image="rendered_image_Phong_figure1")
    assert {path.name for path in app.out.iterdir()} == {  # and no comparison sheet
        f"rendered_image_{name}{suffix}"
        for name in FIGURES for suffix in (".png", ".npy", ".hdr")}
    assert "reference images are 500 x 500 pixels and these 10 x 10" in capsys.readouterr().out
    for name, (make, scene) in FIGURES.items():
        integrator = make(str(tmp_path / "library" / "rendered_image"))
        assert np.array_equal(np.load(app.out / f"rendered_image_{name}.npy"),
                              library_image(integrator, scene, 10, 10)), name


@pytest.fixture
def course_comparisons(monkeypatch):
    """The arguments of every compare_with_course call in main, which still runs."""
    calls = []
    original = AppRenderer.compare_with_course

    def recording(renders, folder, size, samples_per_pixel=1):
        calls.append((renders, folder, size, samples_per_pixel))
        return original(renders, folder, size, samples_per_pixel)

    monkeypatch.setattr(AppRenderer, "compare_with_course", recording)
    return calls


def test_all_figures_compares_every_figure_and_shows_the_last_when_not_compared(
        app, course_comparisons):
    # At 4 x 4 pixels there is no comparison sheet: the window shows Figure 5
    app.run("--all-figures", "--width", 4, "--height", 4, "--spp", 2,
            image="rendered_image_Phong_figure1")
    renders = {name: str(app.out / f"rendered_image_{image}.png")
               for name, image in zip(FIGURE_NAMES, FIGURES)}
    assert course_comparisons == [(renders, str(app.out), (4, 4), 2)]
    assert [Path(png) for png in app.shown] == [app.out / "rendered_image_Phong_figure5.png"]


def test_all_figures_shows_the_comparison_sheet(app, monkeypatch, tmp_path):
    sheet = tmp_path / "figures_vs_reference.png"  # as compare_with_course writes it
    monkeypatch.setattr(AppRenderer, "compare_with_course", lambda *args: sheet)
    app.run("--all-figures", "--width", 2, "--height", 2,
            image="rendered_image_Phong_figure1")
    assert app.shown == [sheet]


BAD_NUMBERS = ["0", "-3", "two"]


@pytest.mark.parametrize("option, value", [
    *[(option, value) for option in ("--width", "--height", "--workers", "--spp")
      for value in BAD_NUMBERS + ["2.5"]],
    *[("--tolerance", value) for value in ["-0.1", "1.5", "two", "nan", "inf"]],
    *[("--max-depth", value) for value in BAD_NUMBERS + ["inf", "nan"]],
    ("--integrator", "foo"), ("--scene", "box")])
def test_bad_option_value_is_a_usage_error_before_anything_is_written(tmp_path, capsys,
                                                                     option, value):
    out = tmp_path / "out"
    with pytest.raises(SystemExit) as exited:
        AppRenderer.main(["--out", str(out), "--width", "8", "--height", "8", "--no-window",
                          "--spp", "4", "--adaptive", option, value])  # the last one counts
    assert exited.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("usage:") and f"argument {option}" in err
    assert not out.exists()
