"""The course kit of Practice 2: its handout, the students' checks (exact where the answer
is a function of the inputs, Bernstein's bound where it is random, closed forms), and the
grader and autograder with --practice 2 on the submissions of
tests/course_submissions_practice2.py. Every grading here draws its inputs from a seeded
generator, so that the statistical checks repeat themselves."""
import math
import random
import subprocess
import sys
import zipfile

import numpy as np
import pytest

import AppWorkbench
import course_kit.__main__
import course_kit.autograder
import course_kit.grader
import course_kit.handout
import course_kit.judging_practice2
import course_kit.sandbox
import course_submissions_practice2 as submissions
from helpers import REPO, SUBPROCESS_TIMEOUT, headless_env, matrix_on_the_main_python_only
from PyRT_Core import Camera
from test_course_autograder import autograder_root, run_autograder

sys.path.insert(0, str(course_kit.handout.CHECKS))
import monte_carlo_check  # noqa: E402
import practice2_checks  # noqa: E402
import practice2_render  # noqa: E402
import practice2_scenes as scenes  # noqa: E402

DRAWS = 45  # the seed of the gradings' draws
MODES = ["bubblewrap", "process"]


@pytest.fixture(scope="module")
def handout(tmp_path_factory):
    return course_kit.handout.write_handout(tmp_path_factory.mktemp("p2") / "handout", 2)


def files_of(folder):
    return {path.relative_to(folder).as_posix(): path.read_bytes()
            for path in sorted(folder.rglob("*")) if path.is_file()}


# ------------------------------------------------------------------------------------------
# The handout
# ------------------------------------------------------------------------------------------
def test_the_handout_holds_the_workbench_the_modules_and_the_checks(handout, tmp_path):
    names = set(files_of(handout))
    assert {"AppWorkbench.py", "PyRT_Common.py", "PyRT_Core.py", "PyRT_Integrators.py",
            "AppRenderer.py", "tests/test_practice2.py", "tests/monte_carlo_check.py",
            "requirements.txt", "pytest.ini"} <= names
    assert not any("practice1.npz" in name or "test_practice1" in name for name in names)
    assert "tqdm" in (handout / "requirements.txt").read_text()
    again = course_kit.handout.write_handout(tmp_path / "again", 2)
    assert files_of(again) == files_of(handout)


def test_the_handout_has_practice_2s_stubs_on_practice_1_finished(handout):
    workbench = (handout / "AppWorkbench.py").read_text()
    assert "    # ASSIGNMENT 2.1: PUT YOUR CODE HERE\n    return 0\n" in workbench
    assert 'methods = [Method("MC", "o", PDFS[args.pdf], args.pdf)]\n' in workbench
    assert "MC IS" not in workbench.split("def main", 1)[1]
    integrators = (handout / "PyRT_Integrators.py").read_text()
    assert "        # ASSIGNMENT 2.3: PUT YOUR CODE HERE\n        pass\n" in integrators
    assert "cam.get_direction(x, y)" in integrators  # the finished render loop
    core = (handout / "PyRT_Core.py").read_text()
    assert "PUT YOUR CODE HERE" not in core  # any_hit finished
    for text in (workbench, integrators, core):
        assert " BEGIN\n" not in text and " END\n" not in text and "FRAMEWORK ONLY" not in text


def practice2_solution_lines():
    """The lines of the 2.1 and 2.3 blocks that appear nowhere else in the framework (the
    solutions of Practice 1 included: its handout keeps them)."""
    blocked, elsewhere = set(), set()
    for name in ("AppWorkbench.py", "PyRT_Integrators.py", "PyRT_Core.py"):
        source = (REPO / name).read_text(encoding="utf-8")
        lines = source.splitlines()
        inside = set()
        for block in course_kit.handout.marked_blocks(source, name):
            if block.step in ("2.1", "2.3"):
                inside.update(range(block.begin, block.end + 1))
                blocked.update(line.strip() for line in lines[block.begin:block.end - 1])
        elsewhere.update(line.strip() for number, line in enumerate(lines, 1)
                         if number not in inside)
    return {line for line in blocked - elsewhere if line and not line.startswith("#")}


