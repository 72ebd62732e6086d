"""Gradescope's autograder of a practice: the zip that `python -m course_kit autograder
[--practice N] ZIP` writes (Practice 1 by default), and what its run_autograder does with
each submission.

The zip holds, at its root, setup.sh (Gradescope runs it once, when it builds the
autograder's image: it installs the grader's requirements), run_autograder (Gradescope
runs it for each submission) and the kit itself: the framework (the course modules and
pyrt/) and course_kit/, which Gradescope unzips into ROOT/source/. run_autograder runs
`python3 -m course_kit.autograder run` (with `--practice N` for a practice after the
first) in ROOT/source/, which grades ROOT/submission/ as one
submission with the checks, limits and points of `grade` (course_kit/grader.py, the same
code), and writes ROOT/results/results.json, also when the grader itself fails (score 0,
the error in its output, the traceback in what it printed, which only the staff sees);
when Python cannot even start, run_autograder writes one of its own. setup.sh ends with
`python3 -m course_kit.autograder check`, which says in the build's log which isolation
run_autograder will use, or in one line why it would refuse to grade.

ROOT is the environment variable AUTOGRADER_ROOT, /autograder by default, and the Python
that runs the grader AUTOGRADER_PYTHON, python3 by default: so the zip runs end to end in
a temporary folder too, with any Python. AUTOGRADER_ISOLATION, when set, names the
isolation (course_kit/sandbox.py); process isolation, which keeps no secret from the
students' code, runs only when named so.
"""
import argparse
import json
import os
import sys
import tempfile
import time
import traceback
import zipfile
from pathlib import Path

import course_kit.handout
import course_kit.sandbox

ROOT_VARIABLE, DEFAULT_ROOT = "AUTOGRADER_ROOT", "/autograder"
SUBMISSION_NAME = "submission"
# The files of the kit, by pattern from the repository's folder
KIT_PATTERNS = ("PyRT_*.py", "AppRenderer.py", "AppWorkbench.py", "GaussianProcess.py",
                "pyrt/**/*.py",
                "course_kit/**/*.py", "course_kit/**/*.toml", "course_kit/**/*.npz",
                "requirements.txt", "requirements-dev.txt", ".vscode/*.json",
                "references/figure*.png")
# Every file of the zip gets this date, so that the same kit makes the same bytes
ZIP_DATE = (2020, 1, 1, 0, 0, 0)
# The visibilities of the results of a grader that failed, whose settings may be what
# failed: the message visible, the traceback for the staff only
FAILED_VISIBILITY = {"visibility": "visible", "stdout_visibility": "hidden"}

SETUP_SH = """\
#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image (Ubuntu 22.04,
# Python 3.10): the grader's requirements from PyPI, and bubblewrap, the sandbox of each
# step, from Ubuntu's packages (the grader uses it where the image lets it run, and says
# which isolation it uses in what it prints).
set -euo pipefail
cd "$(dirname "$0")"
apt-get update
apt-get install -y --no-install-recommends python3 python3-pip bubblewrap
"${AUTOGRADER_PYTHON:-python3}" -m pip install --no-cache-dir -r requirements.txt
# says in one line, in the image's build log, when run_autograder could not sandbox here
"${AUTOGRADER_PYTHON:-python3}" -m course_kit.autograder check
"""
RUN_AUTOGRADER = """\
#!/usr/bin/env bash
# Gradescope runs this for each submission: grades ROOT/submission/ and writes
# ROOT/results/results.json (ROOT: $AUTOGRADER_ROOT, by default /autograder), also when
# Python itself cannot start.
ROOT="${AUTOGRADER_ROOT:-/autograder}"
rm -f "$ROOT/results/results.json"
(cd "$ROOT/source" && "${AUTOGRADER_PYTHON:-python3}" -m course_kit.autograder run \
    ${AUTOGRADER_ISOLATION:+--isolation "$AUTOGRADER_ISOLATION"})
if [ ! -s "$ROOT/results/results.json" ]; then
    mkdir -p "$ROOT/results"
    echo '{"score": 0, "output": "The autograder failed before it could grade, and your' \\
        'course staff can see why.", "visibility": "visible", "stdout_visibility":' \\
        '"hidden", "tests": []}' > "$ROOT/results/results.json"
fi
"""


# ------------------------------------------------------------------------------------------
# The zip
# ------------------------------------------------------------------------------------------
def kit_files():
    """{path in the zip: bytes} of the kit's own files, sorted by path."""
    files = {}
    for pattern in KIT_PATTERNS:
        for path in course_kit.handout.REPO.glob(pattern):
            if path.is_file() and "__pycache__" not in path.parts:
                files[path.relative_to(course_kit.handout.REPO).as_posix()] = path.read_bytes()
    return dict(sorted(files.items()))


def run_autograder_script(practice=1):
    """run_autograder's text for Practice `practice`."""
    if practice == 1:
        return RUN_AUTOGRADER
    return RUN_AUTOGRADER.replace("course_kit.autograder run ",
                                  f"course_kit.autograder run --practice {practice} ")


