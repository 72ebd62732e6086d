"""Gradescope's autograder (course_kit/autograder.py): the zip, and its run_autograder run end
to end in a temporary /autograder tree, as Gradescope runs it."""
import json
import shutil
import stat
import subprocess
import sys
import zipfile

import pytest

import course_kit.autograder
import course_kit.feedback
import course_kit.grader
import course_kit.handout
import course_kit.sandbox
import course_kit_students as students
from helpers import REPO, SUBPROCESS_TIMEOUT, headless_env, run_python

STEPS = list(course_kit.grader.STEP_TITLES)
# Why run_autograder refuses to grade on this machine with the isolation it chooses (no
# bubblewrap, no unprivileged user), or None where it grades: where it refuses, the tests
# that grade through it assert the refusal, then grade with AUTOGRADER_ISOLATION=process
REFUSAL = course_kit.autograder.refusal_of(course_kit.sandbox.choose())
GRADING_ISOLATION = None if REFUSAL is None else "process"


@pytest.fixture(scope="module")
def autograder_zip(tmp_path_factory):
    return course_kit.autograder.write_zip(tmp_path_factory.mktemp("autograder") / "autograder.zip")


@pytest.fixture(scope="module")
def handout(tmp_path_factory):
    return course_kit.handout.write_handout(tmp_path_factory.mktemp("autograder") / "handout")


def autograder_root(autograder_zip, root):
    """A Gradescope tree at root made from the zip: source/ (the zip unzipped, with the
    modes it gives), run_autograder beside it, an empty submission/ and results/."""
    with zipfile.ZipFile(autograder_zip) as archive:
        archive.extractall(root / "source")
        for info in archive.infolist():
            (root / "source" / info.filename).chmod(info.external_attr >> 16 & 0o777)
    shutil.copy2(root / "source" / "run_autograder", root / "run_autograder")
    (root / "submission").mkdir()
    (root / "results").mkdir()
    return root


def run_autograder(root, python=sys.executable, isolation=None):
    """Runs root/run_autograder from root, with python (default: this one) and the
    isolation named (default: the strongest that runs); returns (results.json read, the
    CompletedProcess)."""
    environment = dict(headless_env(), AUTOGRADER_ROOT=str(root), AUTOGRADER_PYTHON=python)
    if isolation is not None:
        environment["AUTOGRADER_ISOLATION"] = isolation
    del environment["PYTHONPATH"]  # the grader runs from source/, not from the repository
    ran = subprocess.run([str(root / "run_autograder")], cwd=root, env=environment,
                         capture_output=True, text=True, timeout=SUBPROCESS_TIMEOUT)
    return json.loads((root / "results" / "results.json").read_text()), ran


def assert_refused(results, ran):
    """run_autograder refused to grade, saying why and what process isolation means."""
    assert ran.returncode == 0, ran.stdout + ran.stderr
    assert results["score"] == 0 and results["tests"] == []
    assert results["output"] == ("The autograder failed, and your course staff can see "
                                 f"why: IsolationUnavailable: {REFUSAL}")
    assert_gradescopes_format(results)


def assert_gradescopes_format(results):
    """results has the fields and types of Gradescope's results.json."""
    assert isinstance(results["score"], (int, float))
    assert isinstance(results["execution_time"], (int, float))
    assert isinstance(results["output"], str)
    assert results["stdout_visibility"] in course_kit.grader.VISIBILITIES
    assert results["visibility"] in course_kit.grader.VISIBILITIES
    assert results["score"] == sum(test["score"] for test in results["tests"])
    for test in results["tests"]:
        assert sorted(test) == ["max_score", "name", "number", "output", "score", "status"]
        assert test["status"] in ("passed", "failed")
        assert (test["status"] == "passed") == (test["score"] == test["max_score"])


def test_the_zip_has_setup_sh_and_an_executable_run_autograder_at_its_root(autograder_zip,
                                                                         tmp_path):
    with zipfile.ZipFile(autograder_zip) as archive:
        modes = {info.filename: info.external_attr >> 16 for info in archive.infolist()}
        setup = archive.read("setup.sh").decode()
    assert modes["setup.sh"] & stat.S_IXUSR and modes["run_autograder"] & stat.S_IXUSR
    assert set(course_kit.autograder.kit_files()) | {"setup.sh", "run_autograder"} == set(modes)
    for needed in ("course_kit/grader.py", "course_kit/sandbox.py", "course_kit/grading.toml",
                   "course_kit/checks/practice1_checks.py", "course_kit/checks/expected/practice1.npz",
                   "pyrt/rendering.py", "references/figure1_phong.png"):
        assert needed in modes
    assert '-m pip install --no-cache-dir -r requirements.txt' in setup
    again = course_kit.autograder.write_zip(tmp_path / "again.zip")
    assert again.read_bytes() == autograder_zip.read_bytes()


