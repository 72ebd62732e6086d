"""GaussianProcess.py: how fast a GP is made, and how fast the workbench of Practices 3 and 4
runs.

A GP of 40 samples made (Q, its inverse, z, the weights), as Assignment 3.1 asks: by PyRT
with the exact z (quadrature) and with the course's draws (z_estimate="course", the same
100,000 draws of random() as the course's 50,000-direction loop), against the course-style
GaussianProcess.py of tests/data/course_practice3/ on the course's base code
(tests/data/course_base/2023-24/), whose compute_z is the course's loop in pure Python. The
baseline runs in a process of its own (its modules have PyRT's names), timed inside it; the
three take turns, and the speed-ups are medians of the ratios within each turn. A pool of
40 GPs (Assignment 3.3.2) is timed beside them, and the course-style z is compared with
PyRT's course draws from the same seed.

The workbench: the default run of `AppWorkbench.py --practice 3` and `--practice 4` (seeded,
100 BMC estimates per N), the time it prints for its estimates and the whole command's.

    python -m benchmarks.gaussian_process              # about a minute on two cores
    python -m benchmarks.gaussian_process --turns 3 --only gp
Results go to out/gaussian_process.md.
"""
import argparse
import json
import random
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from benchmarks.timing import (OUT_DIR, markdown_table, paired_ratio, progress, run_command,
                               write_report)
from GaussianProcess import GP, SobolevCov
from PyRT_Common import Constant, UniformPDF, sample_set_hemisphere

REPO = Path(__file__).resolve().parent.parent
COURSE_BASE = REPO / "tests" / "data" / "course_base" / "2023-24"
COURSE_GP = REPO / "tests" / "data" / "course_practice3" / "GaussianProcess.py"
SAMPLES, POOL, SEED = 40, 40, 2026
# The floors: the exact z at least 50 times faster than the course's loop, the
# course's draws at least 20 times
EXACT_TARGET, COURSE_TARGET = 50, 20

# The baseline, run in a folder holding the course's base code and GaussianProcess.py: one
# GP of SAMPLES uniform samples from the seed, timed, its z printed as JSON
COURSE_RUN = f"""
import json, time
from GaussianProcess import *
import random
random.seed({SEED})
positions, _ = sample_set_hemisphere({SAMPLES}, UniformPDF())
start = time.perf_counter()
gp = GP(SobolevCov(), Constant(1))
gp.add_sample_pos(positions)
print(json.dumps({{"seconds": time.perf_counter() - start, "z": list(gp.z)}}))
"""


def course_folder(folder: Path) -> Path:
    """folder, holding the course's base code, its course-style GaussianProcess.py and the
    baseline's script."""
    for module in COURSE_BASE.glob("*.py"):
        shutil.copy(module, folder)
    shutil.copy(COURSE_GP, folder)
    (folder / "course_run.py").write_text(COURSE_RUN)
    return folder


def course_gp(folder: Path) -> dict:
    """One run of the baseline: its time in seconds and its z."""
    result = subprocess.run([sys.executable, "course_run.py"], cwd=folder, text=True,
                            capture_output=True, check=True)
    return json.loads(result.stdout)


def pyrt_gp(z_estimate: str) -> float:
    """The time in seconds of making PyRT's GP of the baseline's samples."""
    random.seed(SEED)
    positions, _ = sample_set_hemisphere(SAMPLES, UniformPDF())
    start = time.perf_counter()
    gp = GP(SobolevCov(), Constant(1), z_estimate=z_estimate)
    gp.add_sample_pos(positions)
    return time.perf_counter() - start


def pyrt_pool() -> float:
    """The time in seconds of making a pool of POOL GPs of SAMPLES samples each."""
    random.seed(SEED)
    sets = [sample_set_hemisphere(SAMPLES, UniformPDF())[0] for _ in range(POOL)]
    start = time.perf_counter()
    for positions in sets:
        GP(SobolevCov(), Constant(1)).add_sample_pos(positions)
    return time.perf_counter() - start


