"""The Bayesian Monte Carlo integrators: how fast they render, against the flat loop and a
student's integrator on the course's own framework, and Practice 3's Figure 2 on every core.

Speed: the sphere scene lit by the environment map (the course's, or PyRT's sky where the
course's map is not there) at 96 x 96 pixels with 40 samples per hit, rendered by
Integrator.render() in one process with BayesianMonteCarloIntegrator and BMCISIntegrator
(a pool of POOL_SIZE GPs) and by the flat loop (benchmarks/flat_loop.py, flat_bmc: the same
image, bit for bit, from one loop with no calls per ray), in alternating turns: the time
per sample of each and render()'s as a multiple of the flat loop's. Then the course-style
BMC integrator of tests/data/course_practice3 (one GP, a turn about y per hit) on the
course's 2023-24 base code with the course-style GaussianProcess.py, in a process of its
own, its pixels visited by the loop of Assignment 1.2, against render() in one process with
one GP: the GPs' making is left out on both sides.

Figure 2 of Practice 3: the sphere scene at 500 x 500, 40 samples per hit, classic Monte
Carlo beside BMC (a pool of POOL_SIZE GPs), each rendered on every core; the two images
side by side.

    python -m benchmarks.bayesian                    # about a minute on two cores
Results go to out/bayesian.md and out/bayesian_figure2.png.
"""
import argparse
import random
import statistics
import subprocess
import sys
import tempfile
import time
from functools import partial
from pathlib import Path

import matplotlib
import numpy as np

from AppRenderer import SCENES, positive_arg
from benchmarks.flat_loop import flat_bmc
from benchmarks.timing import (OUT_DIR, markdown_table, paired_ratio, progress, run_command,
                               timed_turns, write_report)
from pyrt.environment_maps import sky_map
from pyrt.gaussian_pools import make_gp_pool
from pyrt.images import cv2, display_image
from pyrt.workers import usable_cores
from PyRT_Common import CosineLobe, CosinePDF, Constant, Ray, UniformPDF, Vector3D, plt
from PyRT_Integrators import BayesianMonteCarloIntegrator, BMCISIntegrator, CMCIntegrator

REPO = Path(__file__).resolve().parent.parent
COURSE_BASE = REPO / "tests" / "data" / "course_base" / "2023-24"
COURSE_PRACTICE3 = REPO / "tests" / "data" / "course_practice3"
# Targets: render() in one process at most this multiple of the flat loop's time per
# sample, and at least this many times faster than the course-style integrator
FLAT_LOOP_TARGET, COURSE_TARGET = 1.25, 5.0
SPEED_SIZE, COURSE_SIZE, SAMPLES, POOL_SIZE = 96, 64, 40, 16
FIGURE_SIZE = 500
SEED = 2026
SCENE = "sphere-map"

# The course-style run: the course's base code, its GaussianProcess.py and the BMC
# integrator students write, in a folder of their own; prints the seconds of the pixels'
# loop alone (Assignment 1.2's, calling compute_color for every pixel)
COURSE_SCRIPT = """
import random as random_module, sys, time
from PyRT_Common import *
from PyRT_Core import *
from GaussianProcess import GP, SobolevCov
from bmc_integrator import BayesianMonteCarloIntegrator
size, samples = int(sys.argv[1]), int(sys.argv[2])
random_module.seed(1)
# the sphere scene of the course's AppRenderer.py (a script: importing it renders)
scene = Scene()
sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
sphere.set_BRDF(Lambertian(RGBColor(0.8, 0.8, 0.8)))
scene.add_object(sphere)
floor = Parallelogram(Vector3D(-4.0, -2.0, -1.0), Vector3D(8.0, 0.0, 0.0),
                      Vector3D(0.0, 0.0, -8.0))
floor.set_BRDF(Lambertian(RGBColor(0.2, 0.8, 0.2)))
scene.add_object(floor)
scene.set_environment_map('sky.hdr')
scene.set_camera(Camera(size, size, 60))
gp = GP(SobolevCov(), Constant(1))
gp.add_sample_pos(sample_set_hemisphere(samples, UniformPDF())[0])
integrator = BayesianMonteCarloIntegrator(samples, gp, 'out')
integrator.add_scene(scene)
camera = scene.camera
start = time.perf_counter()
for x in range(camera.width):
    for y in range(camera.height):
        ray = Ray(Vector3D(0.0, 0.0, 0.0), camera.get_direction(x, y))
        scene.set_pixel(integrator.compute_color(ray), x, y)
print(time.perf_counter() - start)
"""


