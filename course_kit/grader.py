"""The grader of a practice: `python -m course_kit grade [--practice N] SUBMISSIONS --out
RESULTS` (Practice 1 by default; course_kit/practices.py lists the practices).

Every entry of SUBMISSIONS (a folder or a .zip) is one submission: the course modules it
holds (PyRT_Common.py, PyRT_Core.py, PyRT_Integrators.py, AppRenderer.py, and Practice 2's
AppWorkbench.py, wherever they lie in it; the shallowest of each name counts) are copied
over a fresh copy of the practice's handout without its checks. Each assignment step
runs the student's code there, on inputs drawn for this grading, in a process of its own
(course_kit/isolation.py) with limits of time, memory and output, isolated as
course_kit/sandbox.py chooses (bubblewrap's sandbox, an unprivileged user, or the process
alone); that process hands back data only,
which this process judges (the practice's judge: course_kit/judging.py for Practice 1,
course_kit/judging_practice2.py for Practice 2) with the students' own rules
(course_kit/checks/practice<N>_checks.py). The submissions themselves are only read.

RESULTS gets grades.csv, and for each submission a folder with feedback.html, results.json
(Gradescope's format), grading.json (the grader's record) and the images of the checks
that failed. A submission whose grading.json shows the same files, checks and settings is
not graded again, unless force is asked.
"""
import hashlib
import importlib
import json
import os
import queue
import random
import shutil
import sys
import tempfile
import time
import zipfile
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

from tqdm import tqdm

if sys.version_info >= (3, 11):
    import tomllib
else:  # tomllib came with Python 3.11; tomli is the same reader, for Python 3.10
    import tomli as tomllib

import course_kit.feedback
import course_kit.handout
import course_kit.isolation
import course_kit.sandbox
from course_kit.practices import PRACTICES, all_steps

CONFIG = course_kit.handout.KIT / "grading.toml"
STEP_TITLES = PRACTICES[1].steps  # Practice 1's; each practice has its own
LIMIT_NAMES = ("cpu_seconds", "wall_seconds", "memory_mib", "output_kib")
# When students see what Gradescope shows: the tests (visibility) and what the grader
# printed (stdout_visibility); the defaults are what results.json has always said
GRADESCOPE_DEFAULTS = {"visibility": "visible", "stdout_visibility": "hidden"}
VISIBILITIES = ("hidden", "visible", "after_due_date", "after_published")
# PyRT's machinery that gives the answers of steps 1.2 and 1.4 (the fast any_hit, the
# fused Phong, the stories' Phong terms): a working copy has none of it, and the plain code that stands in for it
# runs the student's own (or the framework's own) any_hit and compute_color
ANSWERING_MACHINERY = ("pyrt/acceleration/accelerated.py", "pyrt/acceleration/queries.py",
                       "pyrt/acceleration/phong.py", "pyrt/acceleration/culling.py",
                       "pyrt/course_model.py",
                       # the exact z, Q and weights of the framework's GaussianProcess.py
                       "pyrt/gp_inputs.py", "pyrt/gp_integrals.py", "pyrt/gp_kernels.py",
                       "pyrt/gp_solves.py")
PLAIN_ACCELERATION = '''"""PyRT's acceleration, left out of the grader's working copy: the plain code runs."""
import contextlib


def accelerated(integrator, rays=None):
    """No acceleration: the scene's and the integrator's own methods run."""
    return contextlib.nullcontext()


def plain(obj):
    """Nothing to take off: nothing was put on."""


def debugger_attached():
    """Whether a debugger is attached: never asked for in a working copy."""
    return False
'''
# The course modules taken from a submission: those of every practice (a module the
# practice graded does not use changes nothing)
SUBMITTED_MODULES = tuple(dict.fromkeys(name for one in PRACTICES.values()
                                        for name in one.modules))
MAX_MODULE_BYTES = 1024 * 1024  # a course module larger than this is not taken
OUTPUT_SHOWN = 4000  # characters of a step's output kept for the feedback
REASON_LENGTH = 240  # characters of a failed step's reason in grades.csv
# How the step's guard words a refusal to read the framework's answers
STOLEN = course_kit.isolation.READ_ANSWERS


