"""The course kit of Practice 1 (course_kit/handout.py): the handout made from the marked framework,
the students' checks in it, and the grader of submissions."""
import csv
import hashlib
import html
import html.parser
import json
import random
import re
import shutil
import sys
import textwrap
import zipfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest

import course_kit.__main__
import course_kit.feedback
import course_kit.grader
import course_kit.handout
import course_kit.isolation
import course_kit.judging
import course_kit.references
import course_kit_students as students
from helpers import REPO, matrix_on_the_main_python_only, run_python
from PyRT_Common import Vector3D

sys.path.insert(0, str(course_kit.handout.CHECKS))
import practice1_checks as checks  # noqa: E402  (found through the line above)
import practice1_render as render  # noqa: E402

HANDOUT_FILES = [
    ".vscode/launch.json", ".vscode/settings.json", "AppRenderer.py", "PyRT_Common.py",
    "PyRT_Core.py", "PyRT_Integrators.py", "out/.gitkeep", "pyrt/__init__.py",
    "pyrt/compare.py", "pyrt/environment_maps.py", "pyrt/explain.py",
    "pyrt/explain_picture.py", "pyrt/images.py",
    "pytest.ini", "references/figure1_phong.png", "references/figure2_lazy.png",
    "references/figure3_intersection.png", "references/figure4_depth.png",
    "references/figure4_normal.png", "references/figure5_phong.png", "requirements.txt",
    "tests/expected/practice1.npz", "tests/practice1_checks.py", "tests/practice1_render.py",
    "tests/test_practice1.py"]
CHECK_TESTS = {  # the students' tests, by the step in their names
    "test_assignment_1_1_lazy_image": "1.1", "test_assignment_1_2_any_hit": "1.2",
    "test_assignment_1_2_render_loop_rays": "1.2",
    "test_assignment_1_2_intersection_image": "1.2", "test_assignment_1_3_depth_image": "1.3",
    "test_assignment_1_3_normal_image": "1.3", "test_assignment_1_4_phong_sphere_scene": "1.4",
    "test_assignment_1_4_phong_cornell_box": "1.4"}


def tree(folder):
    """{relative path: bytes} of every file under folder."""
    return {path.relative_to(folder).as_posix(): path.read_bytes()
            for path in sorted(Path(folder).rglob("*")) if path.is_file()}


@pytest.fixture(scope="session")
def handout(tmp_path_factory):
    return course_kit.handout.write_handout(tmp_path_factory.mktemp("kit") / "handout")


def with_framework(handout, folder):
    """A copy of the handout in folder with the finished framework's modules in it."""
    shutil.copytree(handout, folder)
    for path in REPO.glob("PyRT_*.py"):
        shutil.copyfile(path, folder / path.name)
    shutil.copyfile(REPO / "AppRenderer.py", folder / "AppRenderer.py")
    shutil.copytree(REPO / "pyrt", folder / "pyrt", dirs_exist_ok=True,
                    ignore=shutil.ignore_patterns("__pycache__"))
    return folder


# ------------------------------------------------------------------------------------------
# The handout
# ------------------------------------------------------------------------------------------
def test_the_handout_holds_the_course_modules_and_what_they_need(handout):
    assert sorted(tree(handout)) == HANDOUT_FILES
    assert (handout / "pytest.ini").read_text() == course_kit.handout.PYTEST_INI
    requirements = (handout / "requirements.txt").read_text().split("\n")[1:]
    assert [re.match(r"[\w.-]+", line)[0] for line in requirements if line] == [
        "numpy", "opencv-python-headless", "matplotlib", "pytest"]


def test_the_handout_is_the_same_on_every_run(handout, tmp_path):
    again = course_kit.handout.write_handout(tmp_path / "again")
    assert tree(again) == tree(handout)


def test_the_handout_goes_into_a_new_folder_only(tmp_path, capsys):
    (tmp_path / "notes.txt").write_text("mine")
    with pytest.raises(SystemExit) as exited:
        course_kit.__main__.main(["handout", str(tmp_path)])
    assert exited.value.code == f"course_kit handout: {tmp_path} is not empty; the " \
                                "handout goes into a new folder"
    assert tree(tmp_path) == {"notes.txt": b"mine"}


def solution_lines():
    """The lines of the framework's solution blocks that appear nowhere else in the
    framework (stripped, comments and blank lines left out)."""
    blocked, elsewhere = set(), set()
    for name in course_kit.handout.COURSE_MODULES:
        source = (REPO / name).read_text(encoding="utf-8")
        lines = source.splitlines()
        inside = set()
        for block in course_kit.handout.marked_blocks(source, name):
            inside.update(range(block.begin, block.end + 1))
            if block.kind != course_kit.handout.FRAMEWORK_ONLY:
                blocked.update(line.strip() for line in lines[block.begin:block.end - 1])
        elsewhere.update(line.strip() for number, line in enumerate(lines, 1)
                         if number not in inside)
    stubs = {line.strip() for line in course_kit.handout.RENDER_STUB.splitlines()} | set(
        course_kit.handout.BODY_STUBS.values())
    return {line for line in blocked - elsewhere - stubs if line and not line.startswith("#")}


