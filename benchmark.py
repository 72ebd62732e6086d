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
(--samples) and adaptive sampling with N = 4, 16 and 64 (--adaptive-samples): the
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

How long it takes: with the defaults, about 9 minutes on a machine with 2 cores (about 3
minutes for part 1 and 6 for part 2). Part 1 grows with the square of --size, part 2 with
the square of --accuracy-size and with --reference-samples, both with --repeats.
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
from functools import partial
from math import hypot, log, log10, sqrt, tan
from pathlib import Path
from typing import Callable, NamedTuple

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from AppRenderer import FIGURES, SCENES, make_integrator, positive_arg
from PyRT_Common import BLACK, Length, Normalize, Ray
from PyRT_Core import (EDGE_TOLERANCE, INFINITY, OFFSET_SCALE, SHADOW_EPSILON, TIE_SHRINK,
                       Sphere)
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
# The flat loop: what CPython needs per pixel
# ------------------------------------------------------------------------------------------
def flat_phong(scene) -> np.ndarray:
    """The course's Phong image of a scene of spheres and parallelograms lit by point lights
    (Figures 1 and 5), made by one flat loop: no objects per pixel and no method calls,
    numpy only for each row's camera directions. It gives the image render() gives, with
    the same numbers in the same order (the primitives' own precomputed constants, the same
    intersection formulas, tie rule, shadow-ray offsets and shading), and measures what the
    interpreter needs for it: the speed table quotes the framework as a multiple of it.

    It does the plain work of the course's algorithm: it tests every object for every
    camera ray and every shadow ray, where render() leaves out the objects a ray cannot
    hit (Scene, _Sightlines). The intersection tests are written out for camera and for
    shadow rays alike, on purpose: a function for them is a call per test, which is what
    this loop measures the framework without."""
    camera, objects = scene.camera, []
    for obj in scene.object_list:
        kd = obj.BRDF.kd
        objects.append((isinstance(obj, Sphere), obj._k, getattr(obj, "_k2", None),
                        kd.r, kd.g, kd.b))
    lights = [(light.pos.x, light.pos.y, light.pos.z, light.intensity.r, light.intensity.g,
               light.intensity.b) for light in scene.pointLights]
    ambient_r, ambient_g, ambient_b = scene.i_a.r, scene.i_a.g, scene.i_a.b
    low, high = -EDGE_TOLERANCE, 1.0 + EDGE_TOLERANCE
    width, height = camera.width, camera.height
    # Camera.get_direction for a whole row at once, as Camera.row_directions computes it
    scale_y = tan(camera.vertical_fov / 2.0)
    scale_x = scale_y * camera.aspect_ratio
    screen_x = np.array([(2.0 * (x + 0.5) / width - 1.0) * scale_x for x in range(width)])
    image = np.zeros((height, width, 3))
    for y in range(height):
        screen_y = (1.0 - 2.0 * (y + 0.5) / height) * scale_y
        length = np.sqrt(screen_x * screen_x + (screen_y * screen_y + 1.0))
        row = []
        for dx, dy, dz in zip((screen_x / length).tolist(), (screen_y / length).tolist(),
                              (-1.0 / length).tolist()):
            # The nearest hit of the camera ray, from the origin: t_min 0, t_max infinity.
            t_max, nearest = INFINITY, None
            for sphere, k, k2, kr, kg, kb in objects:
                if sphere:
                    cx, cy, cz, r = k
                    fx, fy, fz = -cx / r, -cy / r, -cz / r
                    b = fx * dx + fy * dy + fz * dz
                    lx, ly, lz = fx - b * dx, fy - b * dy, fz - b * dz
                    disc = 1.0 - (lx * lx + ly * ly + lz * lz)
                    if disc < 0.0:
                        continue
                    f = hypot(fx, fy, fz)
                    if b > 0.0:
                        q = -b - sqrt(disc)
                        t0, t1 = q * r, (f - 1.0) * ((f + 1.0) / q) * r
                    else:
                        q = sqrt(disc) - b
                        t0, t1 = (f - 1.0) * ((f + 1.0) / q) * r, q * r
                    if 0.0 <= t0 <= t_max:
                        t = t0
                    elif 0.0 <= t1 <= t_max:
                        t = t1
                    else:
                        continue
                else:
                    nx, ny, nz, pn = k
                    den = dx * nx + dy * ny + dz * nz
                    if den == 0.0:
                        continue
                    t = pn / den
                    if not 0.0 <= t <= t_max:
                        continue
                    px, py, pz, uax, uay, uaz, ubx, uby, ubz = k2
                    qx, qy, qz = dx * t - px, dy * t - py, dz * t - pz
                    if not (low <= qx * uax + qy * uay + qz * uaz <= high
                            and low <= qx * ubx + qy * uby + qz * ubz <= high):
                        continue
                nearest, distance, t_max = (sphere, k, kr, kg, kb), t, t * TIE_SHRINK
            if nearest is None:
                row += (0.0, 0.0, 0.0)
                continue
            sphere, k, kr, kg, kb = nearest
            t = distance
            if sphere:
                cx, cy, cz, r = k
                vx, vy, vz = (dx * t - cx) / r, (dy * t - cy) / r, (dz * t - cz) / r
                length = sqrt(vx * vx + vy * vy + vz * vz)
                nx, ny, nz = vx / length, vy / length, vz / length
                px, py, pz = cx + nx * r, cy + ny * r, cz + nz * r
            else:
                nx, ny, nz, _ = k
                if dx * nx + dy * ny + dz * nz > 0.0:
                    nx, ny, nz = -nx, -ny, -nz
                px, py, pz = dx * t, dy * t, dz * t
            red, green, blue = kr * ambient_r, kg * ambient_g, kb * ambient_b
            offset = OFFSET_SCALE * (max(abs(px), abs(py), abs(pz)) + t)
            sx, sy, sz = px + nx * offset, py + ny * offset, pz + nz * offset
            for lpx, lpy, lpz, ir, ig, ib in lights:
                lx, ly, lz = lpx - px, lpy - py, lpz - pz
                if lx * nx + ly * ny + lz * nz <= offset:
                    continue
                r2 = lx * lx + ly * ly + lz * lz
                light_distance = sqrt(r2)
                wx, wy, wz = lx / light_distance, ly / light_distance, lz / light_distance
                s_min, s_max = offset, light_distance * (1.0 - SHADOW_EPSILON) - offset
                for sphere, k, k2, _, _, _ in objects:  # the shadow ray, against every object
                    if sphere:
                        cx, cy, cz, r = k
                        fx, fy, fz = (sx - cx) / r, (sy - cy) / r, (sz - cz) / r
                        b = fx * wx + fy * wy + fz * wz
                        ex, ey, ez = fx - b * wx, fy - b * wy, fz - b * wz
                        disc = 1.0 - (ex * ex + ey * ey + ez * ez)
                        if disc < 0.0:
                            continue
                        f = hypot(fx, fy, fz)
                        if b > 0.0:
                            q = -b - sqrt(disc)
                            t0, t1 = q * r, (f - 1.0) * ((f + 1.0) / q) * r
                        else:
                            q = sqrt(disc) - b
                            t0, t1 = (f - 1.0) * ((f + 1.0) / q) * r, q * r
                        if s_min <= t0 <= s_max or s_min <= t1 <= s_max:
                            break
                    else:
                        onx, ony, onz, pn = k
                        den = wx * onx + wy * ony + wz * onz
                        if den == 0.0:
                            continue
                        ts = (pn - (sx * onx + sy * ony + sz * onz)) / den
                        if not s_min <= ts <= s_max:
                            continue
                        ppx, ppy, ppz, uax, uay, uaz, ubx, uby, ubz = k2
                        qx, qy, qz = sx + wx * ts - ppx, sy + wy * ts - ppy, sz + wz * ts - ppz
                        if (low <= qx * uax + qy * uay + qz * uaz <= high
                                and low <= qx * ubx + qy * uby + qz * ubz <= high):
                            break
                else:  # nothing in the way: the Lambertian kd * cos, over r^2
                    cos_theta = nx * wx + ny * wy + nz * wz
                    if cos_theta > 0.0:
                        red += ir * (kr * cos_theta) / r2
                        green += ig * (kg * cos_theta) / r2
                        blue += ib * (kb * cos_theta) / r2
            row += (red, green, blue)
        image[y] = np.array(row).reshape(-1, 3)
    return image


