"""The isolation of the grader's steps (course_kit/sandbox.py): the choice of a mode, and
hostile submissions, written as a student could write them, graded under bubblewrap.

Each hostile submission is the right solution with hostile code in one step. Under
bubblewrap each is stopped or has no effect, gets its verdict, and the right submission
graded beside them gets all its points. The tests that need bubblewrap are skipped where
it cannot run (CI installs it, see .ci/run)."""
import os
import random
import shutil
import socket
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

import course_kit.__main__
import course_kit.autograder
import course_kit.grader
import course_kit.handout
import course_kit.sandbox
import course_kit_students as students

NO_UNPRIVILEGED_USER = course_kit.sandbox.why_no_unprivileged_user()
UNPRIVILEGED_USER = pytest.mark.skipif(
    NO_UNPRIVILEGED_USER is not None,
    reason=f"needs the unprivileged user's isolation: {NO_UNPRIVILEGED_USER}")
NO_BUBBLEWRAP = course_kit.sandbox.why_no_bubblewrap()
BUBBLEWRAP = pytest.mark.skipif(NO_BUBBLEWRAP is not None,
                                reason=f"needs bubblewrap's sandbox: {NO_BUBBLEWRAP}")
CONFIG = """\
[points]
"1.1" = 25
"1.2" = 25
"1.3" = 25
"1.4" = 25

[limits]
cpu_seconds = 60
wall_seconds = {wall}
memory_mib = 2048
output_kib = 256
"""
GENEROUS_WALL = 300  # seconds: a normal step takes one, however loaded the machine
SECRET = "the grader's secret: 42"

# Hostile answers, each run on the first call of its compute_color; {NAME} fields are
# filled in by the tests with paths and a port
def once(integrator, code):
    """code run on the first call of integrator's compute_color only, then the right
    answer of its stub."""
    stub = {"DepthIntegrator": "depth", "IntersectionIntegrator": "intersection",
            "NormalIntegrator": "normal", "PhongIntegrator": "phong"}[integrator]
    guarded = "".join("    " + line for line in code.splitlines(keepends=True))
    return {stub: f"if not getattr({integrator}, 'tried', False):\n"
                  f"    {integrator}.tried = True\n{guarded}" + students.RIGHT[stub]}


WRITES_THROUGH_C = once("DepthIntegrator", """\
import ctypes, os
libc = ctypes.CDLL(None)
for path in [{OUTSIDE!r}, {OTHER!r}]:
    fd = libc.open(path.encode(), os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)
    if fd >= 0:
        libc.write(fd, b"written by C", 12)
        libc.close(fd)
""")
CONNECTS = once("IntersectionIntegrator", """\
import socket
try:
    with socket.create_connection(("127.0.0.1", {PORT}), timeout=5) as connection:
        connection.sendall(b"the answers of the checks")
except OSError:
    pass
""")
READS_OTHERS = once("NormalIntegrator", """\
for path in [{OTHER!r}, {RESULTS!r}]:
    try:
        text = open(path).read()
    except OSError:
        continue
    raise RuntimeError('read ' + path + ': ' + text[:60])
""")
# Children that wait for ever, as many as the system lets it make (at most 300)
FORKS_MANY = once("PhongIntegrator", """\
import ctypes
libc = ctypes.CDLL(None)
forked = 0
for _ in range(300):
    child = libc.fork()
    if child == 0:
        libc.pause()
    forked += child > 0
print('forked', forked, flush=True)
""")
# Every process forks again, until the system refuses
FORK_BOMB = once("PhongIntegrator", """\
import ctypes, os
libc = ctypes.CDLL(None)
first = os.getpid()
forked = 0
while libc.fork() >= 0:
    forked += 1
if os.getpid() != first:
    libc.pause()
print('forked', forked, flush=True)
""")
SLEEPS = {"phong": "import time\ntime.sleep(3600)\n"}


def hostile(answers, fields):
    """answers with their fields ({placeholder: text}) filled in."""
    filled = {}
    for stub, code in answers.items():
        for placeholder, text in fields.items():
            code = code.replace(placeholder, text)
        filled[stub] = code
    return filled