def test_no_line_of_practice_2s_solution_is_left_in_its_handout(handout):
    distinctive = practice2_solution_lines()
    assert len(distinctive) >= 8
    for name, content in files_of(handout).items():
        if name.endswith(".py"):
            lines = {line.strip() for line in content.decode().splitlines()}
            assert not distinctive & lines, name


def test_the_command_line_writes_practice_2s_handout_and_names_the_practices(tmp_path, capsys):
    assert course_kit.__main__.main(["handout", "--practice", "2", str(tmp_path / "h")]) == 0
    assert "Practice 2" in capsys.readouterr().out
    assert (tmp_path / "h" / "tests" / "test_practice2.py").exists()
    with pytest.raises(SystemExit):
        course_kit.__main__.main(["handout", "--practice", "5", str(tmp_path / "x")])
    choices = ", ".join(str(number) for number in course_kit.practices.PRACTICES)
    assert f"invalid choice: 5 (choose from {choices})" in capsys.readouterr().err


def run_students_checks(folder):
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider"],
                          cwd=folder, env=headless_env(), capture_output=True, text=True,
                          timeout=SUBPROCESS_TIMEOUT)


def test_on_the_untouched_handout_each_check_fails_with_its_own_message(handout):
    ran = run_students_checks(handout)
    assert "4 failed" in ran.stdout, ran.stdout[-3000:]
    for message in ("the handout's stub", "the average error differs at 5 of 5",
                    "white furnace (an environment map of one value): compute_color "
                    "returned None (the handout's pass returns None)",
                    "emitting sphere: compute_color returned None"):
        assert message in ran.stdout


def test_on_a_solved_handout_every_check_passes(handout, tmp_path):
    solved = tmp_path / "solved"
    submissions.write_submission(solved, submissions.FIXTURES[1], handout)
    (solved / "tests").symlink_to(handout / "tests")
    (solved / "pytest.ini").write_bytes((handout / "pytest.ini").read_bytes())
    (solved / "pyrt").symlink_to(handout / "pyrt")
    ran = run_students_checks(solved)
    assert "6 passed" in ran.stdout, ran.stdout[-3000:]


# ------------------------------------------------------------------------------------------
# The Monte Carlo check and the closed forms
# ------------------------------------------------------------------------------------------
def test_bernsteins_tolerance_is_the_bound_solved_for_s():
    # one term in [0, 1] of mean 1/2, L = ln(2 / delta) = 3: s = 1 + sqrt(1 + 2 * 0.25 * 3)
    delta = 2 * math.exp(-3)
    assert monte_carlo_check.bernstein_tolerance([0.5], 1.0, 1, delta) == pytest.approx(
        1 + math.sqrt(2.5), rel=1e-12)
    # the chance is shared among a check's sums: two sums at delta each get delta / 2
    two = monte_carlo_check.judge_sums([monte_carlo_check.Sum("a", [0.5], [0.5], 1.0, 1)] * 2,
                                       2 * delta)
    assert two[0].tolerance == pytest.approx(1 + math.sqrt(2.5), rel=1e-12)
    assert not monte_carlo_check.Judged("nan", math.nan, 1.0, 10.0).passed


def test_the_cameras_directions_are_the_courses():
    directions = scenes.camera_directions(7)
    camera = Camera(7, 7, scenes.FOV)
    for y in range(7):
        for x in range(7):
            d = camera.get_direction(x, y)
            assert directions[y, x] == pytest.approx((d.x, d.y, d.z), abs=1e-15)


def test_the_emitters_closed_form_is_the_irradiance_integrated_over_the_hemisphere():
    e = scenes.PUBLISHED.emitter
    point = np.array([0.7, e.floor_y, -4.0])
    n = 800  # the midpoint rule over (cos theta, phi): the solid angle is d(cos) d(phi)
    cos = (np.arange(n) + 0.5) / n
    phi = 2 * np.pi * (np.arange(2 * n) + 0.5) / (2 * n)
    c, p = np.meshgrid(cos, phi, indexing="ij")
    s = np.sqrt(1 - c * c)
    d = np.stack([s * np.cos(p), c, s * np.sin(p)], axis=-1)
    to_centre = np.asarray(e.centre) - point
    along = d @ to_centre
    hits = (along > 0) & (to_centre @ to_centre - along ** 2 < e.radius ** 2)
    quadrature = float(np.sum(c * hits) / np.pi * (1 / n) * (np.pi / n))  # (1/pi) int cos
    distance = np.linalg.norm(to_centre)
    closed = (e.radius / distance) ** 2 * to_centre[1] / distance
    assert quadrature == pytest.approx(closed, rel=2e-3)