def test_the_finished_framework_gets_every_point_through_run_autograder(autograder_zip,
                                                                       tmp_path):
    root = autograder_root(autograder_zip, tmp_path)
    for name in course_kit.handout.COURSE_MODULES:
        shutil.copyfile(REPO / name, root / "submission" / name)
    if REFUSAL is not None:
        assert_refused(*run_autograder(root))
    results, ran = run_autograder(root, isolation=GRADING_ISOLATION)
    assert ran.returncode == 0, ran.stdout + ran.stderr
    assert_gradescopes_format(results)
    assert results["score"] == 100
    assert [(test["number"], test["name"], test["score"]) for test in results["tests"]] == [
        (step, title, 25) for step, title in course_kit.grader.STEP_TITLES.items()]
    assert ran.stdout.startswith("Isolation of each step: ")


def test_the_untouched_handout_gets_none_with_each_steps_message(autograder_zip, handout,
                                                                tmp_path):
    root = autograder_root(autograder_zip, tmp_path)
    for name in course_kit.handout.COURSE_MODULES:
        shutil.copyfile(handout / name, root / "submission" / name)
    results, _ = run_autograder(root, isolation=GRADING_ISOLATION)
    assert_gradescopes_format(results)
    assert results["score"] == 0
    outputs = {test["number"]: test["output"] for test in results["tests"]}
    assert "every pixel is GREEN" in outputs["1.1"]
    assert "PhongIntegrator.compute_color returned None" in outputs["1.4"]


def test_a_zip_with_its_modules_in_a_folder_and_extra_files_is_graded_as_grade_does(
        autograder_zip, handout, tmp_path):
    root = autograder_root(autograder_zip, tmp_path / "root")
    files = students.submission_files(handout, students.VARIANTS["no_inverse_square"])
    with zipfile.ZipFile(root / "submission" / "practice1.zip", "w") as archive:
        for name, text in files.items():
            archive.writestr(f"practice1/{name}", text)
        archive.writestr("practice1/venv/lib/PyRT_Core.py", "raise SystemExit('decoy')\n")
        archive.writestr("practice1/__pycache__/PyRT_Core.cpython-310.pyc", b"\0")
        archive.writestr("practice1/.idea/workspace.xml", "<project/>\n")
    results, _ = run_autograder(root, isolation=GRADING_ISOLATION)
    assert_gradescopes_format(results)
    assert [test["score"] for test in results["tests"]] == [25, 25, 25, 0]
    assert "not divided by r^2" in results["tests"][3]["output"]
    # The same submission graded by `grade`: the same verdicts, in the same format (the
    # messages differ with the inputs each grading draws, and so does the time it took)
    folder = tmp_path / "submissions"
    students.write_submission(folder / "student", handout,
                              students.VARIANTS["no_inverse_square"])
    record, = course_kit.grader.grade_folder(folder, tmp_path / "graded",
                                         course_kit.grader.load_config(), progress=False,
                                         isolation=GRADING_ISOLATION)
    local = course_kit.feedback.gradescope_results(record)
    for outcome in (results, local):
        del outcome["execution_time"]
        for test in outcome["tests"]:
            test["output"] = "not divided by r^2" in test["output"]
    assert results == local


def test_a_grader_that_fails_still_leaves_a_valid_results_json(autograder_zip, tmp_path):
    root = autograder_root(autograder_zip, tmp_path)
    (root / "source" / "course_kit" / "grading.toml").write_text("[points\n")
    results, ran = run_autograder(root)
    assert ran.returncode == 0
    assert results["score"] == 0 and results["tests"] == []
    assert results["output"].startswith("The autograder failed, and your course staff can "
                                        "see why: ValueError: ")
    assert "Traceback" in ran.stdout  # what it printed, which only the staff sees
    assert_gradescopes_format(results)


