"""course_kit/isolation.py on the systems teaching assistants grade on: limits a system
refuses (as macOS refuses one of the address space) and systems without the process
limits and fork the grader needs (Windows), simulated on this one."""
import json
import random
import re
import shutil
import subprocess
import sys
from types import SimpleNamespace

import pytest

import course_kit.grader
import course_kit.isolation
import course_kit.handout
from helpers import REPO, SUBPROCESS_TIMEOUT, headless_env

pytestmark = pytest.mark.skipif(course_kit.isolation.unsupported() is not None,
                                reason=str(course_kit.isolation.unsupported()))

MACOS_REFUSAL = "current limit exceeds maximum limit"  # what macOS's setrlimit answers


class Limits:
    """A stand-in for the resource module that records the limits set and refuses, with
    macOS's ValueError, the ones named in `refused`."""

    RLIMIT_CPU, RLIMIT_AS, RLIMIT_FSIZE, RLIMIT_CORE = range(4)

    def __init__(self, refused):
        self.refused, self.set = refused, {}

    def setrlimit(self, which, values):
        if which in self.refused:
            raise ValueError(MACOS_REFUSAL)
        self.set[which] = values


def test_a_refused_limit_is_returned_as_a_line_and_the_others_are_still_set(monkeypatch):
    limits = Limits(refused={Limits.RLIMIT_AS})
    monkeypatch.setattr(course_kit.isolation, "resource", limits)
    refused = course_kit.isolation.set_limits({"cpu_seconds": 30, "wall_seconds": 60,
                                           "memory_mib": 2, "output_kib": 3})
    assert refused == [f"memory_mib = 2 (RLIMIT_AS: ValueError: {MACOS_REFUSAL})"]
    assert limits.set == {Limits.RLIMIT_CPU: (30, 31), Limits.RLIMIT_FSIZE: (3072, 3072),
                          Limits.RLIMIT_CORE: (0, 0)}


def test_every_limit_set_returns_nothing(monkeypatch):
    limits = Limits(refused=set())
    monkeypatch.setattr(course_kit.isolation, "resource", limits)
    assert course_kit.isolation.set_limits({"cpu_seconds": 1, "wall_seconds": 2,
                                        "memory_mib": 1, "output_kib": 1}) == []
    assert limits.set[Limits.RLIMIT_AS] == (1024 * 1024, 1024 * 1024)


# A step server whose steps' processes cannot lower their address space, as on macOS
SERVER_REFUSING_THE_ADDRESS_SPACE = f'''
import resource
import sys

sys.path.insert(0, {str(REPO)!r})
set_limit = resource.setrlimit


def setrlimit(which, values):
    if which == resource.RLIMIT_AS:
        raise ValueError({MACOS_REFUSAL!r})
    set_limit(which, values)


resource.setrlimit = setrlimit
import course_kit.isolation
course_kit.isolation.main(sys.argv[1:])
'''


def test_with_the_address_space_limit_refused_a_right_submission_gets_every_point(
        tmp_path, monkeypatch, capsys):
    server = tmp_path / "refusing_server.py"
    server.write_text(SERVER_REFUSING_THE_ADDRESS_SPACE)
    monkeypatch.setattr(course_kit.isolation, "SERVER_SCRIPT", server)
    submissions = tmp_path / "submissions"
    for name in ("first", "second"):  # the finished framework, twice
        (submissions / name).mkdir(parents=True)
        for module in course_kit.handout.COURSE_MODULES:
            shutil.copyfile(REPO / module, submissions / name / module)
    config = course_kit.grader.load_config()
    # the process isolation: the server script above lies where a sandbox shows nothing
    records = course_kit.grader.grade_folder(submissions, tmp_path / "results", config, jobs=1,
                                         progress=False, isolation="process",
                                         draws=random.Random(4))
    refused = (f"memory_mib = {config.limits['memory_mib']} (RLIMIT_AS: ValueError: "
               f"{MACOS_REFUSAL})")
    for record in records:
        assert [(step["passed"], step["reason"]) for step in record["steps"]] == [
            (True, "")] * 4
        assert record["total"] == record["max_total"] == 100
        kept = json.loads((tmp_path / "results" / record["submission"] / "grading.json")
                          .read_text())
        assert kept["limits_not_set"] == [refused]
    err = capsys.readouterr().err
    assert err.count("refused some limits") == 1, err  # once for the whole grading
    assert err.endswith(f"so the steps ran without them (no grade suffers for it): "
                        f"{refused}\n"), err


# Python as on Windows: no resource module, no os.fork
AS_ON_WINDOWS = "import os, sys; sys.modules['resource'] = None; del os.fork; "


def run_as_on_windows(code, cwd):
    return subprocess.run([sys.executable, "-c", AS_ON_WINDOWS + code], cwd=cwd,
                          env=headless_env(), capture_output=True, text=True,
                          timeout=SUBPROCESS_TIMEOUT)


WHERE_THE_GRADER_RUNS = (
    "course_kit grade: the grader runs on Linux, macOS, WSL or Gradescope: it needs "
    "process limits (the resource module) and os.fork, which this system lacks (the "
    "handout and its checks run anywhere)\n")


def test_without_resource_and_fork_the_grader_says_where_it_runs_in_one_sentence(tmp_path):
    (tmp_path / "submissions").mkdir()
    result = run_as_on_windows(
        f"sys.argv = ['course_kit', 'grade', 'submissions', '--out', 'results']; "
        f"sys.path.insert(0, {str(REPO)!r}); "
        f"import runpy; runpy.run_module('course_kit', run_name='__main__')", tmp_path)
    assert result.returncode == 1
    assert result.stderr == WHERE_THE_GRADER_RUNS
    assert not (tmp_path / "results").exists()


def test_without_resource_and_fork_the_suite_runs_and_skips_the_graders_tests(tmp_path):
    result = run_as_on_windows(
        "import pytest; sys.exit(pytest.main(['-q', '-rs', '-p', 'no:cacheprovider', "
        "'tests/test_course_kit.py', '-k', 'grades_csv or default_config_gives']))", REPO)
    assert result.returncode == 0, result.stdout + result.stderr
    assert re.search(r"\b1 passed, 1 skipped\b", result.stdout), result.stdout
    reason = WHERE_THE_GRADER_RUNS.removeprefix("course_kit grade: ").rstrip("\n")
    assert "SKIPPED [1] tests/test_course_kit.py" in result.stdout
    assert reason in result.stdout.replace("\n", " "), result.stdout


def test_a_step_server_that_dies_stops_the_grading_with_the_reason(tmp_path, monkeypatch):
    # Two submissions on one server: the first finds the server gone; the second must not
    # wait for a server that nobody gives back
    server = tmp_path / "dying_server.py"
    server.write_text("raise SystemExit(3)\n")
    monkeypatch.setattr(course_kit.isolation, "SERVER_SCRIPT", server)
    submissions = tmp_path / "submissions"
    for name in ("first", "second"):
        (submissions / name).mkdir(parents=True)
        shutil.copyfile(REPO / "PyRT_Core.py", submissions / name / "PyRT_Core.py")
    with pytest.raises(RuntimeError, match="the grader's step server ended unexpectedly"):
        course_kit.grader.grade_folder(submissions, tmp_path / "results",
                                   course_kit.grader.load_config(), jobs=1, progress=False,
                                   isolation="process")