def test_no_line_of_the_solution_is_left_in_the_handout(handout):
    distinctive = solution_lines()
    assert len(distinctive) >= 10  # the solution of every step has lines of its own
    texts = {name: content.decode("utf-8") for name, content in tree(handout).items()
             if not name.endswith((".png", ".npz"))}
    for name, text in texts.items():
        stripped = {line.strip() for line in text.splitlines()}
        assert not distinctive & stripped, name
        assert not re.search(r"^\s*(from|import) PyRT_(Rendering|Sampling|Workers|Acceleration)",
                             text, re.MULTILINE), name
        assert not re.search(r"# (ASSIGNMENT \S+|FRAMEWORK ONLY) (BEGIN|END)", text), name
    # The expected images are the only data made from the solution
    binary = sorted(name for name in tree(handout) if name.endswith((".png", ".npz")))
    assert binary == [f"references/{name}" for name in course_kit.handout.FIGURES] + [
        "tests/expected/practice1.npz"]


def test_the_handout_has_the_courses_stubs(handout):
    integrators = (handout / "PyRT_Integrators.py").read_text()
    assert textwrap.indent(course_kit.handout.RENDER_STUB, "    ") in integrators
    for step, count in (("1.2", 1), ("1.3", 2), ("1.4", 1)):
        assert integrators.count(f"        # ASSIGNMENT {step}: PUT YOUR CODE HERE\n"
                                 "        pass\n") == count
    assert "        # ASSIGNMENT 1.2: PUT YOUR CODE HERE\n        return False\n" in (
        handout / "PyRT_Core.py").read_text()


def test_the_handout_renders_the_green_image(handout, tmp_path):
    folder = shutil.copytree(handout, tmp_path / "run")
    result = run_python(["AppRenderer.py"], cwd=folder)
    assert result.returncode == 0, result.stderr
    png = plt.imread(folder / "out" / "rendered_image_Phong.png")[:, :, :3]
    assert png.shape == (500, 500, 3) and np.all(png == (0.0, 1.0, 0.0))
    assert "100%" in result.stdout


def failures_of_the_checks(folder):
    """{test name: its failure message, or None when it passed} of `python -m pytest` run
    in folder, from pytest's JUnit XML report."""
    report = folder / "report.xml"
    result = run_python(["-m", "pytest", "-q", "-p", "no:cacheprovider",
                         f"--junitxml={report}"], cwd=folder)
    assert report.exists(), result.stdout + result.stderr  # pytest itself failed
    text = report.read_text(encoding="utf-8")
    cases = re.findall(r'<testcase [^>]*name="(\w+)"[^>]*?(/>|>(.*?)</testcase>)', text,
                       re.DOTALL)
    return {name: (html.unescape(re.search(r'message="([^"]*)"', body).group(1)).removeprefix(
        "Failed: ") if body else None) for name, _, body in cases}


def test_on_the_untouched_handout_every_check_fails_with_its_steps_message(handout, tmp_path):
    failures = failures_of_the_checks(shutil.copytree(handout, tmp_path / "untouched"))
    assert sorted(failures) == sorted(CHECK_TESTS)
    for name, message in failures.items():
        assert message is not None and message.startswith(
            f"Assignment {CHECK_TESTS[name]}, "), name
    assert "GREEN" in failures["test_assignment_1_1_lazy_image"]
    assert "answers False for every ray that hits" in failures["test_assignment_1_2_any_hit"]
    for name in ("test_assignment_1_3_depth_image", "test_assignment_1_4_phong_cornell_box"):
        assert "compute_color returned None" in failures[name]


def test_on_the_finished_framework_every_check_passes(handout, tmp_path):
    failures = failures_of_the_checks(with_framework(handout, tmp_path / "framework"))
    assert failures == dict.fromkeys(CHECK_TESTS)


# ------------------------------------------------------------------------------------------
# Markers
# ------------------------------------------------------------------------------------------
MARKED = '''\
import os
# FRAMEWORK ONLY BEGIN
import fast
# FRAMEWORK ONLY END


class Integrator:
    # ASSIGNMENT 1.1-1.2 BEGIN
    def render(self, workers=None):
        fast.render(self)
    # ASSIGNMENT 1.1-1.2 END

    # FRAMEWORK ONLY BEGIN
    def render_row(self, y):
        return []
    # FRAMEWORK ONLY END

    def any_hit(self, ray):
        """Docstring stays."""
        # ASSIGNMENT 1.2 BEGIN
        return any(ray)
        # ASSIGNMENT 1.2 END

    def compute_color(self, ray):
        # ASSIGNMENT 1.4 BEGIN
        return ray
        # ASSIGNMENT 1.4 END
'''


def test_each_block_is_replaced_by_its_stub_at_its_indentation():
    assert course_kit.handout.strip_solution(MARKED, "example.py") == (
        "import os\n\n\nclass Integrator:\n"
        + textwrap.indent(course_kit.handout.RENDER_STUB, "    ")
        + '\n    def any_hit(self, ray):\n        """Docstring stays."""\n'
        "        # ASSIGNMENT 1.2: PUT YOUR CODE HERE\n        return False\n\n"
        "    def compute_color(self, ray):\n"
        "        # ASSIGNMENT 1.4: PUT YOUR CODE HERE\n        pass\n")