# ------------------------------------------------------------------------------------------
# Measuring
# ------------------------------------------------------------------------------------------
def time_renders(make: Callable[[], Integrator], worker_counts: list, repeats: int,
                 samples_per_pixel: int = 1) -> list:
    """For each worker count, the median time in seconds of `repeats` calls of render()
    on an integrator from make(), the counts taking turns (time_turns). make() is called
    for each render: objects once pickled for worker processes keep their attributes in
    dictionaries from then on, which slows a later one-process render of them by about
    10%."""
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
    """Renders every course figure and the student Phong with 1 and `workers` processes,
    and the Phong images with the flat loop too; returns the Markdown table of
    microseconds per pixel."""
    jobs = list(FIGURES) + [("student", "student_phong", scene, None)
                            for scene in ("sphere", "cornell")]
    pixels = size * size
    rows = []
    for number, (figure, name, scene, max_depth) in enumerate(jobs, 1):
        integrator = prepared(name, figure, scene, max_depth, size, folder)
        progress(f"[{number}/{len(jobs)}] {label(integrator)} on the {SCENE_NAMES[scene]}")
        tasks = [lambda count=count: partial(
            prepared(name, figure, scene, max_depth, size, folder).render, workers=count,
            progress=False) for count in (1, workers)]
        phong = name in ("phong", "student_phong")
        if phong:
            check_flat_loop(integrator)
            tasks.append(lambda: partial(flat_phong, SCENES[scene](size, size)))
        times = timed_turns(tasks, repeats)
        one, many, *flat = [statistics.median(counted) for counted in times]
        rows.append([figure_label(figure), label(integrator), SCENE_NAMES[scene],
                     f"{flat[0] / pixels * 1e6:.2f}" if phong else "",
                     f"{one / pixels * 1e6:.2f}",
                     f"{paired_ratio(times[0], times[2]):.2f}" if phong else "",
                     f"{many / pixels * 1e6:.2f}", f"{paired_ratio(times[0], times[1]):.2f}"])
    header = ["Image", "Integrator", "Scene", "Flat loop (µs/pixel)", "1 process (µs/pixel)",
              "1 process / flat loop", f"{workers} processes (µs/pixel)", "Speed-up"]
    notes = (f"{size}x{size} pixels, one ray through each pixel centre; each time is the "
             f"median of {repeats} call(s) of Integrator.render(), which includes writing "
             "the .png, .npy and .hdr files and, with several processes, starting them; "
             "the one-process render, the all-core render and the flat loop take turns. "
             "'student' is StudentPhongIntegrator of benchmark.py, the Phong model written "
             "with PyRT's Vector3D and RGBColor operations only. The flat loop is flat_phong "
             "of benchmark.py: the same Phong image, bit for bit, from one loop with no "
             "objects per pixel and no method calls, testing every object for every ray; "
             "'1 process / flat loop' is the framework's time as a multiple of it. The "
             "ratios (that one and the speed-up) are medians of the ratios of the times "
             "of each turn, not ratios of the medians.")
    return markdown_table(header, rows, 3) + "\n\n" + notes


def check_flat_loop(integrator: Integrator) -> None:
    """Raises an AssertionError unless flat_phong gives the image integrator.render() gives,
    to within 1e-15."""
    integrator.render(workers=1, progress=False)
    difference = np.abs(flat_phong(integrator.scene) - integrator.scene.rendered_image).max()
    assert difference <= 1e-15, (f"the flat loop's image differs from render()'s by up to "
                                 f"{difference:g}")


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
                    "64 samples per pixel and adaptive sampling with 4, 16 and 64 (by "
                    "default), with the targets of adaptive sampling checked -> "
                    "out/speed_accuracy.md and out/speed_accuracy.png. With no options "
                    "both parts run, in about 9 minutes on 2 cores.")
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
