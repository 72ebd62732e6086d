"""Hostile submissions (tests/course_hostile.py) graded beside the untouched handout and a
right submission, in every isolation that runs here and through run_autograder: none
gets a point the untouched handout does not get, and the right one keeps all of its.

In process isolation the student's code runs as the grader's user and can read what the
grader can: the kinds that read the grader's files (course_hostile.READS_FILES) are
recorded there as the weakness docs/course-kit.md states, and the verdicts of the others
still cannot be changed from inside. The matrix runs on one Python of CI's three (it
grades each kind several times); the other Pythons run the rest of the course kit's
tests."""
import hashlib
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

import pytest

import course_hostile as hostile
import course_kit.autograder
import course_kit.grader
import course_kit.handout
import course_kit.sandbox
import course_kit_students as students
from helpers import MAIN_PYTHON, REPO, SUBPROCESS_TIMEOUT, headless_env
from test_course_autograder import (REFUSAL, assert_refused, autograder_root,
                                   run_autograder)

pytestmark = pytest.mark.skipif(
    sys.version_info[:2] != MAIN_PYTHON,
    reason="the hostile submissions' matrix runs on Python 3.11 only, CI's main Python")
MODES = ["bubblewrap", "unprivileged user", "process"]
SYSTEM_PYTHON = Path("/usr/bin/python3")
# The virtual environment of the unprivileged user's grading, made once per requirements
VENVS = Path(tempfile.gettempdir())


@pytest.fixture(scope="module")
def handout(tmp_path_factory):
    return course_kit.handout.write_handout(tmp_path_factory.mktemp("hostile") / "handout")


@pytest.fixture(scope="module")
def published():
    return hostile.published_data()


def write_all(folder, handout, published, kit, results):
    """Every hostile submission, the untouched handout and a right one, in folder."""
    fields = {"KIT": str(kit), "RESULTS": str(results), "PUBLISHED": published}
    for kind in hostile.KINDS:
        hostile.write_hostile(folder / kind, handout, kind, fields)
    hostile.write_symlinked(folder / "symlinks_to_the_framework", kit)
    hostile.write_untouched(folder / "untouched", handout)
    students.write_submission(folder / "right", handout, {})


def system_venv():
    """A virtual environment of the system's Python with the grader's requirements, in a
    folder all may read, as Gradescope's image has it: where the tests' own Python lies
    in root's home, another user cannot run it. Made once per requirements."""
    requirements = (REPO / "requirements.txt").read_bytes()
    venv = VENVS / f"pyrt-system-venv-{hashlib.sha256(requirements).hexdigest()[:12]}"
    if not (venv / "ready").exists():  # a venv left half made is made again
        shutil.rmtree(venv, ignore_errors=True)
        for command, fix in (
                ([str(SYSTEM_PYTHON), "-m", "venv", str(venv)], "apt-get install python3-venv"),
                ([str(venv / "bin" / "python"), "-m", "pip", "install", "-q", "-r",
                  str(REPO / "requirements.txt")], "PyPI must be reachable")):
            ran = subprocess.run(command, capture_output=True, text=True,
                                 timeout=SUBPROCESS_TIMEOUT)
            if ran.returncode != 0:
                pytest.skip(f"needs a virtual environment of {SYSTEM_PYTHON} for the "
                            f"unprivileged user ({fix}): {' '.join(command[1:4])} failed: "
                            + ran.stderr.strip()[-200:])
        venv.chmod(0o755)
        (venv / "ready").touch()
    return venv / "bin" / "python"


def unprivileged_python():
    """The Python of system_venv, or a skip naming what keeps the unprivileged user out."""
    missing = None
    if os.environ.get(course_kit.sandbox.NO_UNPRIVILEGED_USER):
        missing = f"switched off ({course_kit.sandbox.NO_UNPRIVILEGED_USER} is set)"
    elif not sys.platform.startswith("linux") or os.geteuid() != 0:
        missing = "it needs Linux and root (as on Gradescope)"
    elif not SYSTEM_PYTHON.exists():
        missing = (f"it needs a Python all users may run at {SYSTEM_PYTHON} (apt-get "
                   "install python3 python3-venv)")
    if missing:
        pytest.skip(f"needs the unprivileged user's isolation: {missing}")
    return system_venv()


def grade_as_unprivileged_user(base, handout, published, autograder_zip):
    """({submission: record}, the results' folder) of every submission graded by
    `python -m course_kit grade` run with the system's Python from a copy of the kit
    readable by root only, as on Gradescope, in the unprivileged user's isolation."""
    python = unprivileged_python()
    kit = base / "kit"
    kit.mkdir(mode=0o700)
    with zipfile.ZipFile(autograder_zip) as archive:
        archive.extractall(kit)
    results = base / "results"
    write_all(base / "submissions", handout, published, kit, results)
    environment = {name: value for name, value in headless_env().items()
                   if name != "PYTHONPATH"}
    ran = subprocess.run([str(python), "-m", "course_kit", "grade", str(base / "submissions"),
                          "--out", str(results), "--jobs", "2", "--isolation",
                          "unprivileged user"], cwd=kit, env=environment,
                         capture_output=True, text=True, timeout=SUBPROCESS_TIMEOUT)
    assert ran.returncode == 0, ran.stdout + ran.stderr
    return {folder.name: json.loads((folder / "grading.json").read_text())
            for folder in results.iterdir() if (folder / "grading.json").exists()}, results