def test_the_white_furnace_reflects_albedo_times_the_map_and_its_sky_is_the_map():
    draw = scenes.PUBLISHED
    expected = scenes.furnace_expected(draw)
    albedo, sky = np.asarray(draw.furnace.albedo), draw.furnace.sky
    assert np.all(expected.value[expected.estimated] == albedo * sky)
    assert np.all(expected.value[expected.exact] == sky)
    assert expected.estimated.sum() > 150 and expected.exact.sum() > 500
    assert expected.bound == tuple(2 * albedo * sky)


def test_the_curves_closed_form_is_the_frameworks_workbench_seeded():
    random.seed(123)
    framework = AppWorkbench.average_errors(AppWorkbench.INTEGRANDS["cos"],
                                            [AppWorkbench.Method("MC", "o", AppWorkbench.PDFS[
                                                "uniform"], "uniform")],
                                            np.array([20, 40]), 30, progress=False)[:, 0]
    assert scenes.curve(123, (20, 40), 30) == pytest.approx(framework, rel=1e-12)


@pytest.mark.parametrize("mistake", list(practice2_checks.estimate_mistakes(scenes.PUBLISHED)))
def test_each_mistake_of_the_estimate_is_named(mistake, tmp_path):
    values = practice2_checks.estimate_mistakes(scenes.PUBLISHED)[mistake]
    rendered = practice2_render.Rendered("estimate", {"estimates": values})
    check = practice2_checks.judge_rendered(rendered, scenes.PUBLISHED, tmp_path)
    assert not check.passed and check.reason == mistake
    right = practice2_render.Rendered("estimate", {"estimates": scenes.estimates(
        scenes.PUBLISHED) * (1 + 1e-12)})
    assert practice2_checks.judge_rendered(right, scenes.PUBLISHED, tmp_path).passed


def test_the_hostile_curve_is_the_published_one(handout, tmp_path, monkeypatch):
    # what it hands back passes the handout's own check: only the drawn seed stops it
    hostile = next(f for f in submissions.HOSTILE if f.name == "hostile_published_curve")
    folder = submissions.write_submission(tmp_path / "s", hostile, handout)
    monkeypatch.syspath_prepend(str(folder))
    for name in ("PyRT_Common", "PyRT_Core", "PyRT_Integrators"):
        monkeypatch.delitem(sys.modules, name, raising=False)
    assert practice2_checks.run_check("curve", tmp_path / "out").passed


def test_the_workbenchs_script_is_not_run_only_its_definitions(handout, tmp_path, monkeypatch):
    folder = submissions.write_submission(tmp_path / "s", submissions.FIXTURES[2], handout)
    monkeypatch.chdir(folder)
    monkeypatch.syspath_prepend(str(folder))
    for name in ("PyRT_Common", "PyRT_Core", "PyRT_Integrators"):
        monkeypatch.delitem(sys.modules, name, raising=False)
    bench = practice2_render.workbench()  # its script reads a map that is not there
    assert hasattr(bench, "compute_estimate_cmc") and bench.n_estimates == 1000
    assert not hasattr(bench, "env_map") and not hasattr(bench, "results")


