"""The course kit on submissions of real style: the course's four modules written on the
course's own base code of the students' edition (tests/course_submissions.py), graded by
course_kit.grader and run through the students' checks in a handout. Each must get the
verdict a teaching assistant gives it, step by step: full points for a right one, and
for a mistake a failure of exactly the steps it breaks, for the reason it is."""
import json
import random
import shutil
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

import course_kit.feedback
import course_kit.grader
import course_kit.handout
import course_submissions as submissions
from helpers import REPO, matrix_on_the_main_python_only, run_python
from test_course_kit import CHECK_TESTS, failures_of_the_checks

FIXTURES = {fixture.name: fixture for fixture in submissions.FIXTURES}
RIGHT = sorted(name for name, fixture in FIXTURES.items() if not fixture.fails)
SEAMS = REPO / "tests" / "data" / "course_figure1_seams.npz"
SEAM_SAMPLE = 4  # every 4th of Figure 1's seam pixels: a second of rendering


@dataclass(frozen=True)
class Graded:
    """The fixtures graded once: where their results went and their records by name."""

    results: Path
    records: dict


@pytest.fixture(scope="session")
def real_submissions(tmp_path_factory):
    """A folder holding every submission of FIXTURES, each in its own folder."""
    folder = tmp_path_factory.mktemp("real") / "submissions"
    for fixture in submissions.FIXTURES:
        submissions.write_course_submission(folder / fixture.name, fixture.edition,
                                            fixture.answers)
    return folder


@pytest.fixture(scope="session")
def graded(real_submissions, tmp_path_factory):
    """Every submission of FIXTURES graded once, two at a time, with the kit's settings."""
    matrix_on_the_main_python_only()
    results = tmp_path_factory.mktemp("real_results")
    records = course_kit.grader.grade_folder(real_submissions, results,
                                         course_kit.grader.load_config(), jobs=2,
                                         progress=False, draws=random.Random(2))
    return Graded(results, {record["submission"]: record for record in records})


@pytest.fixture(scope="session")
def checks_run_by_students(real_submissions, tmp_path_factory):
    """{submission: {test of the students' checks: its failure message, or None}}: each
    submission's four files copied over a handout, where `python -m pytest` runs, two
    submissions at a time."""
    matrix_on_the_main_python_only()
    base = tmp_path_factory.mktemp("real_checks")
    handout = course_kit.handout.write_handout(base / "handout")

    def run(name):
        copy = shutil.copytree(handout, base / name)
        for module in submissions.MODULES:
            shutil.copyfile(real_submissions / name / module, copy / module)
        return name, failures_of_the_checks(copy)

    with ThreadPoolExecutor(max_workers=2) as pool:
        return dict(pool.map(run, sorted(FIXTURES)))


def test_the_fixtures_cover_every_edition_and_style_with_a_right_submission():
    right = [FIXTURES[name] for name in RIGHT]
    assert sorted({fixture.edition for fixture in right}) == list(submissions.EDITIONS)
    styles = {style for fixture in right for style in fixture.styles}
    assert set(submissions.SHADOW_STYLES) <= styles
    assert {"Ray() then ray.o and ray.d", "Ray() then ray.d", "Ray(direction=d)",
            "Ray(Vector3D(0, 0, 0), cam.get_direction(x, y))", "RED", "RGBColor(1, 0, 0)",
            "RGBColor(255, 0, 0)"} <= styles
    for edition in submissions.EDITIONS:
        assert any(fixture.fails for fixture in submissions.FIXTURES
                   if fixture.edition == edition), edition


@pytest.mark.parametrize("name", sorted(FIXTURES))
def test_each_real_submission_gets_a_teaching_assistants_verdict_step_by_step(graded, name):
    fixture = FIXTURES[name]
    steps = {step["step"]: step for step in graded.records[name]["steps"]}
    assert sorted(steps) == list(submissions.STEPS)
    for step, verdict in steps.items():
        expected = fixture.expected(step)
        if expected is None:
            assert verdict["passed"] and verdict["points"] == verdict["max_points"], (
                step, verdict["reason"])
        else:
            assert not verdict["passed"] and verdict["points"] == 0, step
            assert expected in verdict["reason"], (step, verdict["reason"])