def measure_gp(turns: int) -> str:
    """The report's section on making a GP."""
    times = {"course": [], "exact": [], "draws": [], "pool": []}
    with tempfile.TemporaryDirectory() as name:
        folder = course_folder(Path(name))
        for turn in range(turns):
            progress(f"GP of {SAMPLES} samples, turn {turn + 1} of {turns}")
            baseline = course_gp(folder)
            times["course"].append(baseline["seconds"])
            times["exact"].append(pyrt_gp("exact"))
            times["draws"].append(pyrt_gp("course"))
            times["pool"].append(pyrt_pool())
    random.seed(SEED)
    positions, _ = sample_set_hemisphere(SAMPLES, UniformPDF())
    drawn = GP(SobolevCov(), Constant(1), z_estimate="course")
    drawn.add_sample_pos(positions)
    difference = np.max(np.abs(drawn.z / np.array(baseline["z"]) - 1))
    exact = paired_ratio(times["course"], times["exact"])
    draws = paired_ratio(times["course"], times["draws"])
    rows = [["course-style loop (baseline)", f"{1e3 * statistics.median(times['course']):.0f}",
             "1", "-"],
            ["PyRT, exact z", f"{1e3 * statistics.median(times['exact']):.2f}",
             f"{exact:.0f}", f"{EXACT_TARGET}"],
            ["PyRT, the course's draws", f"{1e3 * statistics.median(times['draws']):.1f}",
             f"{draws:.0f}", f"{COURSE_TARGET}"]]
    verdict = "meet" if exact >= EXACT_TARGET and draws >= COURSE_TARGET else "MISS"
    return (f"## A GP of {SAMPLES} samples (Q, its inverse, z, the weights)\n\n"
            f"Medians of {turns} turns; speed-up: the median of the ratios within a turn.\n\n"
            + markdown_table(["made by", "ms", "speed-up", "floor"], rows, 1)
            + f"\n\nThe speed-ups {verdict} the floors. A pool of {POOL} GPs of {SAMPLES} "
              f"samples (exact z): {statistics.median(times['pool']):.3f} s. The course's "
              f"z from the same seed against PyRT's course draws: largest relative "
              f"difference {difference:.1e}.\n")


def workbench_run(practice: int, folder: Path) -> tuple:
    """One default run of the workbench for a practice: the time it prints for its
    estimates and the whole command's, in seconds."""
    start = time.perf_counter()
    result = subprocess.run([sys.executable, str(REPO / "AppWorkbench.py"), "--practice",
                             str(practice), "--no-window", "--out", str(folder)],
                            text=True, capture_output=True, check=True)
    total = time.perf_counter() - start
    estimates = float(re.search(r"per number of samples in ([\d.]+) s", result.stdout)[1])
    return estimates, total


def measure_workbench(turns: int) -> str:
    """The report's section on the workbench's default runs."""
    rows = []
    with tempfile.TemporaryDirectory() as name:
        for practice in (3, 4):
            progress(f"AppWorkbench.py --practice {practice}, {turns} runs")
            runs = [workbench_run(practice, Path(name)) for _ in range(turns)]
            rows.append([f"--practice {practice}",
                         f"{statistics.median(run[0] for run in runs):.1f}",
                         f"{statistics.median(run[1] for run in runs):.1f}"])
    return ("## The workbench's default runs (1000 MC and 100 BMC estimates per N, "
            f"N = 20..100)\n\nMedians of {turns} runs.\n\n"
            + markdown_table(["run", "estimates (s)", "whole command (s)"], rows, 1) + "\n")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--turns", type=int, default=5,
                        help="turns of each measurement (default 5)")
    parser.add_argument("--only", choices=("gp", "workbench"),
                        help="measure one of the two (default: both)")
    args = parser.parse_args(argv)
    sections = []
    if args.only in (None, "gp"):
        sections.append(measure_gp(args.turns))
    if args.only in (None, "workbench"):
        sections.append(measure_workbench(min(args.turns, 3)))
    write_report(OUT_DIR / "gaussian_process.md", "GaussianProcess.py: speed",
                 "\n".join(sections))
    return 0


if __name__ == "__main__":
    run_command(main)