# ------------------------------------------------------------------------------------------
# The grader and the autograder
# ------------------------------------------------------------------------------------------
@pytest.fixture(scope="module", params=MODES)
def graded(request, handout, tmp_path_factory):
    """{submission: record} of every fixture and hostile submission graded in the mode."""
    matrix_on_the_main_python_only()
    mode = request.param
    if mode == "bubblewrap" and course_kit.sandbox.why_no_bubblewrap():
        pytest.skip("needs bubblewrap's sandbox: " + course_kit.sandbox.why_no_bubblewrap())
    base = tmp_path_factory.mktemp("p2_" + mode)
    # the confined modes grade a right one, the untouched handout and the mistake whose
    # report is read below, beside the hostile ones
    confined = ("right_handout_loop", "untouched", "mistake_double_cosine")
    fixtures = submissions.FIXTURES + submissions.HOSTILE if mode == "process" else (
        [f for f in submissions.FIXTURES if f.name in confined] + list(submissions.HOSTILE))
    for fixture in fixtures:
        submissions.write_submission(base / "submissions" / fixture.name, fixture, handout)
    records = course_kit.grader.grade_folder(
        base / "submissions", base / "results", course_kit.grader.load_config(practice=2),
        jobs=2, progress=False, isolation=mode, draws=random.Random(DRAWS))
    return {record["submission"]: record for record in records}, base / "results"


@pytest.mark.parametrize("fixture", submissions.FIXTURES, ids=lambda f: f.name)
def test_each_submission_gets_the_points_it_deserves_with_the_mistake_named(graded, fixture):
    records, _ = graded
    if fixture.name not in records:
        pytest.skip("graded in process isolation only")
    steps = {step["step"]: step for step in records[fixture.name]["steps"]}
    assert {step: s["points"] for step, s in steps.items()} == fixture.points, [
        s["reason"] for s in steps.values()]
    for step, fragment in fixture.reasons.items():
        assert fragment in steps[step]["reason"]


@pytest.mark.parametrize("fixture", submissions.HOSTILE, ids=lambda f: f.name)
def test_a_hostile_submission_gets_what_the_untouched_handout_gets(graded, fixture):
    records, _ = graded
    assert [s["points"] for s in records[fixture.name]["steps"]] == [
        s["points"] for s in records["untouched"]["steps"]] == [0, 0]


def test_the_reports_show_the_students_curve_and_image_beside_the_expected(graded):
    records, results = graded
    page = (results / "mistake_double_cosine" / "feedback.html").read_text()
    assert "<h1>Practice 2: mistake_double_cosine, 50 of 100 points</h1>" in page
    for image in ("2.3_furnace_render.png", "2.3_furnace_expected.png",
                  "2.1_curve_render.png", "2.1_curve_expected.png"):
        assert f'src="images/{image}"' in page
        assert (results / "mistake_double_cosine" / "images" / image).stat().st_size > 0
    header = (results / "grades.csv").read_text().splitlines()[0]
    assert header == "submission,2.1,2.3,total,reason 2.1,reason 2.3"
    record = records["right_handout_loop"]
    assert record["practice"] == 2 and record["files"]["AppWorkbench.py"] == "submission"
    assert record["draw"]["size"] in course_kit.judging_practice2.DRAWN_SIZES


def test_a_config_for_practice_2_must_give_its_steps(tmp_path):
    assert course_kit.grader.load_config(practice=2).points == {"2.1": 50, "2.3": 50}
    path = tmp_path / "grading.toml"
    text = course_kit.grader.CONFIG.read_text().replace('"2.1" = 50\n', "")
    path.write_text(text)
    assert course_kit.grader.load_config(path).points["1.1"] == 25
    with pytest.raises(ValueError, match=r"\[points\] must give the steps 2.1, 2.3"):
        course_kit.grader.load_config(path, 2)


def test_the_autograder_of_practice_2_grades_a_submission(handout, tmp_path):
    archive = course_kit.autograder.write_zip(tmp_path / "ag.zip", practice=2)
    with zipfile.ZipFile(archive) as zipped:
        assert "--practice 2" in zipped.read("run_autograder").decode()
        assert "AppWorkbench.py" in zipped.namelist()
    root = autograder_root(archive, tmp_path / "root")
    for name, text in submissions.submission_files(submissions.FIXTURES[0], handout).items():
        (root / "submission" / name).write_text(text)
    results, ran = run_autograder(root, isolation="process")
    assert results["score"] == 100, ran.stdout[-2000:]
    assert [test["number"] for test in results["tests"]] == ["2.1", "2.3"]