def scene(size: int):
    """Practice 3's Figure 2 scene at size x size pixels."""
    return SCENES[SCENE](size, size)


def pools(size: int, samples: int) -> dict:
    """The GP pools of the two integrators, made after random.seed(SEED)."""
    random.seed(SEED)
    return {"bmc": make_gp_pool(size, samples, UniformPDF(), Constant(1)).gps,
            "bmc_is": make_gp_pool(size, samples, CosinePDF(1), CosineLobe(1)).gps}


INTEGRATORS = {"bmc": BayesianMonteCarloIntegrator, "bmc_is": BMCISIntegrator}


def rendered(kind: str, pool, size: int, folder: Path, **options):
    """The integrator `kind` of INTEGRATORS with `pool`, after it rendered the scene."""
    integrator = INTEGRATORS[kind](SAMPLES, pool, str(folder / kind))
    integrator.add_scene(scene(size))
    integrator.render(progress=False, **options)
    return integrator


def seeded(run):
    """run, preceded by random.seed(SEED): every measurement renders the same image."""
    def seeded_run():
        random.seed(SEED)
        return run()
    return seeded_run


def flat_seeded(kind: str, pool, size: int) -> np.ndarray:
    """flat_bmc with the stream seed render() would draw after random.seed(SEED)."""
    return flat_bmc(scene(size), pool, int(random.random() * 2 ** 53),
                    cosine_prior=kind == "bmc_is")


def sample_count(size: int) -> int:
    """The sample rays of a render: the pixels whose camera ray hits, times SAMPLES."""
    figure = scene(size)
    camera = figure.camera
    hits = sum(figure.closest_hit(Ray(Vector3D(0.0, 0.0, 0.0),
                                      camera.get_direction(x, y))).has_hit
               for x in range(size) for y in range(size))
    return hits * SAMPLES


def speed(repeats: int, folder: Path) -> str:
    """The table of render() against the flat loop (see the module's docstring)."""
    size = SPEED_SIZE
    progress(f"Bayesian Monte Carlo speed: {size} x {size}, {SAMPLES} samples per hit, "
             f"pools of {POOL_SIZE}")
    count, rows, ratios = sample_count(size), [], []
    for kind, pool in pools(POOL_SIZE, SAMPLES).items():
        random.seed(SEED)
        image = rendered(kind, pool, size, folder, workers=1).scene.rendered_image
        random.seed(SEED)
        assert np.array_equal(flat_seeded(kind, pool, size), image), (
            f"the flat loop's image differs from render()'s ({kind})")
        times = timed_turns([lambda: seeded(partial(rendered, kind, pool, size, folder,
                                                    workers=1)),
                             lambda: seeded(partial(flat_seeded, kind, pool, size))], repeats)
        one, flat = (statistics.median(counted) for counted in times)
        ratio = paired_ratio(times[0], times[1])
        ratios.append(ratio)
        name = INTEGRATORS[kind].__name__
        rows += [[f"{name}, render(), 1 process", f"{one:.2f}", f"{one / count * 1e6:.2f}",
                  f"{ratio:.2f}"],
                 [f"{name}, flat loop", f"{flat:.2f}", f"{flat / count * 1e6:.2f}", "1.00"]]
    verdict = "met" if max(ratios) <= FLAT_LOOP_TARGET else "MISSED"
    return (markdown_table(["How", "Time (s)", "µs per sample", "/ flat loop"], rows, 1)
            + f"\n\n{size}x{size} pixels, {SAMPLES} samples per hit, {count} sample rays; "
            f"medians of {repeats} alternating turns, the ratios medians of each turn's "
            f"ratios. Target: render() at most {FLAT_LOOP_TARGET} times the flat loop: "
            f"{max(ratios):.2f} at most, {verdict}.")