def grade(tmp_path, submissions, handout, wall=GENEROUS_WALL, results=None,
          isolation="bubblewrap"):
    """{name: record} of the submissions ({name: answers}) graded under isolation with
    a step's wall-clock limit of wall seconds, two at a time."""
    folder = tmp_path / "submissions"
    for name, answers in submissions.items():
        students.write_submission(folder / name, handout, answers)
    config = tmp_path / "grading.toml"
    config.write_text(CONFIG.format(wall=wall))
    records = course_kit.grader.grade_folder(folder, results or tmp_path / "results",
                                         course_kit.grader.load_config(config), jobs=2,
                                         progress=False, isolation=isolation,
                                         draws=random.Random(3))
    return {record["submission"]: record for record in records}


def steps_of(record):
    return {step["step"]: step for step in record["steps"]}


def processes_of(users):
    """The processes of users (numbers; None, the grader's own user, matches none)."""
    found = []
    for entry in os.scandir("/proc"):
        try:
            if entry.name.isdigit() and entry.stat().st_uid in users:
                found.append(entry.name)
        except OSError:  # a process that has just ended
            pass
    return found


@pytest.fixture
def confinements(monkeypatch):
    """The Confinements of the step servers started in the test."""
    made = []
    original = course_kit.sandbox.confinement

    def recording(isolation):
        made.append(original(isolation))
        return made[-1]

    monkeypatch.setattr(course_kit.sandbox, "confinement", recording)
    return made


def left_running(confinements):
    """The processes of the steps' users (none without root: the steps are then the
    grader's user, and the end of bubblewrap's namespace kills what they leave)."""
    return processes_of({made.user for made in confinements})


@pytest.fixture(scope="module")
def handout(tmp_path_factory):
    return course_kit.handout.write_handout(tmp_path_factory.mktemp("sandbox") / "handout")


# ------------------------------------------------------------------------------------------
# The choice of an isolation
# ------------------------------------------------------------------------------------------
def test_an_isolation_asked_for_is_taken_and_an_unknown_one_refused():
    assert course_kit.sandbox.choose("process") == course_kit.sandbox.Isolation("process",
                                                                        "asked for")
    with pytest.raises(course_kit.sandbox.IsolationUnavailable) as error:
        course_kit.sandbox.choose("docker")
    assert str(error.value) == ("unknown isolation 'docker'; the isolations are bubblewrap, "
                                "unprivileged user, process")


def test_without_bwrap_bubblewrap_is_refused_and_a_weaker_isolation_says_why(monkeypatch):
    monkeypatch.setattr(course_kit.sandbox.shutil, "which", lambda name: None)
    monkeypatch.setattr(course_kit.sandbox, "bubblewrap_runs", lambda: False)
    monkeypatch.setattr(course_kit.sandbox, "other_user_runs_python", lambda: False)
    with pytest.raises(course_kit.sandbox.IsolationUnavailable) as error:
        course_kit.sandbox.choose("bubblewrap")
    assert str(error.value) == ("the isolation bubblewrap cannot run: bwrap is not installed "
                                "(apt-get install bubblewrap)")
    chosen = course_kit.sandbox.choose()
    assert chosen.mode == "process"
    assert chosen.describe().startswith("process (bwrap is not installed (apt-get install "
                                        "bubblewrap); no unprivileged user: ")


def test_the_unprivileged_user_can_be_switched_off(monkeypatch):
    monkeypatch.setenv(course_kit.sandbox.NO_UNPRIVILEGED_USER, "1")
    monkeypatch.setattr(course_kit.sandbox, "other_user_runs_python", lambda: True)
    assert course_kit.sandbox.why_no_unprivileged_user() == (
        "switched off (COURSE_KIT_NO_UNPRIVILEGED_USER is set)")
    with pytest.raises(course_kit.sandbox.IsolationUnavailable) as error:
        course_kit.sandbox.choose("unprivileged user")
    assert str(error.value).endswith("switched off (COURSE_KIT_NO_UNPRIVILEGED_USER is set)")


