"""Hunts for tests that fail by chance: runs the test suite again and again, each run in a
new random order (pytest-random-order) while busy processes keep every core loaded, and
reports each test that failed in any run together with the seeds that order it so.

From the repository's folder, after `pip install -r requirements-dev.txt`:

    python tools/hunt_flaky.py                        # 10 runs of the whole suite
    python tools/hunt_flaky.py --runs 20 tests/test_rendering.py
    python tools/hunt_flaky.py --each-file --runs 3   # every test file alone
    python tools/hunt_flaky.py --load 0               # no busy processes

Arguments it does not know go to pytest (files, -k EXPRESSION, ...). A run's seed sets
both the order of the tests and the examples Hypothesis draws, and every run starts from
an empty Hypothesis database, as CI does, so a failing run can be ordered again with the
command printed at the end. It exits with 0 when every run was green, 1 otherwise. What
it prints also goes to out/hunt_flaky.txt (--report), where git does not look.
docs/maintaining.md says when to run it and what it found last.

The file is also the pytest plugin (`-p hunt_flaky`) through which each run writes down
its failed tests; it does nothing in a pytest run that this script did not start.
"""
import argparse
import json
import multiprocessing
import os
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TOOLS = Path(__file__).resolve().parent
REPO = TOOLS.parent
TESTS = REPO / "tests"
REPORT = REPO / "out" / "hunt_flaky.txt"  # out/ is the user's, ignored by git
REPORT_VARIABLE = "HUNT_FLAKY_REPORT"  # where the plugin writes a run's failures
PROFILE_VARIABLE = "PYRT_HYPOTHESIS_PROFILE"
# Only there so that a run that hangs cannot hold the hunt for ever.
RUN_TIMEOUT = 1800  # seconds


# ------------------------------------------------------------------------------------------
# The plugin, inside each pytest run
# ------------------------------------------------------------------------------------------
def pytest_runtest_logreport(report):
    """Writes each failed phase (setup, call, teardown) of a test as one JSON line, at once,
    so that the failures before a crash or a hang are kept too."""
    path = os.environ.get(REPORT_VARIABLE)
    if path and report.failed:
        with open(path, "a", encoding="utf-8") as file:
            file.write(json.dumps({"test": report.nodeid, "when": report.when}) + "\n")


# ------------------------------------------------------------------------------------------
# The hunt
# ------------------------------------------------------------------------------------------
def keep_busy():
    """A load generator: takes a whole core until it is terminated."""
    while True:
        pass


def usable_cores():
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def run_arguments(seed, pytest_args):
    """The arguments of pytest for one run: its order and Hypothesis's examples from seed,
    no cache between runs."""
    return ["-q", "-p", "no:cacheprovider", "-p", "no:randomly",
            "--random-order-bucket=global", f"--random-order-seed={seed}",
            f"--hypothesis-seed={seed}", *pytest_args]


def run_pytest(seed, pytest_args, folder):
    """Runs the tests once: (the tests that failed as [(test id, phase)], pytest's last
    line, the seconds it took). folder is the run's own, new, folder."""
    report = folder / "failures.jsonl"
    env = dict(os.environ)
    env[REPORT_VARIABLE] = str(report)
    env["PYTHONPATH"] = os.pathsep.join(
        [str(TOOLS)] + ([env["PYTHONPATH"]] if env.get("PYTHONPATH") else []))
    # an empty example database: a failure Hypothesis stored in an earlier run would
    # otherwise be replayed first, whatever this run's seed
    env["HYPOTHESIS_STORAGE_DIRECTORY"] = str(folder / "hypothesis")
    env[PROFILE_VARIABLE] = "hunt"  # new examples from each run's seed (tests/conftest.py)
    # temporary folders of its own, apart from other pytest runs on the machine
    command = [sys.executable, "-m", "pytest", "-p", "hunt_flaky",
               f"--basetemp={folder / 'basetemp'}", *run_arguments(seed, pytest_args)]
    start = time.monotonic()
    try:
        result = subprocess.run(command, cwd=REPO, env=env, capture_output=True, text=True,
                                timeout=RUN_TIMEOUT)
        code, output = result.returncode, result.stdout + result.stderr
    except subprocess.TimeoutExpired as timeout:
        code, output = "timeout", timeout.stdout or ""
        if isinstance(output, bytes):  # what the run printed until then
            output = output.decode(errors="replace")
    seconds = time.monotonic() - start
    failures = []
    if report.exists():
        for line in report.read_text(encoding="utf-8").splitlines():
            entry = json.loads(line)
            failures.append((entry["test"], entry["when"]))
    lines = [line for line in output.splitlines() if line.strip()]
    last = lines[-1].strip("= ") if lines else "(no output)"
    # 5: no test was selected; other codes: pytest itself failed, or the run timed out
    if code not in (0, 1, 5) and not failures:
        failures.append((" ".join(["pytest", *pytest_args, f"(exit code {code})"]), "run"))
        print("\n".join(lines[-20:]))
    return failures, last, seconds


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        allow_abbrev=False,  # pytest's long options are not abbreviations of these
        description="Run the tests repeatedly in random order under load and report every "
                    "test that ever failed. Unknown arguments go to pytest.")
    parser.add_argument("--runs", type=int, default=10,
                        help="how many times to run the tests (default 10)")
    parser.add_argument("--load", type=int, default=usable_cores(),
                        help="busy processes kept running meanwhile (default: one per "
                             "usable core)")
    parser.add_argument("--seed", type=int, default=None,
                        help="the seed of the first run, the next runs take the numbers "
                             "after it (default: chosen at random and printed)")
    parser.add_argument("--report", type=Path, default=REPORT,
                        help="the file that gets what the hunt prints (default: "
                             "out/hunt_flaky.txt)")
    parser.add_argument("--each-file", action="store_true",
                        help="run every test file alone, in a pytest of its own, in each run")
    options, pytest_args = parser.parse_known_args(argv)
    if options.runs < 1 or options.load < 0:
        parser.error("--runs must be at least 1 and --load at least 0")
    return options, pytest_args


