"""How fast the error of PyRT's images falls as they take more samples per pixel.

For Phong on the Cornell box (Figure 1) and Depth, Normal and Phong on the sphere scene
(Figures 4 and 5), a 160 x 160 image (--size) rendered with all cores, with uniform
sampling at N = 1, 4, 16 and 64 samples per pixel (--samples) and adaptive sampling with
N = 4, 16 and 64 (--adaptive-samples): the render time, the error of the linear image
(scene.rendered_image) against a reference rendered with 256 samples per pixel
(--reference-samples), as RMSE and PSNR (the PSNR's peak is the reference's largest
value), and the render's own estimate of its RMSE. N = 1 is the ray through the pixel
centre; N > 1 samples are spread over a jittered grid inside the pixel; adaptive sampling
traces the centre rays, then N samples in the pixels that differ from a neighbour. The
tables go to out/speed_accuracy.md, with the targets of adaptive sampling checked, and a
log-log plot of RMSE against time to out/speed_accuracy.png: a solid line per image for
uniform sampling, a dashed one for adaptive, and a dotted line of slope -1/2, the
1/sqrt(N) convergence of plain random sampling.

    python -m benchmarks.accuracy               # the defaults
    python -m benchmarks.accuracy --size 32 --repeats 1 --samples 1 4 \
        --adaptive-samples 4 --reference-samples 16        # a quick check
"""
import argparse
import contextlib
import io
import json
import statistics
import tempfile
import time
from math import log, log10
from pathlib import Path
from typing import NamedTuple

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from AppRenderer import FIGURES, positive_arg
from benchmarks.timing import (OUT_DIR, run_command, SCENE_NAMES, figure_label, label, markdown_table,
                               prepared, progress, write_report)
from PyRT_Integrators import Integrator
from pyrt.sampling import ACCURACY_SUFFIX, ADAPTIVE_TOLERANCE
from pyrt.workers import usable_cores

# The course figures measured: the ray-traced ones whose colour varies smoothly within a
# pixel (Lazy traces no rays, Intersection is red or black).
ACCURACY_INTEGRATORS = ("phong", "depth", "normal")
# Targets of adaptive sampling: at N = 16, its error and its time as multiples of uniform
# sampling's; at equal time, uniform sampling's error as a multiple of adaptive's, for the
# best N; the render's estimate of its error as a multiple of the measured error.
ADAPTIVE_ERROR_TARGET = 1.10
ADAPTIVE_TIME_TARGET = 0.25
EQUAL_TIME_TARGET = 2.0
ESTIMATE_TARGET = (0.5, 2.0)


def verdict(met: bool) -> str:
    return "met" if met else "MISSED"


class Point(NamedTuple):
    """One render of the speed/accuracy measurement."""
    sampling: str       # "uniform" or "adaptive"
    samples: int        # N: rays per pixel, or the most a pixel gets (adaptive)
    seconds: float      # median render time
    rmse: float         # measured against the reference
    psnr: float         # dB
    estimated: float    # the render's own estimate (NaN for N = 1, which has none)


def convergence(integrator: Integrator, samples: list, adaptive_samples: list,
                reference_samples: int, workers: int, repeats: int) -> list:
    """A Point for each sample count, uniform and adaptive (default tolerance), against a
    reference rendered with reference_samples samples per pixel. The renders take turns,
    repeat after repeat, so that a slow spell of the machine slows them alike; the renders'
    own printed reports are left out of the benchmark's output."""
    scene = integrator.scene
    accuracy_file = Path(integrator.get_filename() + ACCURACY_SUFFIX)
    runs = [("uniform", n) for n in samples] + [("adaptive", n) for n in adaptive_samples]
    times = {run: [] for run in runs}
    errors = {}  # the same on every repeat: the images do not change
    with contextlib.redirect_stdout(io.StringIO()):
        integrator.render(workers=workers, samples_per_pixel=reference_samples,
                          progress=False)
        reference = scene.rendered_image.copy()
        for _ in range(repeats):
            for sampling, n in runs:
                start = time.perf_counter()
                integrator.render(workers=workers, samples_per_pixel=n, progress=False,
                                  adaptive=sampling == "adaptive")
                times[sampling, n].append(time.perf_counter() - start)
                rmse = float(np.sqrt(np.mean((scene.rendered_image - reference) ** 2)))
                estimated = (json.loads(accuracy_file.read_text())["estimated_rmse"]
                             if accuracy_file.exists() else float("nan"))
                errors[sampling, n] = rmse, estimated
    peak = float(reference.max())
    return [Point(sampling, n, statistics.median(times[sampling, n]), rmse,
                  20.0 * log10(peak / rmse) if rmse > 0.0 else float("inf"), estimated)
            for (sampling, n), (rmse, estimated) in errors.items()]


