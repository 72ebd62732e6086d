"""AppRenderer.py as a script: it runs from any folder, without a display, with the options it
documents; each option does what it promises; --all-figures compares the figures with the
course's."""
import inspect
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import matplotlib.pyplot as plt
import numpy as np
import pytest

import AppRenderer
from AppRenderer import cornell_box_scene, sphere_test_scene
from helpers import (APP, REPO, SUBPROCESS_TIMEOUT, headless_env, render_image,
                     run_python)
from pyrt.compare import REFERENCE_DIR
from pyrt.sampling import ADAPTIVE_TOLERANCE
from PyRT_Integrators import (DepthIntegrator, IntersectionIntegrator, Integrator,
                              LazyIntegrator, NormalIntegrator, PhongIntegrator)


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


def test_broken_opencv_ends_the_script_with_its_fix_and_no_traceback(tmp_path):
    # An empty cv2 package first on the import path, as uninstalling one of
    # opencv-python and opencv-python-headless leaves it when both were installed
    fake = tmp_path / "fake"
    (fake / "cv2").mkdir(parents=True)
    (fake / "cv2" / "__init__.py").write_text("")
    env = headless_env()
    env["PYTHONPATH"] = os.pathsep.join([str(fake), env["PYTHONPATH"]])
    result = subprocess.run([sys.executable, str(APP), "--width", "8", "--height", "8",
                             "--out", str(tmp_path / "o"), "--no-window"], cwd=tmp_path,
                            env=env, capture_output=True, text=True,
                            timeout=SUBPROCESS_TIMEOUT)
    output = result.stdout + result.stderr
    assert result.returncode != 0
    assert "pip install --force-reinstall opencv-python-headless" in result.stderr, output
    assert "Traceback" not in output
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
        "integrator": "phong", "scene": "cornell", "samples": None, "pool": None, "width": 500,
        "height": 500, "max_depth": None,  # the depth integrator's own, 10
        "out": AppRenderer.DIRECTORY, "workers": None, "spp": 1, "adaptive": False,
        "tolerance": None,  # ADAPTIVE_TOLERANCE, applied by main
        "no_window": False, "explain": None, "all_figures": False}
    assert Path(AppRenderer.DIRECTORY) == REPO / "out"


@pytest.mark.parametrize("name, class_name, filename", [
    ("cmc-is", "CMCISIntegrator", "out/img_MC_cos1_8_samples"),
    ("bmc", "BayesianMonteCarloIntegrator", "out/img_BMC_8_samples"),
    ("bmc-is", "BMCISIntegrator", "out/img_BMCIS_8_samples")])
def test_the_integrators_of_practices_3_and_4_take_samples_and_pools(command_line, capsys,
                                                                       name, class_name,
                                                                       filename):
    args = command_line(["--integrator", name, "--samples", "8"]
                        + (["--pool", "3"] if name != "cmc-is" else []))
    assert args.scene == "sphere-map"
    integrator = AppRenderer.make_integrator(name, "out/img", samples=args.samples,
                                             pool=args.pool)
    assert type(integrator).__name__ == class_name and integrator.n_samples == 8
    assert integrator.get_filename().replace("\\", "/") == filename
    out = capsys.readouterr().out
    if name == "cmc-is":
        assert out == ""
    else:  # what the GPs cost, said once, before any render
        assert len(integrator.myGP) == 3 and all(len(gp.weights) == 8 for gp in integrator.myGP)
        assert out.count("Made 3 GPs of 8 samples each") == 1


def test_a_pool_only_applies_to_the_bayesian_integrators(command_line, capsys):
    with pytest.raises(SystemExit):
        command_line(["--integrator", "cmc", "--pool", "3"])
    assert "argument --pool: only applies with --integrator bmc or bmc-is" in (
        capsys.readouterr().err)


def test_the_monte_carlo_integrator_renders_figure_3_of_practice_2_by_default(command_line):
    args = command_line(["--integrator", "cmc"])
    assert (args.scene, args.samples) == ("sphere-map", None)  # None: DEFAULT_SAMPLES, 40
    integrator = AppRenderer.make_integrator("cmc", "out/img", samples=args.samples)
    assert (type(integrator).__name__, integrator.n_samples) == ("CMCIntegrator", 40)
    assert integrator.get_filename() == "out/img_MC_40_samples"
    assert command_line(["--integrator", "cmc", "--scene", "cornell-area",
                         "--samples", "8"]).samples == 8


def test_an_out_folder_that_cannot_be_written_is_said_in_one_line(tmp_path, capsys,
                                                                   monkeypatch):
    # a file where the folder should be: nothing can be saved inside it
    blocked = tmp_path / "a_file"
    blocked.write_text("")
    monkeypatch.setattr(sys, "argv", ["AppRenderer.py"])
    assert AppRenderer.main(["--out", str(blocked / "out"), "--width", "4", "--height", "4",
                             "--no-window"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("AppRenderer.py: error: render: cannot write the images to ")
    assert "choose another output folder" in err and "Traceback" not in err


def test_adaptive_sampling_is_refused_for_monte_carlo_noise(command_line, capsys):
    assert usage_error(command_line, capsys, ["--integrator", "cmc", "--spp", "4",
                                              "--adaptive"]).endswith(
        "give --samples N instead")


def test_samples_are_refused_for_an_integrator_that_takes_none(command_line, capsys):
    assert usage_error(command_line, capsys, ["--samples", "8"]) == (
        "AppRenderer.py: error: argument --samples: only applies with a Monte Carlo "
        "--integrator (cmc, cmc-is, bmc, bmc-is)")


def test_the_monte_carlo_integrator_renders_from_the_command_line(tmp_path, capsys,
                                                                   monkeypatch):
    # The sphere scene lit by the course's map, which is not here: PyRT's sky stands in,
    # and one line says so; the top row sees the sky, which is nowhere black.
    monkeypatch.chdir(tmp_path)
    assert AppRenderer.main(["--integrator", "cmc", "--samples", "2", "--width", "8",
                             "--height", "8", "--workers", "1", "--no-window",
                             "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "PyRT's own sky map stands in" in out
    image = np.load(tmp_path / "rendered_image_MC_2_samples.npy")
    assert image.shape == (8, 8, 3) and (image[0] > 0.0).all()


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
    """The arguments of every render() call of the course's integrators (they inherit
    Integrator.render, LazyIntegrator has its own with the same arguments), which still
    renders."""
    calls = []

    def record(cls):
        original = cls.render
        signature = inspect.signature(original)

        def recording(*args, **kwargs):
            bound = signature.bind(*args, **kwargs)
            bound.apply_defaults()
            calls.append({name: value for name, value in bound.arguments.items()
                          if name != "self"})
            return original(*args, **kwargs)

        monkeypatch.setattr(cls, "render", recording)

    record(Integrator)
    record(LazyIntegrator)
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