@pytest.mark.parametrize("change, message", [
    (("    # ASSIGNMENT 1.1-1.2 END\n", ""),
     "example.py, line 12: a block begins inside the block begun at line 8"),
    (("        # ASSIGNMENT 1.2 BEGIN\n", ""),
     "example.py, line 21: '# ASSIGNMENT 1.2 END' does not close a block: no block is open"),
    (("        # ASSIGNMENT 1.4 END\n", ""),
     "example.py, line 25: the block begun here is never closed"),
    (("# ASSIGNMENT 1.4 BEGIN", "# ASSIGNMENT 1.5 BEGIN"),
     "example.py, line 25: unknown step '1.5'; the steps are 1.1-1.2, 1.2, 1.3, 1.4"),
    (("# ASSIGNMENT 1.2 BEGIN", "# ASSIGNMENT 1.2 BEGN"),
     "example.py, line 20: not a marker the kit knows: '# ASSIGNMENT 1.2 BEGN'"),
    (("# FRAMEWORK ONLY BEGIN\nimport", "#FRAMEWORK ONLY BEGIN\nimport"),
     "example.py, line 2: not a marker the kit knows: '#FRAMEWORK ONLY BEGIN'"),
    (("        # ASSIGNMENT 1.4 END", "    # ASSIGNMENT 1.4 END"),
     "example.py, line 27: '# ASSIGNMENT 1.4 END' does not close a block: the block begun "
     "at line 25 is ASSIGNMENT 1.4 at indentation 8"),
    (("ASSIGNMENT 1.4", "ASSIGNMENT 1.3"), None),
    (("ASSIGNMENT 1.2 ", "ASSIGNMENT 1.3 "),
     "example.py, line 20: a block of step 1.3 in 'any_hit', where that step has no stub"),
    (("ASSIGNMENT 1.2 END", "ASSIGNMENT 1.3 END"), "example.py, line 22: '# ASSIGNMENT 1.3 "
     "END' does not close a block: the block begun at line 20 is ASSIGNMENT 1.2"),
])
def test_a_marker_the_kit_cannot_read_stops_it_with_the_file_and_line(change, message):
    source = MARKED.replace(*change)
    assert source != MARKED
    if message is None:  # the same stub for another step: allowed
        assert "# ASSIGNMENT 1.3: PUT YOUR CODE HERE" in course_kit.handout.strip_solution(
            source, "example.py")
        return
    with pytest.raises(course_kit.handout.MarkerError) as error:
        course_kit.handout.strip_solution(source, "example.py")
    assert str(error.value).startswith(message)


def test_a_second_block_of_render_methods_is_refused():
    source = MARKED.replace(
        "    # FRAMEWORK ONLY BEGIN\n    def render_row",
        "    # ASSIGNMENT 1.1-1.2 BEGIN\n    def render_row").replace(
        "        return []\n    # FRAMEWORK ONLY END",
        "        return []\n    # ASSIGNMENT 1.1-1.2 END")
    with pytest.raises(course_kit.handout.MarkerError, match=r"^example.py, line 13: a second block "
                                                     r"of step 1.1-1.2"):
        course_kit.handout.strip_solution(source, "example.py")


# ------------------------------------------------------------------------------------------
# The checks and their expected data
# ------------------------------------------------------------------------------------------
def test_the_expected_data_is_what_the_framework_renders():
    # Fails when the framework's images change: then remake the data on purpose, with
    # `python -m course_kit expected`, and say why in the commit.
    arrays = course_kit.references.expected_arrays()
    assert course_kit.references.npz_bytes(arrays) == course_kit.handout.EXPECTED.read_bytes()


def test_the_checks_scenes_are_apprenderers():
    import AppRenderer
    from PyRT_Integrators import PhongIntegrator
    for ours, theirs in ((render.sphere_scene(), AppRenderer.sphere_test_scene(
            width=render.SIZE, height=render.SIZE)), (render.cornell_box(),
                                                      AppRenderer.cornell_box_scene(
                                                          0.75, 2, width=render.SIZE,
                                                          height=render.SIZE))):
        images = [render.traced_image(PhongIntegrator("unused"), scene)
                  for scene in (ours, theirs)]
        assert np.array_equal(*images)
        assert [type(obj) for obj in ours.object_list] == [type(obj)
                                                           for obj in theirs.object_list]


def data_2x2():
    """Expected data of a 2 x 2 image "img" with one seam pixel, (x 1, y 0), whose rays
    also see (0, 0, 0)."""
    return {"img": np.array([[[0.5, 0.5, 0.5], [0.25, 0.0, 1.0]],
                             [[1e-12, 0.0, 0.0], [2.0, 2.0, 2.0]]]),
            "img.seam_pixels": np.array([[0, 1]]),
            "img.seam_colors": np.array([[[0.25, 0.0, 1.0], [0.0, 0.0, 0.0]]])}