def loglog_slope(xs: list, ys: list) -> float:
    """The slope of the least-squares line through (log x, log y); NaN with fewer than two
    points (zero errors are left out: they have no logarithm)."""
    kept = [(x, y) for x, y in zip(xs, ys) if x > 0.0 and y > 0.0]
    if len(kept) < 2:
        return float("nan")
    logs = np.log(np.array(kept))
    return float(np.polyfit(logs[:, 0], logs[:, 1], 1)[0])


def equal_time_error(uniform: list, seconds: float) -> float:
    """The error uniform sampling would have in `seconds`: interpolated between the uniform
    points on log-log axes; NaN outside their range of times."""
    ordered = sorted((p.seconds, p.rmse) for p in uniform if p.rmse > 0.0)
    times = np.log([t for t, _ in ordered])
    if len(ordered) < 2 or not times[0] <= log(seconds) <= times[-1]:
        return float("nan")
    return float(np.exp(np.interp(log(seconds), times, np.log([e for _, e in ordered]))))


def target_checks(points: list) -> list:
    """The issue's targets for one image, as [adaptive/uniform error at N = 16, adaptive/
    uniform time at N = 16, equal-time error ratios (uniform / adaptive) of each adaptive
    N, estimated/measured error over all N >= 4 (lowest - highest)]; 'n/a' where the
    points needed were not measured."""
    uniform = [p for p in points if p.sampling == "uniform"]
    adaptive = [p for p in points if p.sampling == "adaptive"]
    at16 = {p.sampling: p for p in points if p.samples == 16}
    if len(at16) == 2:
        errors = at16["adaptive"].rmse / at16["uniform"].rmse
        times = at16["adaptive"].seconds / at16["uniform"].seconds
        at16_cells = [f"{errors:.3f} ({verdict(errors <= ADAPTIVE_ERROR_TARGET)})",
                      f"{times:.3f} ({verdict(times <= ADAPTIVE_TIME_TARGET)})"]
    else:
        at16_cells = ["n/a", "n/a"]
    gains = [(p.samples, equal_time_error(uniform, p.seconds) / p.rmse) for p in adaptive]
    measured = [gain for _, gain in gains if gain == gain]  # NaN: no uniform time to match
    gain_verdict = "n/a" if not measured else verdict(max(measured) >= EQUAL_TIME_TARGET)
    gains = [f"N={n}: {gain:.1f}" if gain == gain else f"N={n}: n/a" for n, gain in gains]
    ratios = [p.estimated / p.rmse for p in points if p.samples >= 4 and p.rmse > 0.0]
    if ratios:
        low, high = ESTIMATE_TARGET
        inside = all(low <= ratio <= high for ratio in ratios)
        estimate_cell = f"{min(ratios):.2f} - {max(ratios):.2f} ({verdict(inside)})"
    else:
        estimate_cell = "n/a"
    return at16_cells + [", ".join(gains) + f" ({gain_verdict})", estimate_cell]