def test_a_grader_that_cannot_load_or_start_still_leaves_a_valid_results_json(
        autograder_zip, tmp_path):
    root = autograder_root(autograder_zip, tmp_path)
    grader = root / "source" / "course_kit" / "grader.py"
    grader.write_text("import a_requirement_not_installed\n" + grader.read_text())
    results, _ = run_autograder(root)
    assert results["score"] == 0 and results["tests"] == []
    assert results["output"].endswith("ModuleNotFoundError: No module named "
                                      "'a_requirement_not_installed'")
    assert_gradescopes_format(results)
    results, ran = run_autograder(root, python=str(tmp_path / "no-python"))
    assert ran.returncode == 0
    assert results == {"score": 0, "output": "The autograder failed before it could grade, "
                       "and your course staff can see why.", "visibility": "visible",
                       "stdout_visibility": "hidden", "tests": []}


def test_a_submission_without_course_modules_says_so(tmp_path):
    (tmp_path / "notes.txt").write_text("nothing here")
    submission = course_kit.autograder.gradescope_submission(tmp_path)
    assert submission.files == {}
    assert submission.problems == [
        "no course module (PyRT_Common.py, PyRT_Core.py, PyRT_Integrators.py, AppRenderer.py)"
        " was found in what you handed in"]


def test_course_kit_autograder_writes_the_zip_and_refuses_a_wrong_config(tmp_path):
    ran = run_python(["-m", "course_kit", "autograder", tmp_path / "a.zip"], cwd=REPO)
    assert ran.returncode == 0, ran.stderr
    assert zipfile.ZipFile(tmp_path / "a.zip").read("run_autograder").decode() == (
        course_kit.autograder.RUN_AUTOGRADER)
    wrong = tmp_path / "grading.toml"
    wrong.write_text((REPO / "course_kit" / "grading.toml").read_text().replace(
        'visibility = "visible"', 'visibility = "always"'))
    ran = run_python(["-m", "course_kit", "autograder", tmp_path / "b.zip", "--config", wrong],
                     cwd=REPO)
    assert ran.returncode == 1
    assert ran.stderr == (f"course_kit autograder: {wrong}: [gradescope] visibility must "
                          "be one of hidden, visible, after_due_date, after_published, got "
                          "'always'\n")
    assert not (tmp_path / "b.zip").exists()


def test_the_gradescope_table_sets_the_visibilities_of_results_json(tmp_path):
    path = tmp_path / "grading.toml"
    path.write_text((REPO / "course_kit" / "grading.toml").read_text().replace(
        'stdout_visibility = "hidden"', 'stdout_visibility = "after_published"'))
    config = course_kit.grader.load_config(path)
    assert config.gradescope == {"visibility": "visible",
                                 "stdout_visibility": "after_published"}
    assert course_kit.grader.load_config().gradescope == course_kit.grader.GRADESCOPE_DEFAULTS
    path.write_text(path.read_text() + 'tests = "hidden"\n')
    with pytest.raises(ValueError) as error:
        course_kit.grader.load_config(path)
    assert str(error.value) == (f"{path}: [gradescope] may give only visibility, "
                                "stdout_visibility")


def test_run_autograder_refuses_process_isolation_unless_it_is_asked_for(
        autograder_zip, handout, tmp_path, monkeypatch):
    # Where neither bubblewrap nor an unprivileged user can run, the student's code would
    # run as the grader's user, which keeps no secret from it
    monkeypatch.setattr(course_kit.sandbox, "choose", lambda requested=None: (
        course_kit.sandbox.Isolation("process", "asked for" if requested else
                                     "no bubblewrap; no unprivileged user")))
    root = autograder_root(autograder_zip, tmp_path)
    for name in course_kit.handout.COURSE_MODULES:
        shutil.copyfile(REPO / name, root / "submission" / name)
    refused = course_kit.autograder.run(root)
    assert refused["score"] == 0 and refused["tests"] == []
    assert refused["output"] == (
        "The autograder failed, and your course staff can see why: IsolationUnavailable: "
        "this machine cannot sandbox the students' code: no bubblewrap; no unprivileged "
        "user; run_autograder grades here only with AUTOGRADER_ISOLATION=process, and then "
        "in process isolation the students' code runs as the grader's user: it can read "
        "and change whatever the grader can (the finished framework, the expected data, "
        "the results)")
    assert course_kit.autograder.run(root, isolation="process")["score"] == 100
