"""`python AppRenderer.py --explain X,Y` and a click on the window: a pixel's history where
students render (see tests/test_explain.py for the histories themselves)."""
import sys
from types import SimpleNamespace

import pytest

import cv2

import AppRenderer
from helpers import APP, read_png, run_python
from pyrt.explain import opencv_click
from PyRT_Integrators import PhongIntegrator


def test_explain_prints_the_story_of_a_pixel_in_the_shadow_and_saves_its_picture(tmp_path):
    # Pixel (25, 45) of the 50 x 50 Cornell box looks along (0.02 t, -0.82 t, -1) with
    # t = tan 35 = 0.700 and meets the floor y = -1 at about (0.024, -1, -1.74), well
    # inside the shadow of the sphere from light 0 straight above it: the light is 1.5
    # above the floor and 0.5 above the sphere's centre, so the shadow's radius is
    # 1.5 tan(asin(0.25/0.5)) = 0.87 (tests/test_explain.py works out the other lights).
    result = run_python([APP, "--no-window", "--width", "50", "--height", "50",
                         "--workers", "1", "--explain", "25,45", "--out", tmp_path],
                        cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "Pixel (25, 45) of PhongIntegrator" in out
    assert "camera ray -> closest_hit: object 2 (Parallelogram)" in out
    assert "shadow ray to light 0 -> any_hit True: blocked by object 0 (Sphere)" in out
    picture = tmp_path / "pixel_25_45.png"
    assert f"Saved {picture}" in out
    assert read_png(picture).shape == (450, 990, 3)


def explain_error(monkeypatch, capsys, argv):
    """The last line of what parse_args(argv) writes before it exits with status 2."""
    monkeypatch.setattr(sys, "argv", ["AppRenderer.py"])
    with pytest.raises(SystemExit) as exited:
        AppRenderer.parse_args(argv)
    assert exited.value.code == 2
    return capsys.readouterr().err.splitlines()[-1]


@pytest.mark.parametrize("argv, message", [
    (["--explain", "25"], "must be a pixel X,Y such as 250,400 (two whole numbers from 0), "
                          "got '25'"),
    (["--explain", "a,b"], "must be a pixel X,Y such as 250,400 (two whole numbers from 0), "
                           "got 'a,b'"),
    (["--explain=-1,3"], "must be a pixel X,Y such as 250,400 (two whole numbers from 0), "
                            "got '-1,3'"),
    (["--width", "50", "--explain", "50,3"],
     "pixel (50, 3) is not in the 50 x 500 image: x goes from 0 to 49, y from 0 to 499"),
    (["--explain", "3,500"],
     "pixel (3, 500) is not in the 500 x 500 image: x goes from 0 to 499, y from 0 to 499"),
    (["--all-figures", "--explain", "3,5"],
     "explains a pixel of one image; leave out --all-figures"),
])
def test_a_bad_pixel_gets_one_line_that_says_what_to_give(monkeypatch, capsys, argv, message):
    assert explain_error(monkeypatch, capsys, argv) == (
        f"AppRenderer.py: error: argument --explain: {message}")


def test_a_good_pixel_is_read_as_x_then_y(monkeypatch):
    monkeypatch.setattr(sys, "argv", ["AppRenderer.py"])
    assert AppRenderer.parse_args(["--explain", "499,0"]).explain == (499, 0)


def click(x, y, button=1, mode=""):
    """A button_press_event at the point (x, y) of the image's axes (None: outside them)."""
    return SimpleNamespace(xdata=x, ydata=None if x is None else y, button=button,
                           canvas=SimpleNamespace(toolbar=SimpleNamespace(mode=mode)))


@pytest.mark.parametrize("event, pixel", [
    (click(24.6, 3.4), (25, 3)),        # the centre of pixel (x, y) is drawn at (x, y)
    (click(-0.5, -0.5), (0, 0)),        # the top left corner of the image
    (click(49.49, 9.49), (49, 9)),      # near the bottom right corner
    (click(49.5, 3.0), None),           # right of the image
    (click(None, None), None),          # outside the axes
    (click(3.0, 3.0, button=3), None),  # the right button
    (click(3.0, 3.0, mode="zoom rect"), None),  # zooming, not asking
])
def test_a_click_falls_on_the_pixel_under_it(event, pixel):
    assert AppRenderer.clicked_pixel(event, 50, 10) == pixel


def test_a_left_click_on_an_opencv_window_prints_the_pixels_story(capsys):
    integrator = PhongIntegrator("unused")
    integrator.add_scene(AppRenderer.sphere_test_scene())
    callback = opencv_click(integrator)
    callback(cv2.EVENT_MOUSEMOVE, 0, 0, 0, None)
    assert capsys.readouterr().out == ""
    callback(cv2.EVENT_LBUTTONDOWN, 0, 0, 0, None)  # pixel (0, 0) sees the background
    assert capsys.readouterr().out.startswith("Pixel (0, 0) of PhongIntegrator")


def test_a_click_on_the_window_of_a_render_prints_that_pixels_story(tmp_path, monkeypatch,
                                                                    capsys):
    handlers = []
    monkeypatch.setattr(AppRenderer, "show", lambda png, on_click=None: handlers.append(
        on_click))
    assert AppRenderer.main(["--width", "8", "--height", "8", "--workers", "1",
                             "--scene", "sphere", "--out", str(tmp_path)]) == 0
    capsys.readouterr()
    [on_click] = handlers
    on_click(0, 0)  # the top left corner looks up, past the sphere, at nothing
    out = capsys.readouterr().out
    assert out.startswith("Pixel (0, 0) of PhongIntegrator")
    assert "camera ray -> closest_hit: no hit" in out
    assert (tmp_path / "pixel_0_0.png").is_file()