def plot_convergence(curves: list, path: Path, title: str) -> None:
    """Draws RMSE against time on log-log axes: for each (name, points) of curves, uniform
    sampling as a solid line and adaptive sampling as a dashed one of the same colour, with
    a dashed black line of slope -1/2 through the middle of all the points."""
    fig = Figure(figsize=(9, 8), dpi=120)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    all_times, all_errors = [], []
    for number, (name, points) in enumerate(curves):
        color = f"C{number}"
        for sampling, style, marker in (("uniform", "-", "o"), ("adaptive", "--", "s")):
            shown = [p for p in points if p.sampling == sampling and p.rmse > 0.0]
            if not shown:
                continue
            ax.loglog([p.seconds for p in shown], [p.rmse for p in shown], style,
                      marker=marker, color=color, label=f"{name}: {sampling}")
            for p in shown:
                ax.annotate(f"N={p.samples}", (p.seconds, p.rmse), textcoords="offset points",
                            xytext=(5, 4), fontsize=7, color=color)
            all_times += [p.seconds for p in shown]
            all_errors += [p.rmse for p in shown]
    if all_times:
        t = np.array([min(all_times), max(all_times)])
        centre_t = np.exp(np.mean(np.log(all_times)))
        centre_e = np.exp(np.mean(np.log(all_errors)))
        ax.loglog(t, centre_e * (t / centre_t) ** -0.5, "k:", linewidth=1,
                  label="slope -1/2: error ~ 1/sqrt(N), plain random sampling")
    ax.set_xlabel("render time (s)", fontsize=11)
    ax.set_ylabel("RMSE of the linear image against the reference", fontsize=11)
    ax.set_title(title, fontsize=11)
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
        axis.set_minor_formatter(NullFormatter())
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2,
              title="solid: uniform, N rays in every pixel (N=1: the pixel centre); dashed: "
                    "adaptive, at most N",
              title_fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, bbox_inches="tight")
    print(f"Plot written to {path}")


def speed_accuracy(size: int, samples: list, adaptive_samples: list, reference_samples: int,
                   repeats: int, workers: int, folder: Path) -> tuple:
    """Measures time and error of each ray-traced course figure at each sample count,
    uniform and adaptive; returns the Markdown tables and the curves to plot, as
    (name, points)."""
    jobs = [job for job in FIGURES if job[1] in ACCURACY_INTEGRATORS]
    rows, slopes, targets, curves = [], [], [], []
    for number, (figure, name, scene, max_depth) in enumerate(jobs, 1):
        integrator = prepared(name, figure, scene, max_depth, size, folder)
        caption = f"{label(integrator)}, {SCENE_NAMES[scene]} ({figure_label(figure)})"
        progress(f"[{number}/{len(jobs)}] {caption}")
        points = convergence(integrator, samples, adaptive_samples, reference_samples,
                             workers, repeats)
        curves.append((caption, points))
        rows += [[caption, p.sampling, p.samples, f"{p.seconds:.3f}", f"{p.rmse:.3e}",
                  f"{p.estimated:.3e}" if p.estimated == p.estimated else "-",
                  f"{p.estimated / p.rmse:.2f}" if p.estimated == p.estimated else "-",
                  f"{p.psnr:.1f}"] for p in points]
        uniform = [p for p in points if p.sampling == "uniform"]
        errors = [p.rmse for p in uniform]
        slopes.append([caption, f"{loglog_slope([p.seconds for p in uniform], errors):.2f}",
                       f"{loglog_slope([p.samples for p in uniform], errors):.2f}"])
        targets.append([caption] + target_checks(points))
    notes = (f"{size}x{size} pixels rendered with {workers} processes; time: median of "
             f"{repeats} call(s) of Integrator.render(). Error of the linear image "
             f"(scene.rendered_image) against the same scene rendered with "
             f"{reference_samples} samples per pixel: RMSE over all pixels and channels, and "
             "PSNR = 20 log10(peak / RMSE) with the peak taken as the reference's largest "
             "value. Uniform: N rays in every pixel, N = 1 the ray through the pixel "
             "centre, N > 1 jittered over an even grid inside the pixel. Adaptive: the "
             "centre ray of every pixel, then N jittered rays in the pixels that differ from "
             f"a neighbour by more than the default tolerance ({ADAPTIVE_TOLERANCE}). "
             "Estimated: the render's own estimate of its RMSE (its _accuracy.json), from "
             "the spread of each pixel's samples. The slopes are least-squares fits of "
             "log RMSE against log time and against log N for uniform sampling; plain random "
             "sampling converges as 1/sqrt(N), slope -1/2.")
    target_notes = (f"Targets: adaptive N=16 against uniform N=16, error ratio at most "
                    f"{ADAPTIVE_ERROR_TARGET} and time ratio at most {ADAPTIVE_TIME_TARGET}; "
                    "at equal time, uniform sampling's error (interpolated on the log-log "
                    "uniform curve at the adaptive render's time) divided by adaptive's, at "
                    f"least {EQUAL_TIME_TARGET:g} for the best adaptive N; estimated / "
                    f"measured error within {ESTIMATE_TARGET[0]} - {ESTIMATE_TARGET[1]:g} for "
                    "every render with N >= 4.")
    tables = (markdown_table(["Image", "Sampling", "N", "Time (s)", "RMSE", "Estimated RMSE",
                              "Estimated / RMSE", "PSNR (dB)"], rows, 2)
              + "\n\n" + markdown_table(
                  ["Image", "Slope of log RMSE vs log time (uniform)",
                   "Slope of log RMSE vs log N (uniform)"], slopes, 1)
              + "\n\n" + notes
              + "\n\n## Targets\n\n" + markdown_table(
                  ["Image", "Adaptive 16 / uniform 16: error", "Adaptive 16 / uniform 16: time",
                   "Equal time: uniform error / adaptive error",
                   "Estimated / measured (N >= 4)"], targets, 1)
              + "\n\n" + target_notes)
    return tables, curves