# ------------------------------------------------------------------------------------------
# Settings
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Config:
    """The points of each step of the practice graded, the limits of a step's process and
    Gradescope's visibilities (course_kit/grading.toml), and the practice's number."""

    points: dict
    limits: dict
    text: str  # the file's text, part of what makes a grading repeatable
    gradescope: dict = field(default_factory=lambda: dict(GRADESCOPE_DEFAULTS))
    practice: int = 1

    @property
    def kind(self):
        """The course_kit.practices.Practice graded."""
        return PRACTICES[self.practice]


def load_config(path=CONFIG, practice=1):
    """The Config of path for Practice `practice`: its [points] give every step of that
    practice, and may give those of the others."""
    path = Path(path)
    text = path.read_text(encoding="utf-8")
    try:
        settings = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{path}: {error}") from None
    points, limits = settings.get("points", {}), settings.get("limits", {})
    steps = list(PRACTICES[practice].steps)
    if not set(steps) <= set(points) <= set(all_steps()) or sorted(limits) != sorted(
            LIMIT_NAMES):
        raise ValueError(f"{path}: [points] must give the steps {', '.join(steps)} (and "
                         f"may give those of the other practices: "
                         f"{', '.join(sorted(set(all_steps()) - set(steps)))}) and "
                         f"[limits] {', '.join(LIMIT_NAMES)}")
    for table, values in (("points", points), ("limits", limits)):
        for key, value in values.items():
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
                    value > 0 or (table == "points" and value == 0)):
                raise ValueError(f"{path}: [{table}] {key} must be a positive number, "
                                 f"got {value!r}")
    gradescope = {**GRADESCOPE_DEFAULTS, **settings.get("gradescope", {})}
    if sorted(gradescope) != sorted(GRADESCOPE_DEFAULTS):
        raise ValueError(f"{path}: [gradescope] may give only "
                         + ", ".join(GRADESCOPE_DEFAULTS))
    for key, value in gradescope.items():
        if value not in VISIBILITIES:
            raise ValueError(f"{path}: [gradescope] {key} must be one of "
                             f"{', '.join(VISIBILITIES)}, got {value!r}")
    return Config({step: points[step] for step in steps}, dict(limits), text, gradescope,
                  practice)


# ------------------------------------------------------------------------------------------
# Submissions
# ------------------------------------------------------------------------------------------
@dataclass
class Submission:
    """What one student handed in: its name (the folder's, or the zip's without .zip), the
    course modules found in it, and what stood in the way of reading it."""

    name: str
    path: Path
    files: dict = field(default_factory=dict)  # module name -> bytes
    problems: list = field(default_factory=list)

    def digest(self):
        sha = hashlib.sha256()
        for name in sorted(self.files):
            sha.update(name.encode() + b"\0" + self.files[name] + b"\0")
        for problem in self.problems:
            sha.update(problem.encode() + b"\0")
        return sha.hexdigest()


def find_submissions(folder):
    """The submissions of folder, sorted by name: its folders and .zip files (hidden ones
    left out)."""
    folder = Path(folder)
    if not folder.is_dir():
        raise FileNotFoundError(f"{folder} is not a folder of submissions")
    submissions = {}
    for entry in sorted(folder.iterdir()):
        if entry.name.startswith("."):
            continue
        if entry.is_dir():
            submission = read_submission(entry.name, entry)
        elif entry.suffix.lower() == ".zip" and entry.is_file():
            submission = read_submission(entry.stem, entry)
        else:
            continue
        if submission.name in submissions:
            raise ValueError(f"two submissions are called {submission.name!r}: "
                             f"{submissions[submission.name].path} and {entry}")
        submissions[submission.name] = submission
    return list(submissions.values())


def read_submission(name, path):
    """The Submission called name whose files are the folder or .zip file at path."""
    submission = Submission(name, Path(path))
    if submission.path.is_dir():
        _read_folder(submission)
    else:
        _read_zip(submission)
    return submission


def _shallowest(paths):
    """{module name: the shallowest of paths (PurePosixPath) with that name}."""
    chosen = {}
    for path in sorted(paths, key=lambda p: (len(p.parts), str(p))):
        if path.name in SUBMITTED_MODULES:
            chosen.setdefault(path.name, path)
    return chosen


