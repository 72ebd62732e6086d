"""The Monte Carlo integrators: how fast the classic one renders, and the trade of time for
error of all four (classic and Bayesian, each with and without importance sampling).

Speed: Practice 2's Figure 3 (the sphere scene lit by the course's environment map, or by
PyRT's sky where the map is not there; CMCIntegrator with 40 samples per hit) at 160 x 160
pixels, rendered by Integrator.render() in one process and on all cores, by the flat loop
(benchmarks/flat_loop.py: the same image, bit for bit, from one loop with no calls) and by
the same algorithm as a student writes it (one process, a loop over the pixels calling
CMCIntegrator's own compute_color, the scene's own closest_hit): the time per sample of
each, and render()'s as a multiple of the flat loop's.

The trade: the same scene at 128 x 128 with N = 4, 8, ..., 256 samples per hit against a
reference of 1024: the RMSE of each image, its time, their product and RMSE^2 x time (the
variance times the time, constant for an unbiased estimator whose error falls as
1/sqrt(N)); a log-log plot of RMSE against N beside the slope -1/2, and the per-pixel
error of N = 16 (Assignment 2.4). Adaptive sampling at the same number of camera rays is
measured beside uniform sampling. Then CMC, CMC IS, BMC and BMC IS (pools of 16 GPs) from
N = 8 to 256 against the same reference: RMSE against time, the GPs' making included, in
one plot; and at N = 40 the correlation of neighbouring pixels' errors, beside BMC with
one GP never turned (Assignment 3.3 before 3.3.2), whose pattern shows.

    python -m benchmarks.monte_carlo                 # both, about ten minutes on two cores
    python -m benchmarks.monte_carlo --only trade --reference-samples 256   # quicker
Results go to out/monte_carlo.md and out/monte_carlo_*.png (monte_carlo_methods.png: the
four methods; monte_carlo_patterns.png: the error images at N = 40).
"""
import argparse
import random
import statistics
import tempfile
import time
from functools import partial
from pathlib import Path

import matplotlib
import numpy as np

from AppRenderer import SCENES, positive_arg
from benchmarks.flat_loop import flat_cmc
from benchmarks.timing import (OUT_DIR, markdown_table, paired_ratio, progress, run_command,
                               timed_turns, write_report)
from pyrt.gaussian_pools import make_gp_pool
from PyRT_Common import Constant, CosineLobe, CosinePDF, Ray, UniformPDF, Vector3D
from PyRT_Integrators import (BayesianMonteCarloIntegrator, BMCISIntegrator, CMCIntegrator,
                              CMCISIntegrator)
from pyrt.workers import usable_cores

# Target: render() in one process at most this multiple of the flat loop's time per sample
FLAT_LOOP_TARGET = 1.25
SPEED_SIZE, SPEED_SAMPLES = 160, 40
TRADE_SIZE, TRADE_SAMPLES, REFERENCE_SAMPLES = 128, (4, 8, 16, 32, 64, 128, 256), 1024
ERROR_IMAGE_SAMPLES = 16
# The four methods of Practices 2 to 4 against time: their samples per hit, their pool of GPs
METHOD_SAMPLES, POOL_SIZE, PATTERN_SAMPLES = (8, 16, 32, 64, 128, 256), 16, 40
SEED = 2026
SCENE = "sphere-map"


def scene(size: int):
    """Practice 2's Figure 3 at size x size pixels."""
    return SCENES[SCENE](size, size)


def seeded(run):
    """run, preceded by random.seed(SEED): every measurement renders the same image."""
    def seeded_run():
        random.seed(SEED)
        return run()
    return seeded_run


def rendered(samples: int, size: int, folder: Path, **options) -> CMCIntegrator:
    """A CMCIntegrator of `samples` samples that has rendered the scene at size x size."""
    integrator = CMCIntegrator(samples, str(folder / "cmc"))
    integrator.add_scene(scene(size))
    integrator.render(progress=False, **options)
    return integrator


