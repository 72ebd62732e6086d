"""How fast PyRT renders, and how fast its error falls as it takes more samples per pixel.

Part 1, the speed table. For every image of the course's figures (Lazy, Intersection,
Depth with max_depth 5, Normal and Phong on the sphere scene; Phong on the Cornell box) and
for a plain "student" Phong integrator on both scenes (StudentPhongIntegrator below, written
the way the assignment leads a student to write it), the time Integrator.render() takes, in
microseconds per pixel, with one process and with all cores, and the speed-up between the
two. Each time is the median of --repeats renders, one-process and all-core renders taking
turns. It is printed as a Markdown table and written to out/benchmark.md.

Part 2, speed against accuracy. For Phong on the Cornell box (Figure 1) and Depth, Normal
and Phong on the sphere scene (Figures 4 and 5), a 160 x 160 image (--accuracy-size)
rendered with all cores, with uniform sampling at N = 1, 4, 16 and 64 samples per pixel
(--samples) and adaptive sampling capped at N = 4, 16 and 64 (--adaptive-samples): the
render time, the error of the linear image (scene.rendered_image) against a reference
rendered with 256 samples per pixel (--reference-samples), as RMSE and PSNR (the PSNR's
peak is the reference's largest value), and the render's own estimate of its RMSE.
N = 1 is the ray through the pixel centre; N > 1 samples are spread over a jittered grid
inside the pixel; adaptive sampling traces the centre rays, then N samples in the pixels
that differ from a neighbour. The tables go to out/speed_accuracy.md, with the targets of
adaptive sampling checked (adaptive N = 16 against uniform N = 16, error and time; the
error ratio at equal time; estimated against measured error), and a log-log plot of RMSE
against time to out/speed_accuracy.png: a solid line per image for uniform sampling, a
dashed one for adaptive, and for comparison a dotted line of slope -1/2, the 1/sqrt(N)
convergence of plain random sampling.

Run it from any folder; the results go to out/ next to this script, the rendered images to
a temporary folder that is deleted at the end:

    python benchmark.py                       # both parts
    python benchmark.py --only speed          # part 1 only
    python benchmark.py --only accuracy       # part 2 only
    python benchmark.py --size 100 --repeats 1 --accuracy-size 32
                                              # a quick check, about 10 seconds
    python benchmark.py --help                # all options

How long it takes: with the defaults, 5 to 7 minutes on a machine with 2 cores (about
1.7 minutes for part 1 and 3 to 5 minutes for part 2, depending on the machine's load). Part 1 grows with the square of --size,
part 2 with the square of --accuracy-size and with --reference-samples, both with
--repeats.
"""
import argparse
import contextlib
import datetime
import io
import json
import os
import platform
import statistics
import sys
import tempfile
import time
from math import log, log10
from pathlib import Path
from typing import Callable, NamedTuple

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from AppRenderer import FIGURES, SCENES, make_integrator, positive_arg
from PyRT_Common import BLACK, Length, Normalize, Ray
from PyRT_Integrators import Integrator
from PyRT_Rendering import ACCURACY_SUFFIX, ADAPTIVE_TOLERANCE, usable_cores

OUT_DIR = Path(__file__).resolve().parent / "out"
SCENE_NAMES = {"cornell": "Cornell box", "sphere": "sphere scene"}
# Part 2 measures the course figures made by these integrators, the ray-traced ones whose
# colour varies smoothly within a pixel (Lazy traces no rays, Intersection is red or black).
ACCURACY_INTEGRATORS = ("phong", "depth", "normal")


class StudentPhongIntegrator(Integrator):
    """Phong written the way the assignment describes it, with PyRT's vector and colour
    classes and nothing else: the baseline that shows what the framework's own
    PhongIntegrator gains."""

    def __init__(self, filename_, experiment_name=""):
        super().__init__(filename_ + "_StudentPhong", experiment_name)

    def compute_color(self, ray):
        hit_data = self.scene.closest_hit(ray)
        if not hit_data.has_hit:
            return BLACK
        hit_point = hit_data.hit_point
        normal = hit_data.normal
        brdf = self.scene.object_list[hit_data.primitive_index].get_BRDF()
        wo = ray.d * -1.0
        color = brdf.kd.multiply(self.scene.i_a)
        for light in self.scene.pointLights:
            to_light = light.pos - hit_point
            distance = Length(to_light)
            wi = Normalize(to_light)
            shadow_ray = Ray(hit_point, wi, distance)
            if not self.scene.any_hit(shadow_ray):
                light_color = light.intensity.multiply(brdf.get_value(wi, wo, normal))
                color = color + light_color / (distance * distance)
        return color