def _take(submission, name, size, read):
    if size > MAX_MODULE_BYTES:
        submission.problems.append(f"{name} is larger than {MAX_MODULE_BYTES} bytes: not "
                                   "taken, the handout's is used")
    else:
        submission.files[name] = read()


def _read_folder(submission):
    root = submission.path
    paths = []
    for folder, folders, names in os.walk(root):  # symbolic links are not followed
        folders.sort()
        for name in names:
            path = Path(folder) / name
            if not path.is_symlink():
                paths.append(PurePosixPath(path.relative_to(root).as_posix()))
    for name, path in _shallowest(paths).items():
        full = root / path
        _take(submission, name, full.stat().st_size, full.read_bytes)


def _read_zip(submission):
    try:
        with zipfile.ZipFile(submission.path) as archive:
            members = {PurePosixPath(info.filename): info for info in archive.infolist()
                       if not info.is_dir() and ".." not in PurePosixPath(info.filename).parts
                       and not info.filename.startswith("/")}
            for name, path in _shallowest(members).items():
                info = members[path]
                _take(submission, name, info.file_size,
                      lambda info=info: archive.read(info))
    except (zipfile.BadZipFile, OSError) as error:
        submission.problems.append(f"{submission.path.name} is not a readable zip file "
                                   f"({error})")


# ------------------------------------------------------------------------------------------
# Running the steps
# ------------------------------------------------------------------------------------------
def framework_machinery():
    """The modules of PyRT's machinery that the handout leaves out (pyrt/rendering.py, ...),
    as paths relative to the repository, but those that compute a step's answer (see
    PLAIN_ACCELERATION): the working copies hold them too, so that the finished framework
    itself can be graded."""
    shipped = set(course_kit.handout.SHIPPED_AS_IS) | set(ANSWERING_MACHINERY)
    repo = course_kit.handout.REPO
    return [path.relative_to(repo) for path in sorted((repo / "pyrt").rglob("*.py"))
            if path.relative_to(repo).as_posix() not in shipped]


def make_working_copy(submission, template, workdir):
    """The working copy of submission in workdir: the handout without its checks, PyRT's
    machinery without what computes an answer, and the submission's modules."""
    shutil.copytree(template, workdir, ignore=lambda folder, names: (
        ["tests"] if Path(folder) == Path(template) else []))
    for path in framework_machinery():
        (workdir / path).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(course_kit.handout.REPO / path, workdir / path)
    (workdir / "pyrt" / "acceleration" / "accelerated.py").write_text(PLAIN_ACCELERATION)
    for name, content in submission.files.items():
        (workdir / name).write_bytes(content)


def grade_steps(submission, template, scratch, config, server, trial):
    """The verdicts of every step for submission, its working copy made in scratch, its
    steps run by server (a course_kit.isolation.StepServer) on the inputs of trial (a
    Trial of the practice's judge) and judged here."""
    workdir = scratch / "work"
    make_working_copy(submission, template, workdir)
    course_kit.sandbox.hand_over(scratch, workdir, server.confinement.user)
    verdicts = []
    judge = importlib.import_module(config.kind.judge)
    for step, title in config.kind.steps.items():
        checks, refused, limits_not_set, why, output = judge.judge_step(
            step, trial, server, workdir, scratch, config.limits)
        failed = [check for check in checks if not check["passed"]]
        if why:
            reason = why
        elif refused:
            reason = "refused: " + "; ".join(dict.fromkeys(refused))
        elif failed:
            reason = course_kit.feedback.check_reason(failed[0])
        else:
            reason = ""
        passed = not reason
        verdicts.append({
            "step": step, "title": title, "max_points": config.points[step],
            "output": output[-OUTPUT_SHOWN:], "checks": checks, "passed": passed,
            "reason": reason, "points": config.points[step] if passed else 0,
            # the system's doing, not the student's: grade_submission takes it out
            "limits_not_set": limits_not_set, "refused": list(refused)})
    return _without_stolen_answers(verdicts)