def test_a_python_in_a_private_home_is_named_as_what_keeps_the_unprivileged_user_out(
        monkeypatch):
    # in /tmp, which all may enter (pytest's own folders are their user's only)
    with tempfile.TemporaryDirectory(dir="/tmp") as folder:
        os.chmod(folder, 0o755)
        private_home_is_named(monkeypatch, Path(folder) / "home")


def private_home_is_named(monkeypatch, home):
    python = home / "pyenv" / "bin" / "python3"
    python.parent.mkdir(parents=True)
    python.touch()
    home.chmod(0o700)
    monkeypatch.setattr(course_kit.sandbox.sys, "executable", str(python))
    monkeypatch.setattr(course_kit.sandbox.sys, "platform", "linux")
    monkeypatch.setattr(course_kit.sandbox, "_as_root", lambda: True)
    monkeypatch.setattr(course_kit.sandbox, "other_user_runs_python", lambda: False)
    monkeypatch.delenv(course_kit.sandbox.NO_UNPRIVILEGED_USER, raising=False)
    assert course_kit.sandbox.why_no_unprivileged_user() == (
        f"this Python ({python}) lies under {home}, which other users cannot enter: grade "
        "with a Python outside a private home, such as /usr/bin/python3")
    home.chmod(0o755)
    assert course_kit.sandbox.why_no_unprivileged_user() == (
        f"another user cannot run this Python ({python}) with numpy: grade with a Python "
        "outside a private home, such as /usr/bin/python3")


def cannot_sandbox(monkeypatch):
    """A machine with neither bubblewrap nor an unprivileged user, as the grader sees it."""
    monkeypatch.setattr(course_kit.sandbox, "why_no_bubblewrap",
                        lambda: "bwrap is not installed (apt-get install bubblewrap)")
    monkeypatch.setattr(course_kit.sandbox, "why_no_unprivileged_user",
                        lambda: "the grader does not run as root")


def test_grade_says_in_one_line_before_grading_that_the_machine_cannot_sandbox(
        monkeypatch, tmp_path, capsys):
    cannot_sandbox(monkeypatch)
    (tmp_path / "submissions").mkdir()
    args = course_kit.__main__.parse_args(["grade", str(tmp_path / "submissions"), "--out",
                                           str(tmp_path / "results")])
    assert course_kit.grader.main(args) == 0
    assert capsys.readouterr().err.splitlines() == [
        "course_kit grade: this machine cannot sandbox the students' code: bwrap is not "
        "installed (apt-get install bubblewrap); no unprivileged user: the grader does not "
        "run as root; " + course_kit.sandbox.PROCESS_LIMIT]


def test_grade_says_what_the_unprivileged_user_may_read_when_it_takes_that_isolation(
        monkeypatch, tmp_path, capsys):
    monkeypatch.setattr(course_kit.sandbox, "choose", lambda requested=None: (
        course_kit.sandbox.Isolation("unprivileged user", "bwrap is not installed")))
    monkeypatch.setattr(course_kit.grader, "grade_folder", lambda *args, **options: [])
    args = course_kit.__main__.parse_args(["grade", str(tmp_path), "--out",
                                           str(tmp_path / "results")])
    course_kit.grader.main(args)
    err, = capsys.readouterr().err.splitlines()
    assert err.startswith("course_kit grade: in the unprivileged user's isolation any copy "
                          "of the finished framework that all users may read is in the "
                          "students' reach")
    assert "keep your checkouts private" in err


def test_the_autograders_setup_says_in_one_line_when_the_image_cannot_sandbox(
        monkeypatch, capsys):
    cannot_sandbox(monkeypatch)
    refusal = course_kit.autograder.check()
    assert capsys.readouterr().out == f"PyRT's autograder: WARNING: {refusal}\n"
    assert refusal.startswith("this machine cannot sandbox the students' code: bwrap is not "
                              "installed (apt-get install bubblewrap)")
    assert refusal.endswith("run_autograder grades here only with AUTOGRADER_ISOLATION="
                            "process, and then " + course_kit.sandbox.PROCESS_LIMIT)
    assert "-m course_kit.autograder check" in course_kit.autograder.SETUP_SH
    monkeypatch.setattr(course_kit.sandbox, "why_no_bubblewrap", lambda: None)
    assert course_kit.autograder.check() is None
    assert capsys.readouterr().out == ("PyRT's autograder: the isolation of each step: "
                                       "bubblewrap\n")