def course_style(repeats: int, folder: Path) -> str:
    """The course-style BMC integrator on the course's base code against render() (see the
    module's docstring)."""
    size = COURSE_SIZE
    progress(f"The course-style BMC integrator on the course's base code, {size} x {size}")
    course = Path(folder) / "course"
    course.mkdir()
    for source in list(COURSE_BASE.glob("*.py")) + [COURSE_PRACTICE3 / "GaussianProcess.py",
                                                      COURSE_PRACTICE3 / "bmc_integrator.py"]:
        (course / source.name).write_bytes(source.read_bytes())
    cv2.imwrite(str(course / "sky.hdr"), sky_map())
    random.seed(SEED)
    pool = make_gp_pool(1, SAMPLES, UniformPDF(), Constant(1)).gps
    ours, theirs = [], []
    for _ in range(repeats):
        result = subprocess.run([sys.executable, "-c", COURSE_SCRIPT, str(size), str(SAMPLES)],
                                cwd=course, capture_output=True, text=True, check=True)
        theirs.append(float(result.stdout.strip().splitlines()[-1]))
        random.seed(SEED)
        start = time.perf_counter()
        rendered("bmc", pool, size, folder, workers=1)
        ours.append(time.perf_counter() - start)
    ratio = statistics.median(t / o for t, o in zip(theirs, ours))
    verdict = "met" if ratio >= COURSE_TARGET else "MISSED"
    rows = [["the course-style integrator on the course's base code",
             f"{statistics.median(theirs):.2f}", "1.00"],
            ["BayesianMonteCarloIntegrator, render(), 1 process",
             f"{statistics.median(ours):.2f}", f"{ratio:.1f}"]]
    return (markdown_table(["How", "Time (s)", "Speed-up"], rows, 1)
            + f"\n\n{size}x{size} pixels, {SAMPLES} samples per hit, one GP (its making left "
            f"out on both sides); medians of {repeats} alternating turns. Target: at least "
            f"{COURSE_TARGET} times faster: {ratio:.1f}, {verdict}.")


def figure2(workers: int, folder: Path, out: Path) -> str:
    """Practice 3's Figure 2 on every core: times and the two images side by side."""
    size = FIGURE_SIZE
    progress(f"Figure 2 of Practice 3: {size} x {size}, {SAMPLES} samples, {workers} "
             "processes")
    random.seed(SEED)
    pool = make_gp_pool(POOL_SIZE, SAMPLES, UniformPDF(), Constant(1))
    images, rows = [], []
    for integrator in (CMCIntegrator(SAMPLES, str(folder / "figure2")),
                       BayesianMonteCarloIntegrator(SAMPLES, pool.gps, str(folder / "figure2"))):
        integrator.add_scene(scene(size))
        random.seed(SEED)
        start = time.perf_counter()
        integrator.render(progress=False, workers=workers)
        rows.append([type(integrator).__name__, f"{time.perf_counter() - start:.1f}"])
        images.append(integrator.scene.rendered_image)
    # both through one tonemapping, as the course's figure shows them side by side
    side = display_image(np.concatenate(images, axis=1), True)
    plt.imsave(out / "bayesian_figure2.png", side)
    return (markdown_table(["Integrator", "Time (s)"], rows, 1)
            + f"\n\n{size}x{size} pixels, {SAMPLES} samples per hit, {workers} processes; "
            f"BMC with a pool of {POOL_SIZE} GPs, whose making took {pool.seconds:.2f} s.")


def parse_args(argv):
    parser = argparse.ArgumentParser(
        description="Measure the Bayesian Monte Carlo integrators: render() against the flat "
                    "loop and against a student's integrator on the course's framework, and "
                    "Practice 3's Figure 2 on every core -> out/bayesian.md, "
                    "out/bayesian_figure2.png.")
    parser.add_argument("--only", choices=("speed", "course", "figure2"), default=None,
                        help="measure one of the three (default: all)")
    parser.add_argument("--repeats", type=positive_arg(int), default=3,
                        help="turns of each timing (default 3)")
    parser.add_argument("--workers", type=positive_arg(int), default=usable_cores(),
                        help=f"processes for Figure 2 (default {usable_cores()})")
    parser.add_argument("--out", type=Path, default=OUT_DIR,
                        help="folder for the table and the image (default: out/ of the "
                             "repository)")
    return parser.parse_args(argv)


def main(argv=None) -> int:
    args = parse_args(argv)
    matplotlib.use("Agg")
    args.out.mkdir(parents=True, exist_ok=True)
    parts = []
    with tempfile.TemporaryDirectory(prefix="pyrt-bayesian-") as folder:
        folder = Path(folder)
        if args.only in (None, "speed"):
            parts.append("## Against the flat loop\n\n" + speed(args.repeats, folder))
        if args.only in (None, "course"):
            parts.append("## Against a student's integrator on the course's framework\n\n"
                         + course_style(args.repeats, folder))
        if args.only in (None, "figure2"):
            parts.append("## Figure 2 of Practice 3\n\n" + figure2(args.workers, folder,
                                                                    args.out))
    write_report(args.out / "bayesian.md", "PyRT: Bayesian Monte Carlo", "\n\n".join(parts))
    return 0


if __name__ == "__main__":
    run_command(main)