def student_loop(samples: int, size: int) -> np.ndarray:
    """The image as a student's own loop makes it: one process, every pixel's camera ray
    through CMCIntegrator's own compute_color and the scene's own queries."""
    integrator = CMCIntegrator(samples, "unused")
    integrator.add_scene(scene(size))
    camera = integrator.scene.camera
    image = np.zeros((size, size, 3))
    for x in range(camera.width):
        for y in range(camera.height):
            color = integrator.compute_color(Ray(Vector3D(0.0, 0.0, 0.0),
                                                 camera.get_direction(x, y)))
            image[y, x] = (color.r, color.g, color.b)
    return image


def hit_pixels(size: int) -> np.ndarray:
    """Which pixels' camera rays hit an object of the scene, as booleans."""
    figure = scene(size)
    camera = figure.camera
    return np.array([[figure.closest_hit(Ray(Vector3D(0.0, 0.0, 0.0),
                                             camera.get_direction(x, y))).has_hit
                      for x in range(size)] for y in range(size)])


def speed(repeats: int, workers: int, folder: Path) -> str:
    """The speed table of Figure 3 of Practice 2 (see the module's docstring)."""
    size, samples = SPEED_SIZE, SPEED_SAMPLES
    progress(f"Monte Carlo speed: {size} x {size}, {samples} samples per hit")
    random.seed(SEED)
    reference = rendered(samples, size, folder, workers=1).scene.rendered_image
    random.seed(SEED)
    assert np.array_equal(flat_cmc(scene(size), samples, int(random.random() * 2 ** 53)),
                          reference), "the flat loop's image differs from render()'s"
    tasks = [lambda: seeded(partial(rendered, samples, size, folder, workers=1)),
             lambda: seeded(partial(rendered, samples, size, folder, workers=workers)),
             lambda: seeded(partial(flat_cmc_seeded, samples, size))]
    times = timed_turns(tasks, repeats)
    progress("  the student's loop (once)")
    start = time.perf_counter()
    random.seed(SEED)
    student_loop(samples, size)
    student = time.perf_counter() - start
    count = int(hit_pixels(size).sum()) * samples
    one, many, flat = (statistics.median(counted) for counted in times)
    ratio = paired_ratio(times[0], times[2])
    rows = [["render(), 1 process", f"{one:.2f}", f"{one / count * 1e6:.2f}", f"{ratio:.2f}"],
            [f"render(), {workers} processes", f"{many:.2f}", f"{many / count * 1e6:.2f}",
             f"{paired_ratio(times[1], times[2]):.2f}"],
            ["flat loop", f"{flat:.2f}", f"{flat / count * 1e6:.2f}", "1.00"],
            ["a student's loop (own compute_color, own queries), 1 process", f"{student:.2f}",
             f"{student / count * 1e6:.2f}", f"{student / flat:.2f}"]]
    verdict = "met" if ratio <= FLAT_LOOP_TARGET else "MISSED"
    return (markdown_table(["How", "Time (s)", "µs per sample", "/ flat loop"], rows, 1)
            + f"\n\n{size}x{size} pixels, CMCIntegrator({samples}), {count} sample rays "
            f"(the pixels whose camera ray hits, times {samples}); medians of {repeats} "
            "turns (the student's loop once), the ratios medians of each turn's ratios. "
            f"Target: render() in one process at most {FLAT_LOOP_TARGET} times the flat "
            f"loop: {ratio:.2f}, {verdict}.")


def flat_cmc_seeded(samples: int, size: int) -> np.ndarray:
    """flat_cmc with the stream seed render() would draw after random.seed(SEED)."""
    return flat_cmc(scene(size), samples, int(random.random() * 2 ** 53))


def rmse(image: np.ndarray, reference: np.ndarray) -> float:
    """The root mean square of image - reference over pixels and channels."""
    return float(np.sqrt(np.mean((image - reference) ** 2)))


