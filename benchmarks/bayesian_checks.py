"""The random checks of Practices 3 and 4 (course_kit/checks/practice3_checks.py): how often
they fail correct work, and whether they catch every listed mistake.

- compute_z, when a student's z is not the course's seeded estimate: a correct 50,000-sample
  estimate on directions of another seed (practice3_scenes.course_z), judged at a chance of
  failing of 1e-3 for the whole check and at the check's own 1e-6; and each listed mistake
  (z without p, the density multiplied, the density left out) on the same directions, at
  1e-6.
- 3.3.2's pool and rotation: a correct integrator's GPs and angles drawn at random for the
  floor's hits; one rotation for every hit; a single GP of the pool.
Each run draws its inputs as the grader does (practice3_scenes.draw_inputs, from the run's
own seed).

    python -m benchmarks.bayesian_checks                  # 1000 runs each, two cores
    python -m benchmarks.bayesian_checks --runs 50        # quicker
Results go to out/bayesian_checks.md.
"""
import argparse
import math
import random
import sys
import time
from multiprocessing import Pool
from unittest import mock

import numpy as np

from benchmarks.timing import OUT_DIR, markdown_table, write_report
from course_kit.handout import CHECKS

sys.path.insert(0, str(CHECKS))
import monte_carlo_check  # noqa: E402  (found through the line above)
import practice3_checks as checks  # noqa: E402
import practice3_render as render  # noqa: E402
import practice3_scenes as scenes  # noqa: E402

LOOSE = 1e-3
DENSITY = 1 / (2 * math.pi)
Z_CASES = {
    "correct (other directions)": lambda z_one, z_cos, z_cos_without_p: (z_one, z_cos),
    "z without p": lambda z_one, z_cos, z_cos_without_p: (z_one, z_cos_without_p),
    "z times the density": lambda z_one, z_cos, z_cos_without_p:
        (z_one * DENSITY ** 2, z_cos * DENSITY ** 2),
    "z without the density": lambda z_one, z_cos, z_cos_without_p:
        (z_one * DENSITY, z_cos * DENSITY),
}
POOL_CASES = ("correct", "one rotation for every hit", "a single GP of the pool")


def z_passes(draw, z_one, z_cos, delta):
    rendered = render.Rendered("z")
    rendered.arrays.update(z_one=z_one, z_cos=z_cos)
    with mock.patch.object(monte_carlo_check, "FALSE_FAILURE", delta):
        return checks.judge_rendered(rendered, draw, None).passed


def pool_passes(draw, case, draws):
    count = int(scenes.floor_pixels(draw).sum())
    chosen = [0 if case == POOL_CASES[2] else draws.randrange(scenes.POOL)
              for _ in range(count)]
    angle = draws.random() * 2 * math.pi
    angles = [angle if case == POOL_CASES[1] else draws.random() * 2 * math.pi
              for _ in range(count)]
    directions, picked = scenes.turned_sets(draw, chosen, angles)
    rendered = render.Rendered("bmc_pool")
    rendered.arrays.update(directions=directions, chosen=picked,
                           image=np.zeros((draw.size, draw.size, 3)))
    return checks.judge_rendered(rendered, draw, None).passed


def one_run(seed):
    """{case: passed} of one run (its own draw)."""
    draws = random.Random(seed)
    draw = scenes.draw_inputs(draws)
    other = draws.randrange(2 ** 31)
    z_one = scenes.course_z(other, draw.positions, 0)
    z_cos = scenes.course_z(other + 1, draw.positions, 1)
    z_cos_without_p = scenes.course_z(other + 1, draw.positions, 0)
    result = {}
    for name, make in Z_CASES.items():
        one, cos = make(z_one, z_cos, z_cos_without_p)
        result[f"z: {name}"] = z_passes(draw, one, cos, monte_carlo_check.FALSE_FAILURE)
        if name.startswith("correct"):
            result[f"z: {name} at 1e-3"] = z_passes(draw, one, cos, LOOSE)
    for case in POOL_CASES:
        result[f"3.3.2: {case}"] = pool_passes(draw, case, draws)
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=1000)
    args = parser.parse_args(argv)
    start = time.perf_counter()
    with Pool(2) as pool:
        runs = pool.map(one_run, range(args.runs))
    rows = [[case, f"{sum(not run[case] for run in runs)} of {args.runs}"]
            for case in runs[0]]
    body = (markdown_table(["case", "failed"], rows, 1)
            + f"\n\n{args.runs} runs in {time.perf_counter() - start:.0f} s. A correct case "
            "should fail at most its bound's share (1e-6 per check, 1e-3 where said); a "
            "mistake should fail in every run.")
    write_report(OUT_DIR / "bayesian_checks.md", "Practices 3 and 4's random checks", body)
    return 0


if __name__ == "__main__":
    sys.exit(main())