def test_a_right_image_equals_the_expected_one_to_a_millionth_or_takes_a_seams_other_side():
    data = data_2x2()
    image = data["img"].copy()
    image[0, 0, 0] = 0.5 + 0.4e-6    # within 1e-9 + 1e-6 * 0.5
    image[1, 0, 0] = 0.9e-9          # within 1e-9 of 1e-12
    image[0, 1] = (0.0, 0.0, 0.0)    # the seam's other side
    image[1, 1, 2] = 2.0 + 1.9e-6    # within 1e-9 + 1e-6 * 2
    assert checks.right_pixels(image, "img", data).all()
    assert checks.judge(image, "img", data).right


def test_a_pixel_off_by_more_or_with_another_sides_colour_away_from_a_seam_is_wrong():
    data = data_2x2()
    image = data["img"].copy()
    image[0, 0, 1] = 0.5 + 0.6e-6    # beyond 1e-9 + 1e-6 * 0.5
    image[1, 1] = (0.0, 0.0, 0.0)    # a seam's colour, but not at a seam
    image[0, 1] = (0.25, 0.5, 1.0)   # at the seam, neither side
    assert checks.right_pixels(image, "img", data).tolist() == [[False, False], [True, False]]
    verdict = checks.judge(image, "img", data)
    assert verdict.reason == "3 of 4 pixels differ from the expected image"
    assert verdict.details == (
        "  where: x 0 to 1, y 0 to 1 (x to the right, y down, from 0); first: (0, 0) is "
        "(0.5, 0.500001, 0.5), expected (0.5, 0.5, 0.5); (1, 0) is (0.25, 0.5, 1), "
        "expected (0.25, 0, 1); (1, 1) is (0, 0, 0), expected (2, 2, 2)")


def test_an_image_of_a_known_mistake_is_named():
    data = checks.expected_data()
    assert checks.likely_mistake(data["depth"][::-1], "depth", data) == (
        checks.LIKELY["upside_down"])
    assert checks.likely_mistake(data["phong_cornell.mistake.no_shadows"], "phong_cornell",
                                 data) == checks.LIKELY["no_shadows"]
    assert checks.likely_mistake(np.zeros((40, 40, 3)), "intersection", data) == (
        checks.BLACK_HINTS["intersection"])
    assert checks.likely_mistake(data["depth"] * 0.5, "depth", data) is None
    # A depth left unclamped is named by its shape, whatever the grey of a miss: right
    # where the expected grey is above 0, below 0 wherever it differs
    for miss in (-np.inf, -199999.0):
        unclamped = data["depth.mistake.unclamped_depth"].copy()
        unclamped[np.all(data["depth"] == 0.0, axis=2) & np.all(unclamped == 0.0, axis=2)] = miss
        assert checks.likely_mistake(unclamped, "depth", data) == (
            checks.LIKELY["unclamped_depth"]), miss
    assert checks.likely_mistake(-data["depth"], "depth", data) != (
        checks.LIKELY["unclamped_depth"])  # wrong where the clamp changes nothing


@pytest.mark.parametrize("exponent", [1.0, 1.5, 3.0])
def test_a_lights_falloff_is_fitted_from_the_image_itself(exponent):
    data = checks.expected_data()
    image = render.traced_image(course_kit.references.PhongVariant("unused", falloff=exponent),
                                render.sphere_scene())
    assert checks.fitted_falloff(image, "phong_sphere", data) == pytest.approx(exponent,
                                                                              abs=1e-6)
    named = checks.likely_mistake(image, "phong_sphere", data)
    assert named == (checks.LIKELY["inverse_distance"] if exponent == 1.0 else
                     f"the light's contribution falls off as 1/r^{exponent:g}, where r is "
                     "the distance from the point to the light and the falloff is 1/r^2: "
                     "divide by r * r")
    # Right, scaled, or wrong in another way, an image has no falloff of its own
    for other in (data["phong_sphere"], image * 2.0,
                  data["phong_sphere.mistake.no_shadows"]):
        assert checks.fitted_falloff(other, "phong_sphere", data) is None
    probe = data["probe"].copy()
    probe[3, 4] = (-1.0, -1.0, -1.0)  # what RayProbe gives a ray from elsewhere
    assert checks.likely_mistake(probe, "probe", data) == checks.LIKELY["not_from_camera"]


def test_an_image_that_the_courses_tonemapper_shows_as_the_figure_is_right_with_a_note():
    # The course's tonemapper maps an image's smallest value to 0 and its largest to 1: an
    # image that is the expected one scaled by a > 0 and shifted by b makes the same PNG.
    data = checks.expected_data()
    red_255 = checks.judge(data["intersection"] * 255.0, "intersection", data)
    assert red_255.right
    assert red_255.note.startswith("your red is 255 where PyRT's is 1. The course's "
                                   "tonemapper maps")
    assert "matters once lights add up in Phong" in red_255.note
    times_pi = checks.judge(data["phong_sphere"] * np.pi, "phong_sphere", data)
    assert times_pi.right and times_pi.note.startswith("your values are 3.14159 times the "
                                                       "expected ones.")
    shifted = checks.judge(data["depth"] * 2.0 + 0.5, "depth", data)
    assert shifted.right and shifted.note.startswith("your values are the expected ones "
                                                     "times 2, plus 0.5.")
    assert checks.judge(data["normal"], "normal", data).note == ""


