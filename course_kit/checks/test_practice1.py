"""Your checks of Practice 1: one test per check, named after its assignment step.

    python -m pytest                 all of them
    python -m pytest -k 1_3          Assignment 1.3 only

Each renders the course's scenes small with your own code and compares the image with the
one the finished framework renders. A failing test says what differs and where, names the
mistake when it recognises it, and writes your image, the expected one and their
difference into out/checks/. practice1_checks.py states the rule for a right image."""
import pytest

from practice1_checks import run_check


def passes(name):
    check = run_check(name)
    if not check.passed:
        pytest.fail(check.report(), pytrace=False)


def test_assignment_1_1_lazy_image():
    passes("lazy")


def test_assignment_1_2_any_hit():
    passes("any_hit")


def test_assignment_1_2_render_loop_rays():
    passes("probe")


def test_assignment_1_2_intersection_image():
    passes("intersection")


def test_assignment_1_3_depth_image():
    passes("depth")


def test_assignment_1_3_normal_image():
    passes("normal")


def test_assignment_1_4_phong_sphere_scene():
    passes("phong_sphere")


def test_assignment_1_4_phong_cornell_box():
    passes("phong_cornell")