@pytest.fixture(scope="module", params=MODES)
def graded(request, handout, published, autograder_zip, tmp_path_factory):
    """(the mode, {submission: record}, the results' folder) of every submission graded
    by `grade` in the mode."""
    mode = request.param
    base = tmp_path_factory.mktemp("hostile_" + mode.replace(" ", "_"))
    if mode == "unprivileged user":
        return (mode, *grade_as_unprivileged_user(base, handout, published,
                                                  autograder_zip))
    if mode == "bubblewrap" and course_kit.sandbox.why_no_bubblewrap():
        pytest.skip("needs bubblewrap's sandbox: " + course_kit.sandbox.why_no_bubblewrap())
    results = base / "results"
    write_all(base / "submissions", handout, published, REPO, results)
    records = course_kit.grader.grade_folder(base / "submissions", results,
                                             course_kit.grader.load_config(), jobs=2,
                                             progress=False, isolation=mode,
                                             draws=random.Random(36))
    return mode, {record["submission"]: record for record in records}, results


def points(record):
    return [step["points"] for step in record["steps"]]


@pytest.mark.parametrize("kind", sorted(hostile.KINDS) + ["symlinks_to_the_framework"])
def test_a_hostile_submission_gets_what_the_untouched_handout_gets(graded, kind):
    mode, records, _ = graded
    assert points(records["untouched"]) == [0, 0, 0, 0]
    assert records["right"]["total"] == 100, [s["reason"] for s in records["right"]["steps"]]
    if mode == "process" and kind == "finds_the_framework":
        # The documented weakness: in process isolation the student's code reads the
        # grader's folder, and the framework it finds there renders right
        assert records[kind]["total"] == 100
        return
    assert points(records[kind]) == points(records["untouched"]), [
        step["reason"] for step in records[kind]["steps"]]


def test_what_the_graders_processes_show_depends_on_the_isolation(graded):
    mode, records, _ = graded
    output = records["reads_the_graders_processes"]["steps"][0]["output"]
    seen = output[output.index("saw of the grader:"):].splitlines()[0]
    # bubblewrap's own process namespace shows none of the grader's processes; another
    # user may read their command lines but not their variables, memory or files
    assert seen == {"bubblewrap": "saw of the grader: []",
                    "unprivileged user": "saw of the grader: ['command']",
                    "process": "saw of the grader: ['command', 'environ', 'fd', 'mem']"}[
        mode]


def test_the_graders_results_are_not_rewritten_from_inside(graded):
    mode, records, results = graded
    if mode == "process":
        pytest.skip("process isolation: the student's code runs as the grader's user and "
                    "may write what it writes (docs/course-kit.md)")
    for name, record in records.items():
        written = json.loads((results / name / "results.json").read_text())
        assert written["score"] == record["total"], name
        assert [test["score"] for test in written["tests"]] == points(record), name


def test_malformed_data_handed_back_is_named(graded):
    _, records, _ = graded
    reasons = {kind: records[f"hands_back_{kind}"]["steps"][0]["reason"]
               for kind in hostile.FILLS}
    assert reasons["object_arrays"].startswith("refused: the step's process handed back ")
    assert "which is no plain array" in reasons["object_arrays"]
    assert "float32" in reasons["float32_images"]
    assert "of shape" in reasons["wrong_shape"]
    assert "differ from the expected image" in reasons["nan_images"]
    assert "printed more than" in reasons["huge_images"]


@pytest.fixture(scope="module")
def autograder_zip(tmp_path_factory):
    return course_kit.autograder.write_zip(tmp_path_factory.mktemp("hostile_zip") / "ag.zip")


@pytest.mark.parametrize("isolation", [None, "unprivileged user"])
@pytest.mark.parametrize("kind", sorted(hostile.KINDS) + ["untouched", "right"])
def test_through_run_autograder_a_hostile_submission_gets_nothing(
        kind, isolation, autograder_zip, handout, published, tmp_path):
    # None: the strongest isolation that runs here; the unprivileged user as Gradescope's
    # containers have it, the system's Python in a virtual environment
    python = sys.executable
    if isolation is not None:
        python = unprivileged_python()
    root = autograder_root(autograder_zip, tmp_path / "autograder")
    submissions = tmp_path / "submissions"
    write_all(submissions, handout, published, root / "source", root / "results")
    for path in (submissions / kind).iterdir():
        path.rename(root / "submission" / path.name)
    results, ran = run_autograder(root, python, isolation)
    if isolation is None and REFUSAL is not None:
        # no sandbox here: run_autograder grades nothing, and says why
        assert_refused(results, ran)
        return
    assert results["score"] == (100 if kind == "right" else 0), ran.stdout
    assert f"Isolation of each step: {isolation or ''}" in ran.stdout