def test_an_image_that_the_tonemapper_shows_otherwise_is_still_wrong():
    data = checks.expected_data()
    assert not checks.judge(data["phong_sphere"] * (1.0, 2.0, 1.0), "phong_sphere", data).right
    assert not checks.judge(1.0 - data["depth"], "depth", data).right  # a negative scale
    assert not checks.judge(np.full((40, 40, 3), 0.5), "depth", data).right  # flat
    assert not checks.judge(data["probe"] * 2.0, "probe", data).right  # no figure shows it
    nan = data["depth"] * 2.0
    nan[0, 0, 0] = np.nan
    assert not checks.judge(nan, "depth", data).right


def test_the_seams_of_the_cornell_box_take_the_background_the_courses_arithmetic_sees():
    # At 40 x 40 pixels the rays of (35, 4) and (4, 35) pass through corners of the box
    # (the ceiling meets a side wall, the floor the other); the course's arithmetic has no
    # edge tolerance and lets them through to the black background.
    data = checks.expected_data()
    seams = {tuple(pixel): colours for pixel, colours
             in zip(data["phong_cornell.seam_pixels"].tolist(),
                    data["phong_cornell.seam_colors"])}
    for x, y in ((35, 4), (4, 35)):
        assert np.any(np.all(seams[(y, x)] == 0.0, axis=1)), (x, y)
        image = data["phong_cornell"].copy()
        image[y, x] = 0.0
        assert checks.judge(image, "phong_cornell", data).right
    away = data["phong_cornell"].copy()
    away[20, 10] = 0.0  # the left wall, far from every edge
    assert not checks.judge(away, "phong_cornell", data).right


def test_the_ray_probe_reads_the_numpy_arrays_of_the_2021_22_ray():
    assert render.components(np.array([0, 0, 0])) == (0.0, 0.0, 0.0)
    assert render.components(np.array([0.25, -1.0, 2.0])) == (0.25, -1.0, 2.0)
    assert render.components(Vector3D(1, 2, 3)) == (1.0, 2.0, 3.0)


def test_a_passed_check_with_a_note_shows_it_without_marking_anything_wrong():
    check = {"name": "intersection", "title": "the Intersection image (Figure 3)",
             "passed": True, "reason": "", "note": "your red is 255 where PyRT's is 1",
             "message": "right", "error": "", "images": {}}
    step = {"step": "1.2", "title": course_kit.grader.STEP_TITLES["1.2"], "points": 25,
            "max_points": 25, "passed": True, "reason": "", "output": "", "checks": [check]}
    record = {"submission": "s", "files": {}, "problems": [], "steps": [step], "total": 25,
              "max_total": 25}
    page = course_kit.feedback.feedback_html(record)
    assert "Worth knowing: your red is 255 where PyRT&#x27;s is 1." in page
    assert "wrong" not in page and 'class="failed"' not in page


# ------------------------------------------------------------------------------------------
# The grader
# ------------------------------------------------------------------------------------------
LIMITS = """\
[points]
"1.1" = 10
"1.2" = 20
"1.3" = 30
"1.4" = 40.5

[limits]
cpu_seconds = 3
wall_seconds = 300
memory_mib = 1536
output_kib = 256
"""
PASS = None  # a step that passes
# Per submission, per step: PASS or a part of the reason for failing it
VERDICTS = {
    "handout_untouched": {"1.1": "every pixel is GREEN",
                          "1.2": "answers False for every ray that hits",
                          "1.3": "DepthIntegrator.compute_color returned None",
                          "1.4": "PhongIntegrator.compute_color returned None"},
    "framework": {},
    "right": {},
    "right_other_style": {},
    "right_zipped": {},
    # a mistake of render() costs its own steps: in 1.3 and 1.4 compute_color counts
    "upside_down": dict.fromkeys(("1.1", "1.2"), "upside down"),
    "transposed": dict.fromkeys(("1.1", "1.2"), "transposed"),
    "corner_rays": dict.fromkeys(("1.1", "1.2"), "top-left corners"),
    "any_hit_first_object_only": {"1.2": "any_hit is wrong for 2 of 12 rays"},
    "unclamped_depth_and_no_ambient": {"1.3": "not clamped at 0",
                                       "1.4": "the ambient term, kd (x) i_a, is missing"},
    "unmapped_normals_and_no_shadows": {"1.3": "normals are not mapped to [0, 1]",
                                        "1.4": "there are no shadows"},
    "no_inverse_square": {"1.4": "not divided by r^2"},
    "inverse_distance": {"1.4": "divided by r, the distance from the point to the light"},
    "depth_of_misses_too": {"1.3": "the depth is not clamped at 0"},
    "raises": {"1.2": "raised ZeroDivisionError: float division by zero"},
    "calls_sys_exit": {"1.3": "your code called sys.exit(3)"},
    "calls_os_exit": {"1.3": "the process ended (exit code 7) before the checks were done"},
    "hangs": {"1.4": "used more than 3 s of processor time"},
    "prints_without_end": {"1.4": "printed more than 256 KiB"},
    "allocates_without_bound": {"1.3": "ran out of memory"},
    "starts_a_process": {"1.3": "refused: started a process (os.system)"},
    "writes_outside": {"1.3": "refused: wrote outside its working copy: "},
    "writes_into_the_checks": {"1.3": "refused: wrote into the checks: "},
    "not_a_zip": {"1.1": "every pixel is GREEN",
                  "1.2": "answers False for every ray that hits",
                  "1.3": "DepthIntegrator.compute_color returned None",
                  "1.4": "PhongIntegrator.compute_color returned None"},
    "syntax_error": dict.fromkeys(("1.1", "1.2", "1.3", "1.4"),
                                  "PyRT_Integrators.py, line {line} is not valid Python"),
}


