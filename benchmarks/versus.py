"""Figure 1's render time against another checkout of PyRT (an earlier commit, say), in
one process and on every core: the two take turns, each render in a fresh process of its
own checkout, and the ratios are medians of the ratios within each turn.

    git worktree add /tmp/pyrt-before <commit>
    python -m benchmarks.versus /tmp/pyrt-before --repeats 5
Results go to out/versus.md.
"""
import argparse
import subprocess
import sys
from pathlib import Path

from benchmarks.timing import (OUT_DIR, markdown_table, paired_ratio, progress, run_command,
                               write_report)

REPO = Path(__file__).resolve().parent.parent
# Renders Figure 1 (Phong on the Cornell box) at size x size with `workers` processes in
# the checkout it runs in, and prints the seconds render() took.
RENDER = """
import sys, tempfile, time
from AppRenderer import SCENES
from PyRT_Integrators import PhongIntegrator
size, workers = int(sys.argv[1]), (None if sys.argv[2] == 'all' else int(sys.argv[2]))
with tempfile.TemporaryDirectory() as folder:
    integrator = PhongIntegrator(folder + '/figure1')
    integrator.add_scene(SCENES['cornell'](size, size))
    start = time.perf_counter()
    integrator.render(workers=workers, progress=False)
    print(time.perf_counter() - start, file=sys.stderr)
"""


def render_seconds(checkout: Path, size: int, workers: str) -> float:
    """The seconds of one render of Figure 1 in a fresh process of checkout."""
    result = subprocess.run([sys.executable, "-c", RENDER, str(size), workers], cwd=checkout,
                            capture_output=True, text=True, check=True)
    return float(result.stderr.strip().splitlines()[-1])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("before", type=Path, help="the other checkout")
    parser.add_argument("--size", type=int, default=500)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--workers", nargs="+", default=["1", "all"],
                        help="the worker counts to compare ('all': every core)")
    args = parser.parse_args()
    rows = []
    for workers in args.workers:
        times = {"before": [], "now": []}
        for turn in range(args.repeats):
            progress(f"workers={workers}, turn {turn + 1} of {args.repeats}")
            for name, checkout in (("before", args.before), ("now", REPO)):
                times[name].append(render_seconds(checkout, args.size, workers))
        before, now = sorted(times["before"]), sorted(times["now"])
        progress(f"workers={workers}: before {before}, now {now}")
        rows.append([workers, f"{before[len(before) // 2]:.2f}", f"{now[len(now) // 2]:.2f}",
                     f"{paired_ratio(times['now'], times['before']):.3f}"])
    table = markdown_table(["workers", "before (s)", "now (s)", "now / before"], rows, 1)
    write_report(OUT_DIR / "versus.md",
                 f"Figure 1 at {args.size} x {args.size}: this checkout against "
                 f"{args.before}", table)
    return 0


if __name__ == "__main__":
    run_command(main)
