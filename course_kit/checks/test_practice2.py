"""Your checks of Practice 2: one test per check, named after its assignment step.

    python -m pytest                 all of them
    python -m pytest -k 2_3          Assignment 2.3 only

Assignment 2.1's checks call your compute_estimate_cmc; Assignment 2.3's render two small
scenes whose right answer is known in closed form with your CMCIntegrator. The integrator's
answer is random: a check compares the mean of your pixels with the closed form, within a
tolerance that a correct integrator exceeds with a chance of at most one in a million
(practice2_checks.py says how). A failing test says what differs, names the mistake when it
recognises it, and writes your image or curve and the expected one into out/checks/.
Assignments 2.2 and 2.4 are optional: their tests only run your code.
"""
import os
import subprocess
import sys

import numpy as np
import pytest

from practice2_checks import OUT, PROJECT, run_check
import practice2_render
import practice2_scenes

WORKBENCH_SECONDS = 600


def passes(name):
    check = run_check(name)
    if not check.passed:
        pytest.fail(check.report(), pytrace=False)


def test_assignment_2_1_estimate():
    passes("estimate")


def test_assignment_2_1_workbench_curve():
    passes("curve")


def test_assignment_2_3_white_furnace():
    passes("furnace")


def test_assignment_2_3_emitter():
    passes("emitter")


def test_optional_2_2_the_workbench_runs():
    """AppWorkbench.py runs to its end (a few estimates only, no window)."""
    environment = dict(os.environ, MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, "AppWorkbench.py", "--no-window", "--estimates",
                           "20"], cwd=PROJECT, env=environment, capture_output=True,
                          text=True, timeout=WORKBENCH_SECONDS)
    if done.returncode != 0:
        pytest.fail("Assignment 2.2 (optional): AppWorkbench.py ended with exit code "
                    f"{done.returncode}:\n{done.stderr[-2000:]}", pytrace=False)


def test_optional_2_4_render_loop_runs():
    """The CMCIntegrator renders a small image through your render() (Assignment 2.4's
    images come out of it), every pixel a finite colour."""
    try:
        image = practice2_render.render_loop_image(practice2_scenes.PUBLISHED,
                                                   OUT / "render_loop")
    except Exception as error:
        pytest.fail("Assignment 2.4 (optional): render() with the CMCIntegrator raised "
                    f"{type(error).__name__}: {error}", pytrace=False)
    if image is None:
        pytest.skip("Assignment 2.4 (optional) needs Assignment 2.3's compute_color first")
    if not np.all(np.isfinite(image)):
        pytest.fail("Assignment 2.4 (optional): the image that render() makes with the "
                    "CMCIntegrator has pixels that are not finite", pytrace=False)