def digest(folder):
    return hashlib.sha256(json.dumps({name: hashlib.sha256(content).hexdigest() for name, content
                                      in tree(folder).items()}).encode()).hexdigest()


@pytest.fixture(scope="session")
def graded(handout, tmp_path_factory):
    """Every submission of VERDICTS graded with the LIMITS: (the submissions' folder, its
    digest before grading, the results' folder, the records, the outside path)."""
    if course_kit.isolation.unsupported():  # Windows: the handout's tests still run
        pytest.skip(course_kit.isolation.unsupported())
    matrix_on_the_main_python_only()
    base = tmp_path_factory.mktemp("grading")
    folder, results, outside = base / "submissions", base / "results", base / "outside.txt"
    folder.mkdir()
    shutil.copytree(handout, folder / "handout_untouched",
                    ignore=lambda _, names: [n for n in names
                                             if n not in course_kit.handout.COURSE_MODULES])
    framework = folder / "framework"
    framework.mkdir()
    for name in course_kit.handout.COURSE_MODULES:
        shutil.copyfile(REPO / name, framework / name)
    students.write_submission(folder / "right", handout, {})
    for name, answers in students.VARIANTS.items():
        students.write_submission(folder / name, handout, answers)
    students.write_submission(folder / "writes_outside", handout, {
        stub: code.replace("{OUTSIDE!r}", repr(str(outside)))
        for stub, code in students.WRITES_OUTSIDE.items()})
    students.write_submission(folder / "writes_into_the_checks", handout,
                              students.WRITES_INTO_THE_CHECKS)
    (folder / "not_a_zip.zip").write_bytes(b"a file of another kind")
    broken = students.write_submission(folder / "syntax_error", handout, {})
    text = (broken / "PyRT_Integrators.py").read_text()
    (broken / "PyRT_Integrators.py").write_text(
        text.replace("    def compute_color(self, ray):\n", students.SYNTAX_ERROR_LINE, 1))
    # A zip whose modules lie in a folder, with a deeper decoy that does not count
    right = students.submission_files(handout, {})
    with zipfile.ZipFile(folder / "right_zipped.zip", "w") as archive:
        for name, text in right.items():
            archive.writestr(f"my_practice/{name}", text)
        archive.writestr("my_practice/venv/lib/PyRT_Core.py", "raise SystemExit('decoy')\n")
    config_path = base / "grading.toml"
    config_path.write_text(LIMITS)
    before = digest(folder)
    records = course_kit.grader.grade_folder(folder, results,
                                         course_kit.grader.load_config(config_path), jobs=2,
                                         progress=False, draws=random.Random(1))
    return folder, before, results, {record["submission"]: record for record in records}, \
        outside, config_path


def syntax_error_line(folder):
    text = (folder / "syntax_error" / "PyRT_Integrators.py").read_text()
    return text.splitlines().index(students.SYNTAX_ERROR_LINE.rstrip("\n")) + 1


@pytest.mark.parametrize("submission", sorted(VERDICTS))
def test_each_submission_gets_the_verdict_it_deserves_step_by_step(graded, submission):
    folder, _, _, records, _, _ = graded
    steps = {step["step"]: step for step in records[submission]["steps"]}
    for step, expected in ((step, VERDICTS[submission].get(step, PASS)) for step in steps):
        if expected is PASS:
            assert steps[step]["passed"] and steps[step]["points"] == steps[step][
                "max_points"], (step, steps[step]["reason"])
        else:
            assert not steps[step]["passed"] and steps[step]["points"] == 0, step
            assert expected.format(line=syntax_error_line(folder)) in steps[step]["reason"], (
                step, steps[step]["reason"])


def test_submissions_are_only_read_and_nothing_is_written_outside(graded):
    folder, before, _, _, outside, _ = graded
    assert digest(folder) == before
    assert not outside.exists()


def test_a_submission_that_cannot_be_read_says_so_and_is_graded_as_the_handout(graded):
    _, _, results, records, _, _ = graded
    assert records["not_a_zip"]["problems"] == [
        "not_a_zip.zip is not a readable zip file (File is not a zip file)"]
    assert records["not_a_zip"]["files"] == dict.fromkeys(course_kit.handout.COURSE_MODULES,
                                                          "handout")
    page = Page((results / "not_a_zip" / "feedback.html").read_text())
    assert "not_a_zip.zip is not a readable zip file (File is not a zip file)" in page.text


def test_the_student_sees_the_lines_of_their_own_code_that_raised(graded):
    _, _, _, records, _, _ = graded
    check = records["raises"]["steps"][1]["checks"][2]
    assert check["name"] == "intersection"
    # The first frame is the student's line; PyRT_Common.py, a file of theirs, follows
    assert re.fullmatch(r'  File "PyRT_Integrators\.py", line \d+, in compute_color\n'
                        r'    return RED / 0\n  File "PyRT_Common\.py", line \d+, in '
                        r'__truediv__\n    .*\nZeroDivisionError: float division by zero\n',
                        check["error"]), check["error"]