def trade(reference_samples: int, workers: int, folder: Path, out: Path) -> str:
    """The table and plots of the time-for-error trade (see the module's docstring)."""
    size = TRADE_SIZE
    progress(f"The trade: a reference of {reference_samples} samples at {size} x {size}")
    random.seed(SEED + 1)
    reference = rendered(reference_samples, size, folder, workers=workers).scene.rendered_image
    rows, errors, seconds, images = [], [], [], {}
    for samples in TRADE_SAMPLES:
        progress(f"  N = {samples}")
        random.seed(SEED)
        start = time.perf_counter()
        image = rendered(samples, size, folder, workers=workers).scene.rendered_image
        elapsed = time.perf_counter() - start
        error = rmse(image, reference)
        errors.append(error)
        seconds.append(elapsed)
        images[samples] = image
        rows.append([samples, f"{error:.4f}", f"{elapsed:.2f}", f"{error * elapsed:.4f}",
                     f"{error ** 2 * elapsed:.5f}"])
    slope = float(np.polyfit(np.log(TRADE_SAMPLES), np.log(errors), 1)[0])
    plot_trade(errors, reference_samples, out / "monte_carlo_rmse.png")
    plot_error_image(images[ERROR_IMAGE_SAMPLES], reference, out / "monte_carlo_error.png")
    table = markdown_table(["N (samples per hit)", "RMSE", "Time (s)", "RMSE x time",
                            "RMSE^2 x time"], rows, 0)
    return (table + f"\n\n{size}x{size} pixels, {workers} processes, against a reference of "
            f"{reference_samples} samples per hit; RMSE over every pixel and channel of the "
            f"linear image. Fitted slope of log RMSE against log N: {slope:.3f} (theory: "
            "-0.5).\n\n" + adaptive_against_uniform(reference, workers, folder) + "\n\n"
            + four_methods(reference, workers, folder, out))


class OneUnturnedGP(BayesianMonteCarloIntegrator):
    """Assignment 3.3 before 3.3.2: the first GP of the pool at every hit, never turned."""

    def pick_sample_set(self):
        return self.myGP[0], 0.0


def method_integrator(name: str, samples: int, folder: Path):
    """(integrator, seconds its GPs took to make) for one of the four methods."""
    if name == "CMC":
        return CMCIntegrator(samples, str(folder / "m")), 0.0
    if name == "CMC IS":
        return CMCISIntegrator(samples, str(folder / "m")), 0.0
    pdf, p_func, make = {"BMC": (UniformPDF(), Constant(1), BayesianMonteCarloIntegrator),
                         "BMC IS": (CosinePDF(1), CosineLobe(1), BMCISIntegrator),
                         "BMC, one GP unturned": (UniformPDF(), Constant(1), OneUnturnedGP)}[name]
    pool = make_gp_pool(POOL_SIZE, samples, pdf, p_func)
    return make(samples, pool.gps, str(folder / "m")), pool.seconds


def neighbour_correlation(error: np.ndarray, hit: np.ndarray) -> float:
    """The correlation of the errors (mean over channels) of horizontally and vertically
    neighbouring pixels, both of whose camera rays hit an object."""
    error = error.mean(axis=2)
    pairs = [(error[:, :-1][hit[:, :-1] & hit[:, 1:]], error[:, 1:][hit[:, :-1] & hit[:, 1:]]),
             (error[:-1][hit[:-1] & hit[1:]], error[1:][hit[:-1] & hit[1:]])]
    a = np.concatenate([p[0] for p in pairs])
    b = np.concatenate([p[1] for p in pairs])
    return float(np.corrcoef(a, b)[0, 1])


