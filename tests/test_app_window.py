"""AppRenderer.py's window: it shows an image pixel for pixel, with the backends that open
windows and those that write files; and VSCode finds the run configurations and the tests."""
import json
from pathlib import PurePosixPath, PureWindowsPath
from types import SimpleNamespace

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.backend_bases import ResizeEvent

import AppRenderer
from helpers import REPO


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
