"""What the benchmarks share: timing renders fairly on a noisy machine, and reporting.

Renders that are compared take turns (timed_turns), so that a slow spell of the machine
slows them alike; ratios are medians of the ratios within each turn (paired_ratio).
"""
import datetime
import os
import platform
import statistics
import sys
import time
from functools import partial
from pathlib import Path
from typing import Callable

from AppRenderer import SCENES, make_integrator
from PyRT_Integrators import Integrator
from pyrt.workers import usable_cores

OUT_DIR = Path(__file__).resolve().parent.parent / "out"
SCENE_NAMES = {"cornell": "Cornell box", "sphere": "sphere scene"}


def time_renders(make: Callable[[], Integrator], worker_counts: list, repeats: int,
                 samples_per_pixel: int = 1) -> list:
    """For each worker count, the median time in seconds of `repeats` calls of render()
    on an integrator from make(), the counts taking turns (time_turns). make() is called
    for each render: objects once pickled for worker processes keep their attributes in
    dictionaries from then on, which slows a later one-process render of them."""
    def renders(workers):
        return lambda: partial(make().render, workers=workers,
                               samples_per_pixel=samples_per_pixel, progress=False)

    return time_turns([renders(workers) for workers in worker_counts], repeats)


def time_turns(tasks: list, repeats: int) -> list:
    """For each task, the median time in seconds of `repeats` runs (see timed_turns)."""
    return [statistics.median(times) for times in timed_turns(tasks, repeats)]


def timed_turns(tasks: list, repeats: int) -> list:
    """For each task, the times in seconds of `repeats` runs. A task is a function that
    prepares a run (not timed) and returns it; the tasks take turns, so that a slow spell
    of the machine slows them alike instead of one of them."""
    times = [[] for _ in tasks]
    for _ in range(repeats):
        for task, counted in zip(tasks, times):
            run = task()
            start = time.perf_counter()
            run()
            counted.append(time.perf_counter() - start)
    return times


def paired_ratio(times_a: list, times_b: list) -> float:
    """The median of the ratios a/b of runs made in the same turn: a slow spell of the
    machine that lasts a turn changes both times of its ratio alike, where it would move
    one of two medians."""
    return statistics.median(a / b for a, b in zip(times_a, times_b))


def prepared(name: str, figure: str, scene: str, max_depth, size: int,
             folder: Path) -> Integrator:
    """The integrator `name` of AppRenderer with a size x size image of `scene` attached,
    saving its images in `folder`."""
    integrator = make_integrator(name, str(folder / "benchmark"), max_depth, "_" + figure)
    integrator.add_scene(SCENES[scene](size, size))
    return integrator


def label(integrator: Integrator) -> str:
    """PhongIntegrator -> 'Phong', DepthIntegrator -> 'Depth (max_depth 5)'."""
    name = type(integrator).__name__.removesuffix("Integrator")
    if hasattr(integrator, "max_depth"):
        name += f" (max_depth {integrator.max_depth:g})"
    return name


def figure_label(figure: str) -> str:
    """'figure4' -> 'Figure 4'."""
    return figure.replace("figure", "Figure ")


def machine_description() -> str:
    """One line naming the machine, the Python version and the date."""
    return (f"{platform.platform()}, {cpu_name()}, {usable_cores()} usable cores "
            f"(of {os.cpu_count()}), Python {platform.python_version()}, "
            f"{datetime.datetime.now():%Y-%m-%d %H:%M}")


def cpu_name() -> str:
    """The processor's model name, from /proc/cpuinfo where there is one."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def markdown_table(header: list, rows: list, numeric_from: int) -> str:
    """A Markdown table; the columns from index `numeric_from` on are right-aligned."""
    rule = ["---" if i < numeric_from else "---:" for i in range(len(header))]
    return "\n".join("| " + " | ".join(str(cell) for cell in row) + " |"
                     for row in [header, rule] + rows)


def write_report(path: Path, title: str, body: str) -> None:
    """Prints body and writes it to path under a title and the machine's description."""
    print(body)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(f"# {title}\n\nMachine: {machine_description()}\n\n{body}\n")
    print(f"\nWritten to {path}")


def progress(message: str) -> None:
    """Tells the user, on stderr, what is being measured."""
    print(message, file=sys.stderr, flush=True)


def run_command(main: Callable[[], int]) -> None:
    """Runs a benchmark's main() as a command: its result is the exit status, and Ctrl+C
    stops it with the status 130 instead of a traceback."""
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        sys.exit(130)