def four_methods(reference: np.ndarray, workers: int, folder: Path, out: Path) -> str:
    """CMC, CMC IS, BMC and BMC IS from 8 to 256 samples per hit: the RMSE of each image
    against the reference and its time, the GPs' making included (and given apart), plotted
    as RMSE against time; then at 40 samples the correlation of neighbouring pixels'
    errors, with the pattern BMC leaves with one GP never turned, and the error images."""
    size, rows, curves = TRADE_SIZE, [], {}
    for name in ("CMC", "CMC IS", "BMC", "BMC IS"):
        for samples in METHOD_SAMPLES:
            progress(f"  {name}, N = {samples}")
            random.seed(SEED)
            integrator, gp_seconds = method_integrator(name, samples, folder)
            integrator.add_scene(scene(size))
            start = time.perf_counter()
            integrator.render(progress=False, workers=workers)
            elapsed = time.perf_counter() - start + gp_seconds
            error = rmse(integrator.scene.rendered_image, reference)
            curves.setdefault(name, []).append((elapsed, error))
            rows.append([name, samples, f"{error:.4f}", f"{elapsed:.2f}", f"{gp_seconds:.2f}",
                         f"{error ** 2 * elapsed:.5f}"])
    plot_methods(curves, out / "monte_carlo_methods.png")
    hit = hit_pixels(size)
    pattern_rows, errors = [], {}
    for name in ("CMC", "BMC", "BMC, one GP unturned"):
        random.seed(SEED)
        integrator, _ = method_integrator(name, PATTERN_SAMPLES, folder)
        integrator.add_scene(scene(size))
        integrator.render(progress=False, workers=workers)
        errors[name] = integrator.scene.rendered_image - reference
        pattern_rows.append([name, f"{rmse(integrator.scene.rendered_image, reference):.4f}",
                             f"{neighbour_correlation(errors[name], hit):.3f}"])
    plot_error_images(errors, out / "monte_carlo_patterns.png")
    return ("The four methods, a pool of " f"{POOL_SIZE} GPs for each Bayesian render:\n\n"
            + markdown_table(["Method", "N", "RMSE", "Time (s)", "of it, the GPs (s)",
                              "RMSE^2 x time"], rows, 1)
            + f"\n\nAt N = {PATTERN_SAMPLES}, the error's correlation between neighbouring "
            "pixels (both on an object):\n\n"
            + markdown_table(["Method", "RMSE", "Neighbour correlation"], pattern_rows, 1))


def plot_methods(curves: dict, path: Path) -> None:
    """RMSE against time on log-log axes, one line per method, its points N = 8 ... 256."""
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(figsize=(6.5, 4.8))
    for (name, points), marker in zip(curves.items(), ("o", "v", "x", "1")):
        times, errors = zip(*points)
        axes.loglog(times, errors, marker + "-", label=name, markersize=8)
        for (t, e), samples in zip(points, METHOD_SAMPLES):
            if samples in (8, 256):
                axes.annotate(f"N={samples}", (t, e), textcoords="offset points",
                              xytext=(4, 4), fontsize=7)
    # seconds as plain numbers at 1, 2 and 5 of each decade; the minor ticks unlabelled
    from matplotlib.ticker import FuncFormatter, NullFormatter
    axes.set_xticks([step * 10.0 ** decade for decade in range(-2, 3) for step in (1, 2, 5)
                     if axes.get_xlim()[0] <= step * 10.0 ** decade <= axes.get_xlim()[1]])
    axes.xaxis.set_major_formatter(FuncFormatter(lambda seconds, _: f"{seconds:g}"))
    axes.xaxis.set_minor_formatter(NullFormatter())
    axes.set_xlabel("time of the render, the GPs' making included (s)")
    axes.set_ylabel("RMSE against the reference")
    axes.set_title("Error against time: classic and Bayesian Monte Carlo")
    axes.legend()
    axes.grid(True, which="both", alpha=0.3)
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)


def plot_error_images(errors: dict, path: Path) -> None:
    """The signed error (mean over channels) of each render, side by side, on one scale."""
    import matplotlib.pyplot as plt
    limit = max(float(np.abs(e.mean(axis=2)).max()) for e in errors.values()) * 0.5
    figure, axes = plt.subplots(1, len(errors), figsize=(4 * len(errors), 4.2))
    for ax, (name, error) in zip(axes, errors.items()):
        shown = ax.imshow(error.mean(axis=2), cmap="RdBu", vmin=-limit, vmax=limit)
        ax.set_axis_off()
        ax.set_title(f"{name}, N = {PATTERN_SAMPLES}", fontsize=10)
    figure.colorbar(shown, ax=list(axes), label="image - reference, mean of r, g, b",
                    shrink=0.8)
    figure.savefig(path, dpi=100)
    plt.close(figure)