# ------------------------------------------------------------------------------------------
# Command line
# ------------------------------------------------------------------------------------------
def parse_args(argv: list | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        description="Measure PyRT's speed against accuracy: render time, error against a "
                    "high-quality reference and estimated error for uniform sampling at 1, "
                    "4, 16 and 64 samples per pixel and adaptive sampling with 4, 16 and 64 "
                    "(by default), with the targets of adaptive sampling checked -> "
                    "out/speed_accuracy.md and out/speed_accuracy.png.")
    parser.add_argument("--size", type=positive_arg(int), default=160,
                        help="image width and height in pixels (default 160)")
    parser.add_argument("--repeats", type=positive_arg(int), default=5,
                        help="renders per measurement, of which the median time counts "
                             "(default 5)")
    parser.add_argument("--workers", type=positive_arg(int), default=usable_cores(),
                        help=f"processes that render (default: all usable cores, here "
                             f"{usable_cores()})")
    parser.add_argument("--samples", type=positive_arg(int), nargs="+",
                        default=[1, 4, 16, 64],
                        help="samples per pixel of uniform sampling (default 1 4 16 64)")
    parser.add_argument("--adaptive-samples", type=positive_arg(int), nargs="*",
                        default=[4, 16, 64],
                        help="the most samples per pixel of adaptive sampling, each 2 or more "
                             "(default 4 16 64; none to leave it out)")
    parser.add_argument("--reference-samples", type=positive_arg(int), default=256,
                        help="samples per pixel of the reference image (default 256)")
    parser.add_argument("--out", type=Path, default=OUT_DIR,
                        help="folder for the tables and the plot (default: out/ of the "
                             "repository)")
    args = parser.parse_args(argv)
    if args.reference_samples <= max(args.samples + args.adaptive_samples):
        parser.error("--reference-samples must be larger than every value of --samples and "
                     "--adaptive-samples")
    if 1 in args.adaptive_samples:
        parser.error("--adaptive-samples: adaptive sampling needs 2 or more samples per pixel")
    return args


def main(argv: list | None = None) -> int:
    args = parse_args(argv)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="pyrt-benchmark-") as folder:
        tables, curves = speed_accuracy(args.size, args.samples, args.adaptive_samples,
                                        args.reference_samples, args.repeats, args.workers,
                                        Path(folder))
    write_report(args.out / "speed_accuracy.md", "PyRT speed against accuracy", tables)
    plot_convergence(curves, args.out / "speed_accuracy.png",
                     f"PyRT: error against render time, {args.size}x{args.size} pixels, "
                     f"{args.workers} processes,\nreference: {args.reference_samples} "
                     "samples per pixel")
    progress(f"Benchmark finished in {time.perf_counter() - start:.0f} s")
    return 0


if __name__ == "__main__":
    run_command(main)