def _without_stolen_answers(verdicts):
    """verdicts with every step at no points when the guard caught one step reading the
    framework's answers (course_kit/isolation.py's FRAMEWORK_ANSWERS): what the code of
    such a submission makes is not its own in any step, so it scores what the untouched
    handout scores, which solves nothing (a step that reads nothing may still run what
    was read, held in memory or copied into another module)."""
    caught = [(verdict["step"], refusal) for verdict in verdicts
              for refusal in verdict.pop("refused") if refusal.startswith(STOLEN)]
    if not caught:
        return verdicts
    step, refusal = caught[0]
    reason = (f"refused: {refusal}, in step {step}: no step of a submission that reads "
              "the framework's answers earns points")
    for verdict in verdicts:
        verdict.update(passed=False, points=0, reason=reason)
    return verdicts


# ------------------------------------------------------------------------------------------
# Grading a folder
# ------------------------------------------------------------------------------------------
def kit_fingerprint(config):
    """What else decides a grade besides the submission: the handout with its checks and
    expected images, the step's process, the judge and the settings."""
    sha = hashlib.sha256()
    for name, content in course_kit.handout.handout_files(config.practice).items():
        sha.update(name.encode() + b"\0" + content + b"\0")
    machinery = [course_kit.handout.REPO / path for path in framework_machinery()]
    kit = ("isolation.py", "sandbox.py", "handback.py", "practices.py",
           config.kind.judge.rsplit(".", 1)[1] + ".py")
    for path in machinery + [course_kit.handout.KIT / name for name in kit]:
        sha.update(path.read_bytes())
    sha.update(config.text.encode())
    return sha.hexdigest()


def grade_submission(submission, template, results, config, kit, servers, isolation,
                     trial):
    """Grades one submission on the inputs of trial (the Trial of the practice's judge) and
    writes its folder of results; returns its record. Its steps run on a step server
    taken from the queue servers, and given back, isolated as isolation (a
    course_kit.sandbox.Isolation) says."""
    fingerprint = hashlib.sha256((submission.digest() + kit).encode()).hexdigest()
    start = time.monotonic()
    server = servers.get()
    try:  # the server's next submission comes once this one's working copy is gone
        with tempfile.TemporaryDirectory(prefix=f"pyrt-grading-{os.getpid()}-",
                                         dir=server.confinement.cell) as scratch:
            scratch = Path(scratch)
            steps = grade_steps(submission, template, scratch, config, server, trial)
            limits_not_set = sorted({line for step in steps
                                     for line in step.pop("limits_not_set", ())})
            record = {
                "submission": submission.name,
                "fingerprint": fingerprint,
                "files": {name: "submission" if name in submission.files else "handout"
                          for name in config.kind.modules},
                "practice": config.practice,
                "problems": submission.problems,
                "isolation": isolation.mode,
                "draw": importlib.import_module(config.kind.judge).draw_record(trial.draw),
                "steps": steps,
                "total": sum(step["points"] for step in steps),
                "max_total": sum(config.points.values()),
                "seconds": round(time.monotonic() - start, 2),
                "limits_not_set": limits_not_set,
            }
            folder = results / submission.name
            if folder.exists():
                shutil.rmtree(folder)
            folder.mkdir(parents=True)
            if (scratch / "images").is_dir():
                shutil.copytree(scratch / "images", folder / "images")
    finally:
        servers.put(server)
    course_kit.feedback.write_submission_reports(record, folder, config.gradescope)
    return record


def recorded(results, submission, kit):
    """The record of an earlier grading of submission, when it is still valid; else None."""
    path = results / submission.name / course_kit.feedback.RECORD
    try:
        record = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    fingerprint = hashlib.sha256((submission.digest() + kit).encode()).hexdigest()
    return record if record.get("fingerprint") == fingerprint else None


def grade_folder(submissions_folder, results, config, jobs=None, force=False, progress=True,
                 isolation=None, draws=None):
    """Grades every submission of submissions_folder into results (see the module's
    docstring and grade_submissions); returns the records, sorted by submission."""
    return grade_submissions(find_submissions(submissions_folder), results, config, jobs,
                             force, progress, isolation, draws)