def test_grades_csv_has_a_row_per_submission_with_points_total_and_reasons(graded):
    _, _, results, records, _, _ = graded
    with open(results / "grades.csv", newline="", encoding="utf-8") as grades:
        rows = list(csv.reader(grades))
    assert rows[0] == ["submission", "1.1", "1.2", "1.3", "1.4", "total", "reason 1.1",
                       "reason 1.2", "reason 1.3", "reason 1.4"]
    assert [row[0] for row in rows[1:]] == sorted(VERDICTS)
    weights = {"1.1": 10, "1.2": 20, "1.3": 30, "1.4": 40.5}
    for row in rows[1:]:
        verdicts = VERDICTS[row[0]]
        points = [0 if step in verdicts else weights[step] for step in weights]
        assert row[1:6] == [str(p) for p in points] + [str(sum(points))], row
        assert [bool(reason) for reason in row[6:]] == [step in verdicts for step in weights]
        assert all(len(reason) <= course_kit.grader.REASON_LENGTH for reason in row[6:])


def test_results_json_has_the_fields_of_gradescopes_format(graded):
    _, _, results, records, _, _ = graded
    for name, record in records.items():
        result = json.loads((results / name / course_kit.feedback.GRADESCOPE).read_text())
        assert sorted(result) == ["execution_time", "output", "score", "stdout_visibility",
                                  "tests", "visibility"]
        assert result["score"] == sum(test["score"] for test in result["tests"])
        assert [(test["number"], test["name"]) for test in result["tests"]] == list(
            course_kit.grader.STEP_TITLES.items())
        for test in result["tests"]:
            assert sorted(test) == ["max_score", "name", "number", "output", "score",
                                    "status"]
            assert test["status"] in ("passed", "failed")
            assert (test["status"] == "passed") == (test["score"] == test["max_score"])


class Page(html.parser.HTMLParser):
    """The headings, the images' sources and the text of a feedback page."""

    def __init__(self, text):
        super().__init__()
        self.headings, self.images, self.text, self._heading = [], [], [], None
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        if tag in ("h1", "h2", "h3"):
            self._heading = []
        if tag == "img":
            self.images.append(dict(attrs)["src"])

    def handle_endtag(self, tag):
        if tag in ("h1", "h2", "h3"):
            self.headings.append("".join(self._heading))
            self._heading = None

    def handle_data(self, data):
        self.text.append(data)
        if self._heading is not None:
            self._heading.append(data)


def test_the_feedback_page_shows_each_step_its_verdict_and_the_images(graded):
    _, _, results, records, _, _ = graded
    page = Page((results / "unclamped_depth_and_no_ambient" / "feedback.html").read_text())
    assert page.headings[0] == ("Practice 1: unclamped_depth_and_no_ambient, 30 of 100.5 "
                                "points")
    assert [h for h in page.headings if h.startswith("Assignment")] == [
        "Assignment 1.1: the render loop (Lazy integrator): passed, 10 of 10 points",
        "Assignment 1.2: any_hit and the Intersection integrator: passed, 20 of 20 points",
        "Assignment 1.3: the Depth and Normal integrators: failed, 0 of 30 points",
        "Assignment 1.4: the Phong integrator: failed, 0 of 40.5 points"]
    assert page.images[:3] == ["images/1.3_depth_render.png", "images/1.3_depth_expected.png",
                               "images/1.3_depth_difference.png"]
    for source in page.images:
        image = plt.imread(results / "unclamped_depth_and_no_ambient" / source)
        size = records["unclamped_depth_and_no_ambient"]["draw"]["size"]
        assert image.shape[:2] == (size * checks.PNG_SCALE,) * 2
    assert "likely mistake: the depth is not clamped at 0" in "".join(page.text)


def test_a_wrong_phong_image_tells_its_first_wrong_pixel_beside_the_frameworks_story(graded):
    # Without shadows, a pixel of the Cornell box is wrong only where the framework finds
    # a light blocked; inside the box, whose walls face inwards with the lights inside it,
    # only the sphere (object 0) can block one.
    _, _, results, records, _, _ = graded
    record = records["unmapped_normals_and_no_shadows"]
    [check] = [check for step in record["steps"] for check in step["checks"]
               if check["name"] == "phong_cornell"]
    x, y = check["story_pixel"]
    assert check["story"].startswith(f"Pixel ({x}, {y}) is the first that differs")
    assert "shadow ray to light" not in check["story"] and "no shadow ray" in check["story"]
    page = "".join(Page((results / "unmapped_normals_and_no_shadows" / "feedback.html")
                        .read_text()).text)
    assert "Your code:" in page and "The finished framework:" in page
    framework = page[page.index("The finished framework:"):]
    assert f"Pixel ({x}, {y}) of PhongIntegrator" in framework
    assert "blocked by object 0 (Sphere)" in framework
    # What a light adds in the course's model is the grader's to tell: the student's
    # story, told by the handout's pyrt/explain.py, has no model of Phong to say it with
    assert "in the course's Phong model" in framework
    assert "in the course's Phong model" not in check["story"]
    result = json.loads((results / "unmapped_normals_and_no_shadows" / course_kit.feedback.GRADESCOPE)
                        .read_text())
    assert check["story"] in result["tests"][3]["output"]  # the step of Phong, 1.4


