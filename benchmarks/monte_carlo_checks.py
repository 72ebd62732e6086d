"""The statistical checks of Practice 2's integrator (course_kit/checks/practice2_checks.py,
Bernstein's bound of monte_carlo_check.py): how often they fail a correct integrator, and
whether they catch every listed mistake.

Each run draws the inputs as the grader does (practice2_scenes.draw_inputs, from the run's
own seed, at a size the grader draws), renders the white furnace and the emitter with an
integrator, and judges both images as the grader does, Assignment 2.3 failing when either
check fails.
- False failures: the framework's CMCIntegrator, judged at a chance of failing of 1e-3 per
  check (the bound then allows 2 x 1e-3 per run) and at the checks' own 1e-6.
- Power: each listed mistake (a variant of the framework's integrator with that one
  mistake) judged at 1e-6, in every run.

    python -m benchmarks.monte_carlo_checks                  # 1000 runs each, two cores
    python -m benchmarks.monte_carlo_checks --runs 50        # quicker
Results go to out/monte_carlo_checks.md.
"""
import argparse
import random
import sys
import tempfile
import time
from multiprocessing import Pool
from pathlib import Path

from benchmarks.timing import OUT_DIR, markdown_table, write_report
from course_kit.handout import CHECKS
from PyRT_Common import BLACK, Dot, Ray, RGBColor, UniformPDF, Vector3D
from PyRT_Common import center_around_normal, sample_set_hemisphere
from PyRT_Integrators import CMCIntegrator

sys.path.insert(0, str(CHECKS))
import practice2_checks as checks  # noqa: E402  (found through the line above)
import practice2_render as render  # noqa: E402
import practice2_scenes as scenes  # noqa: E402
from course_kit.judging_practice2 import DRAWN_SIZES  # noqa: E402

MISTAKES = ("double cosine", "no 1/p", "no 1/N", "divided by the rays that found light",
            "a missed camera ray sees black", "the emission of a sample ray's hit forgotten")
LOOSE = 1e-3  # the chance of failing per check at which false failures are counted


class MistakenCMC(CMCIntegrator):
    """The classic Monte Carlo integrator with one of MISTAKES made, as students make it."""

    def __init__(self, n, filename_, mistake):
        super().__init__(n, filename_)
        self.mistake = mistake

    def compute_color(self, ray):
        scene, mistake = self.scene, self.mistake
        hit = scene.closest_hit(ray)
        if not hit.has_hit:
            if scene.env_map is None or mistake == "a missed camera ray sees black":
                return BLACK
            return scene.env_map.getValue(ray.d)
        brdf = scene.object_list[hit.primitive_index].get_BRDF()
        sample_set, sample_prob = sample_set_hemisphere(self.n_samples, UniformPDF())
        color, found = RGBColor(0.0, 0.0, 0.0), 0
        for omega, prob in zip(sample_set, sample_prob):
            wi = center_around_normal(omega, hit.normal)
            sample_hit = scene.closest_hit(Ray(hit.hit_point, wi))
            if sample_hit.has_hit:
                if mistake == "the emission of a sample ray's hit forgotten":
                    continue
                l_i = scene.object_list[sample_hit.primitive_index].emission
            elif scene.env_map is not None:
                l_i = scene.env_map.getValue(wi)
            else:
                continue
            found += 1
            term = l_i.multiply(brdf.get_value(wi, Vector3D(0.0, 0.0, 0.0), hit.normal))
            if mistake == "double cosine":
                term = term * Dot(hit.normal, wi)
            color = color + (term if mistake == "no 1/p" else term / prob)
        if mistake == "no 1/N":
            return color
        if mistake == "divided by the rays that found light":
            return color / max(found, 1)
        return color / self.n_samples


def one_run(job):
    """(the mistake or None, the run's seed, {delta: whether 2.3 failed}) of one run."""
    mistake, seed = job
    draws = random.Random(seed)
    draw = scenes.draw_inputs(draws, draws.choice(DRAWN_SIZES))
    random.seed(draw.seed)
    failed = dict.fromkeys((LOOSE, checks.monte_carlo_check.FALSE_FAILURE), False)
    with tempfile.TemporaryDirectory() as folder:
        for name in ("furnace", "emitter"):
            scene = render.scene_of(name, draw, Path(folder))
            integrator = (CMCIntegrator(draw.n_samples, "unused") if mistake is None
                          else MistakenCMC(draw.n_samples, "unused", mistake))
            image, _ = render.traced_image(integrator, scene)
            for delta in failed:
                _, exact_wrong, judged = checks.judge_image(name, image, draw, delta)
                failed[delta] |= bool(exact_wrong.any()) or not all(j.passed for j in judged)
    return mistake, seed, failed


def main(argv=None):
    parser = argparse.ArgumentParser(description="The false failures and the power of "
                                     "Practice 2's statistical checks.")
    parser.add_argument("--runs", type=int, default=1000, help="runs per integrator")
    parser.add_argument("--processes", type=int, default=2)
    args = parser.parse_args(argv)
    jobs = [(mistake, seed) for mistake in (None,) + MISTAKES for seed in range(args.runs)]
    start = time.perf_counter()
    failures = {}
    with Pool(args.processes) as pool:
        for mistake, _, failed in pool.imap_unordered(one_run, jobs, chunksize=8):
            counts = failures.setdefault(mistake, dict.fromkeys(failed, 0))
            for delta, fails in failed.items():
                counts[delta] += fails
    seconds = time.perf_counter() - start
    rows = [["the framework's CMCIntegrator (correct)",
             f"{failures[None][LOOSE]} of {args.runs}",
             f"{failures[None][checks.monte_carlo_check.FALSE_FAILURE]} of {args.runs}"]]
    rows += [[mistake, "", f"{failures[mistake][checks.monte_carlo_check.FALSE_FAILURE]} of "
              f"{args.runs}"] for mistake in MISTAKES]
    table = markdown_table(["integrator", "2.3 failed at 1e-3 per check",
                            "2.3 failed at 1e-6 per check (the grader's)"], rows, 1)
    write_report(OUT_DIR / "monte_carlo_checks.md", "Practice 2's statistical checks",
                 f"{args.runs} runs per integrator, each on inputs drawn as the grader "
                 f"draws them, in {seconds:.0f} s.\n\n{table}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