def grade_submissions(submissions, results, config, jobs=None, force=False, progress=True,
                      isolation=None, draws=None):
    """Grades the Submissions into results (see the module's docstring), their steps
    isolated as course_kit.sandbox.choose(isolation) says, which it prints, on inputs
    drawn now with draws (a random.Random; default: the system's own source, which no
    submission can foresee); returns their records, in the order of submissions."""
    results = Path(results)
    results.mkdir(parents=True, exist_ok=True)
    isolation = course_kit.sandbox.choose(isolation)
    print(f"Isolation of each step: {isolation.describe()}", flush=True)
    if isolation.mode == "unprivileged user":
        results.chmod(0o700)  # the steps' users may read what all may read
        # checked, not assumed: the finished framework, the expected data, the results
        # and the submissions must be out of a step's reach
        repo = course_kit.handout.REPO
        course_kit.sandbox.check_unreadable(
            [repo / name for name in config.kind.modules]
            + [course_kit.handout.CHECKS / "expected" / name for name in config.kind.expected]
            + [results]
            + sorted({submission.path.parent for submission in submissions}))
    kit = kit_fingerprint(config) + isolation.mode
    records = {}
    if not force:
        for submission in submissions:
            record = recorded(results, submission, kit)
            if record is not None:
                records[submission.name] = record
    todo = [submission for submission in submissions if submission.name not in records]
    jobs = min(jobs or os.cpu_count() or 1, len(todo)) or 1
    servers = queue.Queue()
    # every folder of the grading lies in this one, which goes when the grading ends
    with tempfile.TemporaryDirectory(prefix="pyrt-grade-") as grading:
        template = course_kit.handout.write_handout(Path(grading) / "handout",
                                                    config.practice)
        try:
            cores = course_kit.isolation.cores()
            for index in range(jobs if todo else 0):
                servers.put(course_kit.isolation.StepServer(
                    cores[index % len(cores)], course_kit.sandbox.confinement(isolation)))
            # imported and made while the servers start: the judge (numpy, the framework),
            # the inputs, and what the framework makes of them
            judging = importlib.import_module(config.kind.judge)
            trial = judging.drawn_trial(draws or random.SystemRandom(),
                                        Path(grading) / "expected") if todo else None
            # The pool ends before the servers close: a submission still being graded
            # gives its server back first, and one not started yet never waits for one
            with ThreadPoolExecutor(max_workers=jobs) as pool:
                running = [pool.submit(grade_submission, submission, template, results,
                                       config, kit, servers, isolation, trial)
                           for submission in todo]
                try:
                    for done in tqdm(as_completed(running), total=len(running),
                                     unit="submission", desc="grading",
                                     disable=not progress or not running):
                        record = done.result()
                        records[record["submission"]] = record
                except BaseException:
                    for future in running:
                        future.cancel()
                    raise
        finally:
            while not servers.empty():
                server = servers.get()
                server.close()
                course_kit.sandbox.close_confinement(server.confinement)
    ordered = [records[submission.name] for submission in submissions]
    course_kit.feedback.write_grades(ordered, results / "grades.csv", REASON_LENGTH)
    limits_not_set = sorted({line for record in ordered
                             for line in record.get("limits_not_set", ())})
    if limits_not_set:
        print("course_kit grade: this system refused some limits of a step's process, "
              "so the steps ran without them (no grade suffers for it): "
              + "; ".join(limits_not_set), file=sys.stderr)
    return ordered


def main(args):
    unsupported = course_kit.isolation.unsupported()
    if unsupported:
        sys.exit(f"course_kit grade: {unsupported}")
    try:
        config = load_config(args.config or CONFIG, getattr(args, "practice", 1))
        if args.jobs is not None and args.jobs < 1:
            raise ValueError(f"--jobs must be 1 or more, got {args.jobs}")
        isolation = course_kit.sandbox.choose(args.isolation)
        said = "; ".join(line for line in (course_kit.sandbox.cannot_sandbox(isolation),
                                            course_kit.sandbox.limit_of(isolation)) if line)
        if said:  # one line, before anything is graded
            print(f"course_kit grade: {said}", file=sys.stderr, flush=True)
        records = grade_folder(args.submissions, args.out, config, args.jobs, args.force,
                               isolation=args.isolation)
    except (ValueError, FileNotFoundError) as error:
        sys.exit(f"course_kit grade: {error}")
    print(f"The grades of {len(records)} submissions: {Path(args.out) / 'grades.csv'}")
    return 0