# ------------------------------------------------------------------------------------------
# Measuring
# ------------------------------------------------------------------------------------------
def time_renders(make: Callable[[], Integrator], worker_counts: list, repeats: int,
                 samples_per_pixel: int = 1) -> list:
    """For each worker count, the median time in seconds of `repeats` calls of render()
    on an integrator from make(). The counts take turns, so that a slow spell of the
    machine slows them alike instead of one of them. make() is called for each render:
    objects once pickled for worker processes keep their attributes in dictionaries from
    then on, which slows a later one-process render of them by about 10%."""
    times = [[] for _ in worker_counts]
    for _ in range(repeats):
        for workers, counted in zip(worker_counts, times):
            integrator = make()
            start = time.perf_counter()
            integrator.render(workers=workers, samples_per_pixel=samples_per_pixel,
                              progress=False)
            counted.append(time.perf_counter() - start)
    return [statistics.median(counted) for counted in times]


def prepared(name: str, figure: str, scene: str, max_depth, size: int,
             folder: Path) -> Integrator:
    """The integrator `name` of AppRenderer with a size x size image of `scene` attached,
    saving its images in `folder`."""
    if name == "student_phong":
        integrator = StudentPhongIntegrator(str(folder / "benchmark"), "_" + figure)
    else:
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


# ------------------------------------------------------------------------------------------
# Reporting
# ------------------------------------------------------------------------------------------
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


# ------------------------------------------------------------------------------------------
# Part 1: the speed table
# ------------------------------------------------------------------------------------------
def speed_table(size: int, repeats: int, workers: int, folder: Path) -> str:
    """Renders every course figure and the student Phong with 1 and `workers` processes;
    returns the Markdown table of microseconds per pixel."""
    jobs = list(FIGURES) + [("student", "student_phong", scene, None)
                            for scene in ("sphere", "cornell")]
    pixels = size * size
    rows = []
    for number, (figure, name, scene, max_depth) in enumerate(jobs, 1):
        integrator = prepared(name, figure, scene, max_depth, size, folder)
        progress(f"[{number}/{len(jobs)}] {label(integrator)} on the {SCENE_NAMES[scene]}")
        one, many = time_renders(
            lambda: prepared(name, figure, scene, max_depth, size, folder), [1, workers],
            repeats)
        rows.append([figure_label(figure), label(integrator), SCENE_NAMES[scene],
                     f"{one / pixels * 1e6:.2f}", f"{many / pixels * 1e6:.2f}",
                     f"{one / many:.2f}"])
    header = ["Image", "Integrator", "Scene", "1 process (µs/pixel)",
              f"{workers} processes (µs/pixel)", "Speed-up"]
    notes = (f"{size}x{size} pixels, one ray through each pixel centre; each time is the "
             f"median of {repeats} call(s) of Integrator.render(), which includes writing "
             "the .png, .npy and .hdr files and, with several processes, starting them. "
             "'student' is StudentPhongIntegrator of benchmark.py, the Phong model written "
             "with PyRT's Vector3D and RGBColor operations only.")
    return markdown_table(header, rows, 3) + "\n\n" + notes