def test_grading_again_skips_what_is_graded_and_regrades_what_changed(graded, monkeypatch,
                                                                    tmp_path):
    folder, _, shared_results, records, _, config_path = graded
    # A copy of the results, which this test changes and the other tests read as graded
    results = shutil.copytree(shared_results, tmp_path / "results")
    config = course_kit.grader.load_config(config_path)
    graded_again = []
    original = course_kit.grader.grade_submission

    def recording(submission, *args):
        graded_again.append(submission.name)
        return original(submission, *args)

    monkeypatch.setattr(course_kit.grader, "grade_submission", recording)
    again = course_kit.grader.grade_folder(folder, results, config, progress=False)
    assert graded_again == [] and again == [records[name] for name in sorted(VERDICTS)]
    copy = tmp_path / "changed"
    shutil.copytree(folder / "syntax_error", copy / "syntax_error")
    course_kit.grader.grade_folder(copy, results, config, progress=False)
    assert graded_again == []  # the same files: the same grading
    (copy / "syntax_error" / "PyRT_Integrators.py").write_text(
        (folder / "right" / "PyRT_Integrators.py").read_text())
    changed = course_kit.grader.grade_folder(copy, results, config, progress=False)
    assert graded_again == ["syntax_error"] and changed[0]["steps"][0]["passed"]
    course_kit.grader.grade_folder(copy, results, config, force=True, progress=False)
    assert graded_again == ["syntax_error"] * 2


def run_step_after(prelude, handout, tmp_path, wall_seconds, core=None):
    """(result, why, output) of step 1.1 run by a StepServer (on `core`, if given) in a copy
    of the handout whose PyRT_Common.py starts with the lines `prelude`."""
    if course_kit.isolation.unsupported():
        pytest.skip(course_kit.isolation.unsupported())
    work = shutil.copytree(handout, tmp_path / "work")
    common = work / "PyRT_Common.py"
    common.write_text(prelude + common.read_text())
    server = course_kit.isolation.StepServer(core)
    try:
        limits = {"cpu_seconds": 60, "wall_seconds": wall_seconds, "memory_mib": 2048,
                  "output_kib": 256}
        task = {"kind": "collect", "names": ["lazy"], "draw": render.PUBLISHED,
                "traced": False}
        return server.run_step(work, tmp_path, "1.1", task, limits)
    finally:
        server.close()


def test_a_step_that_sleeps_is_stopped_at_the_wall_clock_limit(handout, tmp_path):
    result, why, _ = run_step_after("import time\ntime.sleep(600)\n", handout, tmp_path, 1)
    assert result is None
    assert why == ("did not finish within 1 s, the time limit of a step: the code hangs or "
                   "is far too slow")


def test_a_step_server_given_a_core_runs_its_steps_there(handout, tmp_path):
    # PyRT's render() starts no workers on one core: the framework graded as a submission
    # then stays in its process, where the guard would refuse the workers
    core = course_kit.isolation.cores()[-1]
    prints_its_cores = "import os\nprint('cores', sorted(os.sched_getaffinity(0)))\n"
    _, _, output = run_step_after(prints_its_cores, handout, tmp_path, 300, core)
    assert f"cores [{core}]\n" in output


@pytest.mark.parametrize("text, message", [
    ("[points]\n", "[points] must give the steps 1.1, 1.2, 1.3, 1.4"),
    (LIMITS.replace("cpu_seconds = 3", "cpu_seconds = 0"),
     "[limits] cpu_seconds must be a positive number, got 0"),
    (LIMITS.replace('"1.1" = 10', '"1.1" = "ten"'),
     "[points] 1.1 must be a positive number, got 'ten'"),
    ("[points", "Expected ']'"),
])
def test_a_config_that_is_not_right_is_refused_with_the_reason(tmp_path, text, message):
    path = tmp_path / "grading.toml"
    path.write_text(text)
    with pytest.raises(ValueError) as error:
        course_kit.grader.load_config(path)
    assert str(error.value).startswith(f"{path}: ") and message in str(error.value)


def test_the_grader_draws_inputs_the_handout_does_not_publish():
    # (the sizes drawn: tests/test_course_judging.py)
    draws = [course_kit.judging.draw_inputs(random.Random(seed)) for seed in range(200)]
    assert all(draw.offset != (0.0, 0.0, 0.0) for draw, _ in draws)
    # any_hit's answers follow neither from a case's place nor from what it is handed
    patterns = {tuple(answer for _, _, answer in cases) for _, cases in draws}
    assert len(patterns) > 50
    for draw, cases in draws[:5]:
        assert [case for _, case, _ in cases] == list(draw.any_hit)
        assert all(isinstance(field, (tuple, float, type(None)))
                   for case in draw.any_hit for field in case)


def test_the_default_config_gives_25_points_a_step():
    config = course_kit.grader.load_config()
    assert config.points == dict.fromkeys(("1.1", "1.2", "1.3", "1.4"), 25)