def write_zip(path, config=None, practice=1):
    """Writes Gradescope's autograder zip of Practice `practice` to path, with the
    settings of the file config (default: course_kit/grading.toml), which must be valid
    for it."""
    import course_kit.grader
    files = kit_files()
    course_kit.grader.load_config(course_kit.grader.CONFIG if config is None else config,
                                  practice)
    if config is not None:
        files["course_kit/grading.toml"] = Path(config).read_bytes()
    entries = {"setup.sh": (SETUP_SH.encode(), 0o755),
               "run_autograder": (run_autograder_script(practice).encode(), 0o755)}
    entries.update((name, (content, 0o644)) for name, content in files.items())
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, (content, mode) in entries.items():
            info = zipfile.ZipInfo(name, ZIP_DATE)
            info.external_attr = (0o100000 | mode) << 16  # a regular file and its mode
            info.compress_type = zipfile.ZIP_DEFLATED
            archive.writestr(info, content)
    return Path(path)


# ------------------------------------------------------------------------------------------
# run_autograder
# ------------------------------------------------------------------------------------------
def gradescope_submission(folder):
    """The Submission in Gradescope's submission folder: its course modules wherever they
    lie (the shallowest of each name), else those of the shallowest .zip in it that has
    any."""
    import course_kit.grader
    submission = course_kit.grader.read_submission(SUBMISSION_NAME, folder)
    if submission.files:
        return submission
    archives = sorted(Path(folder).rglob("*.zip"),
                      key=lambda path: (len(path.relative_to(folder).parts), str(path)))
    for archive in archives:
        zipped = course_kit.grader.read_submission(SUBMISSION_NAME, archive)
        if zipped.files:
            return zipped
    submission.problems.append("no course module ("
                               + ", ".join(course_kit.handout.COURSE_MODULES)
                               + ") was found in what you handed in")
    return submission


def refusal_of(isolation):
    """Why run_autograder refuses to grade in isolation (chosen by course_kit.sandbox), in
    one line, or None when it grades: where the image cannot sandbox the students' code,
    unless process isolation was asked for."""
    missing = course_kit.sandbox.cannot_sandbox(isolation)
    if missing is None:
        return None
    return (f"{missing}; run_autograder grades here only with "
            f"AUTOGRADER_ISOLATION=process, and then {course_kit.sandbox.PROCESS_LIMIT}")


def check():
    """What setup.sh prints when Gradescope builds the image: the isolation that
    run_autograder will use, or the one line saying why it will refuse to grade."""
    chosen = course_kit.sandbox.choose()
    refusal = refusal_of(chosen)
    if refusal:
        print(f"PyRT's autograder: WARNING: {refusal}", flush=True)
    else:
        print(f"PyRT's autograder: the isolation of each step: {chosen.describe()}")
    return refusal


def run(root, isolation=None, practice=1):
    """Grades root/submission/ for Practice `practice` into root/results/results.json (see
    the module's docstring); returns what it wrote."""
    root = Path(root)
    start = time.monotonic()
    results = root / "results"
    results.mkdir(parents=True, exist_ok=True)
    # the student's code may run as another user: none of these is for its eyes
    for folder in (results, root / "source", root / SUBMISSION_NAME):
        if folder.is_dir():
            folder.chmod(0o700)
    try:
        # imported here, so that a grader that cannot even load (a requirement missing on
        # the image) leaves its results.json too
        import course_kit.feedback
        import course_kit.grader
        config = course_kit.grader.load_config(course_kit.grader.CONFIG, practice)
        refusal = refusal_of(course_kit.sandbox.choose(isolation))
        if refusal:
            raise course_kit.sandbox.IsolationUnavailable(refusal)
        submission = gradescope_submission(root / SUBMISSION_NAME)
        with tempfile.TemporaryDirectory(prefix="pyrt-autograder-") as graded:
            record, = course_kit.grader.grade_submissions(
                [submission], graded, config, jobs=1, progress=False, isolation=isolation)
        outcome = course_kit.feedback.gradescope_results(record, config.gradescope)
        for test in outcome["tests"]:
            print(f"{test['number']}: {test['status']}, {test['score']} of "
                  f"{test['max_score']}")
    except Exception as error:  # noqa: BLE001  (whatever fails, Gradescope gets a result)
        traceback.print_exc(file=sys.stdout)
        outcome = {"score": 0, "output": "The autograder failed, and your course staff can "
                   f"see why: {type(error).__name__}: {error}",
                   **FAILED_VISIBILITY, "tests": []}
    outcome["execution_time"] = round(time.monotonic() - start, 2)
    written = results / "results.json"
    partial = results / "results.json.part"
    partial.write_text(json.dumps(outcome, indent=2) + "\n", encoding="utf-8")
    os.replace(partial, written)
    print(f"score {outcome['score']}: {written}")
    return outcome


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m course_kit.autograder", description="What Gradescope's run_autograder runs: "
        f"grades ${ROOT_VARIABLE}/{SUBMISSION_NAME}/ (default root {DEFAULT_ROOT}) into "
        "results/results.json.")
    parser.add_argument("command", choices=["run", "check"], help="run: grade the "
                        "submission; check: say which isolation run would use (setup.sh)")
    course_kit.sandbox.add_argument(parser)
    parser.add_argument("--practice", type=int, default=1, help="the practice graded")
    args = parser.parse_args(argv)
    if args.command == "check":
        check()
    else:
        run(Path(os.environ.get(ROOT_VARIABLE, DEFAULT_ROOT)), args.isolation,
            args.practice)
    return 0


if __name__ == "__main__":
    sys.exit(main())