def test_the_grader_says_which_isolation_it_uses_in_the_terminal_and_the_record(
        handout, tmp_path, capsys):
    folder = tmp_path / "submissions"
    shutil.copytree(handout, folder / "untouched",
                    ignore=lambda _, names: [n for n in names
                                             if n not in course_kit.handout.COURSE_MODULES])
    config = course_kit.grader.load_config()
    records = course_kit.grader.grade_folder(folder, tmp_path / "results", config, jobs=1,
                                         progress=False, isolation="process")
    assert capsys.readouterr().out == "Isolation of each step: process (asked for)\n"
    assert records[0]["isolation"] == "process"


def test_the_sandbox_shows_no_folder_of_the_grader_but_its_cell(tmp_path):
    command = course_kit.sandbox.bubblewrap_command(tmp_path / "cell", root=True)
    assert command[:2] == ["bwrap", "--die-with-parent"]
    for option in course_kit.sandbox.NAMESPACES + ("--cap-drop", "--tmpfs"):
        assert option in command
    read_write = [command[at + 1] for at, option in enumerate(command) if option == "--bind"]
    assert read_write == [str(tmp_path / "cell")]
    assert command.index("--tmpfs") < command.index("--bind")  # the cell lies in /tmp


# ------------------------------------------------------------------------------------------
# Hostile submissions under bubblewrap
# ------------------------------------------------------------------------------------------
def hostile_fields(base):
    """The fields of the hostile answers, with their files in the folder base: (the
    results' folder, with a secret in it, the folder of another submission, a file
    outside, the fields)."""
    results = base / "results"
    results.mkdir()
    (results / "secret.txt").write_text(SECRET)
    others, outside = base / "submissions" / "right", base / "outside.txt"
    return results, others, outside, {"{OUTSIDE!r}": repr(str(outside)),
                                      "{OTHER!r}": repr(str(others / "PyRT_Core.py")),
                                      "{RESULTS!r}": repr(str(results / "secret.txt"))}


@pytest.fixture
def open_folder():
    """A new folder that all may read, outside pytest's own, which only its user may."""
    folder = Path(tempfile.mkdtemp(prefix="pyrt-open-"))
    folder.chmod(0o755)
    yield folder
    shutil.rmtree(folder)