@pytest.mark.parametrize("name", RIGHT)
def test_a_right_submission_has_nothing_marked_wrong_in_its_feedback(graded, name):
    folder = graded.results / name
    record = json.loads((folder / course_kit.feedback.RECORD).read_text(encoding="utf-8"))
    assert record["total"] == record["max_total"] == 100
    assert record["files"] == dict.fromkeys(submissions.MODULES, "submission")
    failed = [(step["step"], check["name"], check["reason"])
              for step in record["steps"] for check in step["checks"] if not check["passed"]]
    assert failed == []
    assert all(step["checks"] and step["reason"] == "" for step in record["steps"])
    result = json.loads((folder / course_kit.feedback.GRADESCOPE).read_text(encoding="utf-8"))
    assert result["score"] == 100
    assert [test["status"] for test in result["tests"]] == ["passed"] * 4
    assert 'class="failed"' not in (folder / course_kit.feedback.FEEDBACK).read_text(
        encoding="utf-8")


@pytest.mark.parametrize("name", sorted(FIXTURES))
def test_the_students_checks_give_each_step_the_same_verdict(checks_run_by_students, name):
    fixture = FIXTURES[name]
    failures = checks_run_by_students[name]
    assert sorted(failures) == sorted(CHECK_TESTS)
    for step in submissions.STEPS:
        messages = [message for test, message in failures.items()
                    if CHECK_TESTS[test] == step and message is not None]
        expected = fixture.expected(step)
        if expected is None:
            assert messages == [], step
        else:
            assert any(expected in message for message in messages), (step, messages)


def test_the_2023_24_base_renders_figure_1s_seams_as_the_course_did(tmp_path):
    # On the seams of the Cornell box the course's own arithmetic decides which wall a
    # ray sees; its shadow rays lifted EPSILON along the normal are what Figure 1 was
    # rendered with, to the last bit
    folder = submissions.write_course_submission(tmp_path / "course", "2023-24",
                                                 submissions.RIGHT_2023)
    with np.load(SEAMS) as seams:
        pixels = np.stack([seams["y"], seams["x"]], axis=1)[::SEAM_SAMPLE]
        course = seams["rgb"][::SEAM_SAMPLE]
    np.save(folder / "pixels.npy", pixels)
    result = run_python(["-c", submissions.FIGURE_PIXELS_SCRIPT, "figure1", "pixels.npy",
                         "colours.npy"], cwd=folder)
    assert result.returncode == 0, result.stderr
    colours = np.load(folder / "colours.npy")
    assert colours.shape == course.shape
    differ = ~np.all(colours == course, axis=1)
    assert pixels[differ].tolist() == []


def test_a_red_of_255_passes_with_a_note_on_what_differs(graded, checks_run_by_students):
    # RGBColor(255, 0, 0) makes Figure 3's PNG through the course's tonemapper: right, with
    # a note in the feedback, and not a word of it marked wrong
    name = next(name for name in RIGHT if "RGBColor(255, 0, 0)" in FIXTURES[name].styles)
    step = next(step for step in graded.records[name]["steps"] if step["step"] == "1.2")
    intersection = next(check for check in step["checks"] if check["name"] == "intersection")
    assert intersection["passed"]
    assert intersection["note"].startswith("your red is 255 where PyRT's is 1.")
    page = (graded.results / name / course_kit.feedback.FEEDBACK).read_text(encoding="utf-8")
    assert "Worth knowing: your red is 255" in page
    assert checks_run_by_students[name]["test_assignment_1_2_intersection_image"] is None


@pytest.mark.parametrize("name, mistake", [("upside_down_2021", "upside down"),
                                           ("transposed_2023", "transposed"),
                                           ("corner_rays_2025", "top-left corners")])
def test_a_mistake_of_render_costs_its_steps_and_is_named_in_the_others(graded, name,
                                                                       mistake):
    # The images of 1.3 and 1.4 come out of the same render(): they pass on the strength
    # of compute_color, and say what render() still does wrong
    for step in graded.records[name]["steps"]:
        if step["step"] in ("1.3", "1.4"):
            for check in step["checks"]:
                assert check["passed"], (step["step"], check["name"])
                assert check["note"].startswith("compute_color is right: the image that "
                                                "your render() makes differs"), check["note"]
                assert mistake in check["note"]