def adaptive_against_uniform(reference: np.ndarray, workers: int, folder: Path) -> str:
    """Uniform and adaptive sampling of the camera rays (16 per pixel) with 4 samples per
    hit: error, time and rays. Adaptive sampling refines where neighbouring pixels differ,
    which Monte Carlo noise makes everywhere."""
    rows = []
    for adaptive in (False, True):
        random.seed(SEED)
        start = time.perf_counter()
        image = rendered(4, TRADE_SIZE, folder, workers=workers, samples_per_pixel=16,
                         adaptive=adaptive).scene.rendered_image
        elapsed = time.perf_counter() - start
        rows.append(["adaptive" if adaptive else "uniform", f"{rmse(image, reference):.4f}",
                     f"{elapsed:.2f}"])
    return ("Camera rays, 16 per pixel, with 4 samples per hit:\n\n"
            + markdown_table(["Sampling", "RMSE", "Time (s)"], rows, 1))


def plot_trade(errors: list, reference_samples: int, path: Path) -> None:
    """RMSE against N on log-log axes, with the line of slope -1/2 through the first, and
    what it becomes measured against a reference of its own error: the reference of
    M samples adds its variance sigma^2/M to each image's sigma^2/N."""
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(figsize=(6, 4.5))
    samples = np.array(TRADE_SAMPLES, dtype=float)
    variance = errors[0] ** 2 * samples[0]  # sigma^2, from the fewest samples
    axes.loglog(samples, errors, "o-", label="CMCIntegrator, measured")
    axes.loglog(samples, np.sqrt(variance / samples), "--",
                label="slope -1/2 (error ~ 1/sqrt(N))")
    axes.loglog(samples, np.sqrt(variance / samples + variance / reference_samples), ":",
                label=f"the same, against a reference of {reference_samples}")
    axes.set_xlabel("N, samples per hit")
    axes.set_ylabel("RMSE against the reference")
    axes.set_title("Classic Monte Carlo: error against samples")
    axes.legend()
    axes.grid(True, which="both", alpha=0.3)
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)


def plot_error_image(image: np.ndarray, reference: np.ndarray, path: Path) -> None:
    """The per-pixel error |image - reference| (mean over channels), as a heat map."""
    import matplotlib.pyplot as plt
    error = np.abs(image - reference).mean(axis=2)
    figure, axes = plt.subplots(figsize=(5, 4.2))
    shown = axes.imshow(error, cmap="inferno")
    axes.set_axis_off()
    axes.set_title(f"Per-pixel error, N = {ERROR_IMAGE_SAMPLES}")
    figure.colorbar(shown, label="|image - reference|, mean of r, g, b")
    figure.tight_layout()
    figure.savefig(path, dpi=100)
    plt.close(figure)


def parse_args(argv):
    parser = argparse.ArgumentParser(
        description="Measure the classic Monte Carlo integrator: its speed against the flat "
                    "loop and a student's loop, and its error against the samples per hit "
                    "-> out/monte_carlo.md, out/monte_carlo_rmse.png, "
                    "out/monte_carlo_error.png.")
    parser.add_argument("--only", choices=("speed", "trade"), default=None,
                        help="measure one of the two (default: both)")
    parser.add_argument("--repeats", type=positive_arg(int), default=3,
                        help="turns of the speed measurement (default 3)")
    parser.add_argument("--reference-samples", type=positive_arg(int),
                        default=REFERENCE_SAMPLES,
                        help=f"samples per hit of the trade's reference (default "
                             f"{REFERENCE_SAMPLES})")
    parser.add_argument("--workers", type=positive_arg(int), default=usable_cores(),
                        help=f"processes for the all-core renders (default {usable_cores()})")
    parser.add_argument("--out", type=Path, default=OUT_DIR,
                        help="folder for the table and plots (default: out/ of the repository)")
    return parser.parse_args(argv)


def main(argv=None) -> int:
    args = parse_args(argv)
    matplotlib.use("Agg")
    args.out.mkdir(parents=True, exist_ok=True)
    parts = []
    with tempfile.TemporaryDirectory(prefix="pyrt-monte-carlo-") as folder:
        if args.only in (None, "speed"):
            parts.append("## Speed\n\n" + speed(args.repeats, args.workers, Path(folder)))
        if args.only in (None, "trade"):
            parts.append("## The trade of time for error\n\n"
                         + trade(args.reference_samples, args.workers, Path(folder), args.out))
    write_report(args.out / "monte_carlo.md", "PyRT: classic Monte Carlo", "\n\n".join(parts))
    return 0


if __name__ == "__main__":
    run_command(main)