@pytest.fixture
def listening():
    """A socket listening on an ephemeral port of 127.0.0.1."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as server:
        server.bind(("127.0.0.1", 0))
        server.listen(8)
        yield server


@BUBBLEWRAP
def test_hostile_submissions_are_contained_and_the_others_graded_as_if_alone(
        handout, tmp_path, listening):
    results, others, outside, fields = hostile_fields(tmp_path)
    fields["{PORT}"] = str(listening.getsockname()[1])
    records = grade(tmp_path, {
        "right": {}, "writes_through_c": hostile(WRITES_THROUGH_C, fields),
        "connects": hostile(CONNECTS, fields), "reads_others": hostile(READS_OTHERS, fields),
    }, handout, results=results)
    for name, record in records.items():
        assert record["isolation"] == "bubblewrap"
        assert record["total"] == 100, (name, [step["reason"] for step in record["steps"]])
    # The write through C reached neither the folder outside nor the other submission
    assert not outside.exists()
    assert "written by C" not in (others / "PyRT_Core.py").read_text()
    # No connection arrived
    listening.setblocking(False)
    with pytest.raises(BlockingIOError):
        listening.accept()


@BUBBLEWRAP
def test_a_fork_bomb_meets_the_limit_on_processes_and_leaves_nothing_running(
        handout, tmp_path, confinements):
    # First a bounded number of forks, to see the limit hold before the bomb runs
    for name, answers in (("many", FORKS_MANY), ("bomb", FORK_BOMB)):
        records = grade(tmp_path / name, {"forks": answers}, handout)
        steps = steps_of(records["forks"])
        assert all(steps[step]["passed"] for step in ("1.1", "1.2", "1.3"))
        forked = [int(line.split()[1]) for line in steps["1.4"]["output"].splitlines()
                  if line.startswith("forked ")]
        # The step itself counts: it makes fewer children than the limit
        assert forked and max(forked) < min(made.processes for made in confinements)
        assert left_running(confinements) == []
    assert all(made.processes == course_kit.sandbox.MAX_PROCESSES
               for made in confinements if made.user is not None)


@BUBBLEWRAP
def test_a_step_that_sleeps_past_the_wall_clock_limit_is_stopped(handout, tmp_path,
                                                                confinements):
    # Only the sleeping step's verdict is asserted: with a limit this short, the others'
    # could depend on the machine's load
    records = grade(tmp_path, {"sleeps": SLEEPS}, handout, wall=2)
    assert steps_of(records["sleeps"])["1.4"]["reason"] == (
        "did not finish within 2 s, the time limit of a step: the code hangs or is far too "
        "slow")
    assert confinements and left_running(confinements) == []


@BUBBLEWRAP
def test_the_sandbox_has_no_network_and_shows_none_of_the_graders_folders(tmp_path):
    (tmp_path / "grader's.txt").write_text(SECRET)
    confinement = course_kit.sandbox.confinement(course_kit.sandbox.Isolation("bubblewrap"))
    try:
        probe = [*confinement.wrapper, sys.executable, "-I", "-c",
                 f"import os, socket; print(os.path.exists({str(tmp_path)!r}), "
                 "os.path.isdir(os.getcwd()), socket.if_nameindex())"]
        output = subprocess.run(probe, capture_output=True, text=True, check=True).stdout
    finally:
        course_kit.sandbox.close_confinement(confinement)
    assert output == "False True [(1, 'lo')]\n"
    assert not os.path.exists(confinement.cell)


@pytest.mark.skipif(not sys.platform.startswith("linux") or os.geteuid() != 0,
                    reason="a step's user exists only where the grader runs as root")
def test_what_a_steps_user_could_read_is_found_not_assumed(open_folder, tmp_path):
    shown, private = open_folder / "shown.txt", tmp_path / "private.txt"
    for path in (shown, private):
        path.write_text(SECRET)
    shown.chmod(0o644)
    private.chmod(0o600)
    assert course_kit.sandbox.readable_by_steps([shown, private]) == [str(shown)]
    with pytest.raises(course_kit.sandbox.IsolationUnavailable, match=str(shown)):
        course_kit.sandbox.check_unreadable([private, shown])


@UNPRIVILEGED_USER
def test_an_unprivileged_user_is_refused_where_the_graders_folders_are_open(handout,
                                                                           open_folder):
    # What this mode cannot hold is what all may read: the grader finds it, and stops
    results, _, _, _ = hostile_fields(open_folder)
    results.chmod(0o755)
    with pytest.raises(course_kit.sandbox.IsolationUnavailable, match="chmod 700"):
        grade(open_folder, {"right": {}}, handout, results=results,
              isolation="unprivileged user")


def test_a_step_users_lock_is_held_once_and_its_file_goes_when_given_back(monkeypatch,
                                                                           tmp_path):
    monkeypatch.setattr(course_kit.sandbox, "LOCKS", str(tmp_path))
    lock = course_kit.sandbox._lock_user(7)
    assert lock is not None
    assert course_kit.sandbox._lock_user(7) is None  # held: another grader passes it by
    course_kit.sandbox._release_user(7, lock)
    assert list(tmp_path.iterdir()) == []  # grading leaves /tmp as it found it
    again = course_kit.sandbox._lock_user(7)
    assert again is not None
    course_kit.sandbox._release_user(7, again)