def main(argv=None):
    options, pytest_args = parse_arguments(sys.argv[1:] if argv is None else argv)
    options.report.parent.mkdir(parents=True, exist_ok=True)
    with open(options.report, "w", encoding="utf-8") as report:
        def say(text):
            print(text, flush=True)
            report.write(text + "\n")
            report.flush()

        return hunt(options, pytest_args, say)


def hunt(options, pytest_args, say):
    """The runs of main, with what they tell given to say (one line or more at a time)."""
    try:
        import random_order  # noqa: F401  (pytest-random-order, the plugin that shuffles)
    except ImportError:
        sys.exit("hunt_flaky needs pytest-random-order: pip install -r requirements-dev.txt")
    first = options.seed if options.seed is not None else random.randrange(10 ** 6)
    if options.each_file:
        groups = [[str(path.relative_to(REPO)), *pytest_args]
                  for path in sorted(TESTS.glob("test_*.py"))]
    else:
        groups = [pytest_args]
    # spawned: a fork of this process, multi-threaded when the tests run it, may deadlock
    # (Python 3.12 and later warn of it)
    spawn = multiprocessing.get_context("spawn")
    load = [spawn.Process(target=keep_busy, daemon=True) for _ in range(options.load)]
    for process in load:
        process.start()
    say(f"{options.runs} run(s) from seed {first}, {options.load} busy process(es) "
        f"on {usable_cores()} core(s)")
    failed = {}  # test id: [seeds]
    red = 0
    first_red = None  # (seed, pytest arguments) of the first red run
    try:
        with tempfile.TemporaryDirectory(prefix="hunt_flaky_") as folder:
            for run in range(options.runs):
                seed = first + run
                red_run = False
                for number, args in enumerate(groups):
                    run_folder = Path(folder) / f"run{run}_{number}"
                    run_folder.mkdir()
                    failures, last, seconds = run_pytest(seed, args, run_folder)
                    what = " ".join(args) or "the suite"
                    say(f"run {run + 1}/{options.runs}, seed {seed}, {what}: {last} "
                        f"({seconds:.1f} s of wall time)")
                    for test, when in failures:
                        say(f"    FAILED {test} ({when})")
                    for test in dict.fromkeys(test for test, _ in failures):
                        failed.setdefault(test, []).append(seed)
                    if failures and first_red is None:
                        first_red = (seed, args)
                    red_run = red_run or bool(failures)
                red += red_run
    finally:
        for process in load:
            process.terminate()
        for process in load:
            process.join()
    say(f"\n{options.runs} run(s) in random order with {options.load} busy process(es): "
        f"{options.runs - red} green, {red} red")
    for test, seeds in sorted(failed.items()):
        say(f"  {test}: failed in {len(seeds)} of {options.runs} run(s), seed(s) "
            f"{', '.join(map(str, seeds))}")
    if first_red:
        seed, args = first_red
        say("The tests of the first red run, in its order (scheduling and load are not "
            f"repeated):\n    {PROFILE_VARIABLE}=hunt python -m pytest "
            + " ".join(run_arguments(seed, args)))
    return 1 if red else 0


if __name__ == "__main__":
    sys.exit(main())