# ------------------------------------------------------------------------------------------
# Part 2: speed against accuracy
# ------------------------------------------------------------------------------------------
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
        at16_cells = [f"{errors:.3f} ({'met' if errors <= 1.10 else 'MISSED'})",
                      f"{times:.3f} ({'met' if times <= 0.25 else 'MISSED'})"]
    else:
        at16_cells = ["n/a", "n/a"]
    gains = [(p.samples, equal_time_error(uniform, p.seconds) / p.rmse) for p in adaptive]
    measured = [gain for _, gain in gains if gain == gain]  # NaN: no uniform time to match
    verdict = "n/a" if not measured else "met" if max(measured) >= 2.0 else "MISSED"
    gains = [f"N={n}: {gain:.1f}" if gain == gain else f"N={n}: n/a" for n, gain in gains]
    ratios = [p.estimated / p.rmse for p in points if p.samples >= 4 and p.rmse > 0.0]
    if ratios:
        inside = all(0.5 <= ratio <= 2.0 for ratio in ratios)
        estimate_cell = (f"{min(ratios):.2f} - {max(ratios):.2f} "
                         f"({'met' if inside else 'MISSED'})")
    else:
        estimate_cell = "n/a"
    return at16_cells + [", ".join(gains) + f" ({verdict})", estimate_cell]


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
    target_notes = ("Targets: adaptive N=16 against uniform N=16, error ratio at most 1.10 "
                    "and time ratio at most 0.25; at equal time, uniform sampling's error "
                    "(interpolated on the log-log uniform curve at the adaptive render's "
                    "time) divided by adaptive's, at least 2 for the best adaptive N (aim "
                    "3); estimated / measured error within 0.5 - 2 for every render with "
                    "N >= 4.")
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
        description="Measure how fast PyRT renders. Part 1 (speed): microseconds per pixel "
                    "of every integrator of the course's figures, and of a plain student "
                    "Phong, with one process and with all cores -> out/benchmark.md. "
                    "Part 2 (accuracy): render time, error against a high-quality "
                    "reference and estimated error for uniform sampling at 1, 4, 16 and "
                    "64 samples per pixel and adaptive sampling capped at 4, 16 and 64 (by "
                    "default), with the targets of adaptive sampling checked -> "
                    "out/speed_accuracy.md and out/speed_accuracy.png. With no options "
                    "both parts run, in 5 to 7 minutes on 2 cores.")
    parser.add_argument("--only", choices=("speed", "accuracy"),
                        help="run only part 1 (speed) or only part 2 (accuracy)")
    parser.add_argument("--size", type=positive_arg(int), default=500,
                        help="part 1: image width and height in pixels (default 500, as in "
                             "the course)")
    parser.add_argument("--repeats", type=positive_arg(int), default=5,
                        help="renders per measurement, of which the median time counts "
                             "(default 5)")
    parser.add_argument("--workers", type=positive_arg(int), default=usable_cores(),
                        help="processes for the 'all cores' measurements (default: all "
                             f"usable cores, here {usable_cores()})")
    parser.add_argument("--accuracy-size", type=positive_arg(int), default=160,
                        help="part 2: image width and height in pixels (default 160)")
    parser.add_argument("--samples", type=positive_arg(int), nargs="+",
                        default=[1, 4, 16, 64],
                        help="part 2: samples per pixel of uniform sampling (default 1 4 16 "
                             "64)")
    parser.add_argument("--adaptive-samples", type=positive_arg(int), nargs="*",
                        default=[4, 16, 64],
                        help="part 2: the most samples per pixel of adaptive sampling, each "
                             "2 or more (default 4 16 64; none to leave it out)")
    parser.add_argument("--reference-samples", type=positive_arg(int), default=256,
                        help="part 2: samples per pixel of the reference image (default "
                             "256)")
    parser.add_argument("--out", type=Path, default=OUT_DIR,
                        help="folder for the tables and the plot (default: out/ next to "
                             "this script)")
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
        if args.only in (None, "speed"):
            table = speed_table(args.size, args.repeats, args.workers, Path(folder))
            write_report(args.out / "benchmark.md", "PyRT speed", table)
        if args.only in (None, "accuracy"):
            tables, curves = speed_accuracy(args.accuracy_size, args.samples,
                                            args.adaptive_samples, args.reference_samples,
                                            args.repeats, args.workers, Path(folder))
            write_report(args.out / "speed_accuracy.md", "PyRT speed against accuracy",
                         tables)
            plot_convergence(curves, args.out / "speed_accuracy.png",
                             f"PyRT: error against render time, {args.accuracy_size}x"
                             f"{args.accuracy_size} pixels, {args.workers} processes,\n"
                             f"reference: {args.reference_samples} samples per pixel")
    progress(f"Benchmark finished in {time.perf_counter() - start:.0f} s")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        sys.exit(130)
