"""How fast PyRT renders: the speed table, and how render time grows with the objects.

The speed table: for every image of the course's figures (Lazy, Intersection, Depth with
max_depth 5, Normal and Phong on the sphere scene; Phong on the Cornell box), the time
Integrator.render() takes in microseconds per pixel with one process and with all cores,
and the speed-up between the two. For the Phong images also the flat loop's time
(benchmarks/flat_loop.py) and render()'s time as a multiple of it; and the same for
PhongIntegrator's own compute_color, the course's algorithm as students write it, which
runs when pyrt.acceleration's AcceleratedPhong does not stand in for it.

Many objects: Phong at 32 x 32 pixels on a scene of small tiles (parallelograms) lit by
three point lights, with 100 and with 1000 tiles: the time of 1000 as a multiple of 100.
Linear growth is 10.

    python -m benchmarks.speed                  # the defaults: 500 x 500, 5 repeats
    python -m benchmarks.speed --size 100 --repeats 1   # a quick check
Results go to out/benchmark.md next to the repository's modules.
"""
import argparse
import random
import statistics
import tempfile
import time
from functools import partial
from pathlib import Path

import numpy as np

from AppRenderer import FIGURES, SCENES, positive_arg
from benchmarks.flat_loop import flat_phong
from benchmarks.timing import (OUT_DIR, run_command, SCENE_NAMES, figure_label, label, markdown_table,
                               paired_ratio, prepared, progress, timed_turns, write_report)
from PyRT_Common import Normalize, RGBColor, Vector3D
from PyRT_Core import Camera, Lambertian, Parallelogram, PointLight, Scene
from PyRT_Integrators import Integrator, PhongIntegrator
from pyrt.workers import usable_cores

# Targets: render() of Figure 1 in one process at most this multiple of the flat loop's
# time; PhongIntegrator's own code at most this multiple; 1000 tiles at most this multiple
# of 100 tiles.
FIGURE1_TARGET = 1.25
OWN_CODE_TARGET = 2.0
MANY_OBJECTS_TARGET = 12.0
TILE_COUNTS = (100, 1000)
TILES_IMAGE_SIZE = 32
TILES_SEED = 2026


def own_code(integrator: PhongIntegrator) -> PhongIntegrator:
    """The integrator with its class's compute_color set on the instance itself: the same
    method, which AcceleratedPhong does not stand in for (it stands in for the class's
    own only), so that its own code runs, with the accelerated queries."""
    integrator.compute_color = integrator.compute_color
    return integrator


def speed_table(size: int, repeats: int, workers: int, folder: Path) -> str:
    """Renders every course figure, and PhongIntegrator's own code on both scenes, with 1
    and `workers` processes, and the Phong images with the flat loop too; returns the
    Markdown table of microseconds per pixel with the targets checked."""
    jobs = [(figure, name, scene, max_depth, False)
            for figure, name, scene, max_depth in FIGURES]
    jobs += [(figure, name, scene, max_depth, True)
             for figure, name, scene, max_depth in FIGURES if name == "phong"]
    pixels = size * size
    rows, checks = [], []
    for number, (figure, name, scene, max_depth, own) in enumerate(jobs, 1):
        def make(name=name, figure=figure, scene=scene, max_depth=max_depth, own=own):
            integrator = prepared(name, figure, scene, max_depth, size, folder)
            return own_code(integrator) if own else integrator

        caption = label(make()) + (", own code" if own else "")
        progress(f"[{number}/{len(jobs)}] {caption} on the {SCENE_NAMES[scene]}")
        tasks = [lambda count=count: partial(make().render, workers=count, progress=False)
                 for count in (1, workers)]
        phong = name == "phong"
        if phong:
            check_flat_loop(make())
            tasks.append(lambda scene=scene: partial(flat_phong, SCENES[scene](size, size)))
        times = timed_turns(tasks, repeats)
        one, many, *flat = [statistics.median(counted) for counted in times]
        ratio = paired_ratio(times[0], times[2]) if phong else None
        rows.append([figure_label(figure) if not own else "", caption, SCENE_NAMES[scene],
                     f"{flat[0] / pixels * 1e6:.2f}" if phong else "",
                     f"{one / pixels * 1e6:.2f}", f"{ratio:.2f}" if phong else "",
                     f"{many / pixels * 1e6:.2f}", f"{paired_ratio(times[0], times[1]):.2f}"])
        if phong and scene == "cornell":
            target = OWN_CODE_TARGET if own else FIGURE1_TARGET
            checks.append(f"{caption}, Cornell box, 1 process / flat loop: {ratio:.2f} "
                          f"(target at most {target}: {verdict(ratio <= target)})")
    header = ["Image", "Integrator", "Scene", "Flat loop (µs/pixel)", "1 process (µs/pixel)",
              "1 process / flat loop", f"{workers} processes (µs/pixel)", "Speed-up"]
    notes = (f"{size}x{size} pixels, one ray through each pixel centre; each time is the "
             f"median of {repeats} call(s) of Integrator.render(), which includes writing "
             "the .png, .npy and .hdr files and, with several processes, starting them; "
             "the one-process render, the all-core render and the flat loop take turns. "
             "'own code' is PhongIntegrator's own compute_color, the course's algorithm "
             "as students write it (the queries accelerated, AcceleratedPhong not standing "
             "in for it). The flat loop is benchmarks/flat_loop.py: the same Phong image, "
             "bit for bit, from one loop with no objects per pixel and no calls, testing "
             "every object for every ray; '1 process / flat loop' is render()'s time as a "
             "multiple of it. The ratios (that one and the speed-up) are medians of the "
             "ratios of the times of each turn, not ratios of the medians.")
    return (markdown_table(header, rows, 3) + "\n\n" + notes + "\n\n## Targets\n\n"
            + "\n".join(f"- {check}" for check in checks))


def check_flat_loop(integrator: Integrator) -> None:
    """Raises an AssertionError unless flat_phong gives the image integrator.render() gives,
    bit for bit."""
    integrator.render(workers=1, progress=False)
    image = flat_phong(integrator.scene)
    assert np.array_equal(image, integrator.scene.rendered_image), (
        f"the flat loop's image differs from render()'s by up to "
        f"{np.abs(image - integrator.scene.rendered_image).max():g}")


def verdict(met: bool) -> str:
    return "met" if met else "MISSED"


# ------------------------------------------------------------------------------------------
# Many objects
# ------------------------------------------------------------------------------------------
def tiles_scene(count: int, size: int = TILES_IMAGE_SIZE) -> Scene:
    """A scene of `count` small square tiles of random orientation, scattered in front of
    the camera (the same tiles on every run), lit by three point lights above them."""
    rng = random.Random(TILES_SEED)
    scene = Scene()
    scene.set_ambient(RGBColor(0.2, 0.2, 0.2))
    for _ in range(count):
        corner = Vector3D(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-5, -2))
        sides = [Normalize(Vector3D(rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1))) * 0.1
                 for _ in range(2)]
        tile = Parallelogram(corner, *sides)
        tile.set_BRDF(Lambertian(RGBColor(rng.random(), rng.random(), rng.random())))
        scene.add_object(tile)
    for x in (-1.0, 0.0, 1.0):
        scene.add_point_light_sources(PointLight(Vector3D(x, 2.0, -3.0),
                                                 RGBColor(2.0, 2.0, 2.0)))
    scene.set_camera(Camera(size, size, 60))
    return scene


def many_objects(repeats: int, folder: Path) -> str:
    """The time of a one-process Phong render of tiles_scene for each of TILE_COUNTS, and
    the largest as a multiple of the smallest, checked against MANY_OBJECTS_TARGET."""
    def render(count):
        def run():
            integrator = PhongIntegrator(str(folder / f"tiles{count}"))
            integrator.add_scene(tiles_scene(count))
            return partial(integrator.render, workers=1, progress=False)
        return run

    progress(f"Many objects: {' and '.join(map(str, TILE_COUNTS))} tiles")
    times = timed_turns([render(count) for count in TILE_COUNTS], repeats)
    ratio = paired_ratio(times[-1], times[0])
    rows = [[count, f"{statistics.median(counted):.3f}"]
            for count, counted in zip(TILE_COUNTS, times)]
    return (markdown_table(["Tiles", "Phong render, 1 process (s)"], rows, 1) + "\n\n"
            + f"{TILES_IMAGE_SIZE}x{TILES_IMAGE_SIZE} pixels, three point lights; median of "
            f"{repeats} render(s) each, taking turns. {TILE_COUNTS[-1]} tiles / "
            f"{TILE_COUNTS[0]} tiles: {ratio:.2f} (linear: "
            f"{TILE_COUNTS[-1] / TILE_COUNTS[0]:g}; target at most {MANY_OBJECTS_TARGET:g}: "
            f"{verdict(ratio <= MANY_OBJECTS_TARGET)})")


# ------------------------------------------------------------------------------------------
# Command line
# ------------------------------------------------------------------------------------------
def parse_args(argv: list | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        description="Measure how fast PyRT renders: microseconds per pixel of every "
                    "integrator of the course's figures with one process and with all "
                    "cores, the Phong images against the flat loop, and Phong on 100 and "
                    "1000 objects -> out/benchmark.md.")
    parser.add_argument("--size", type=positive_arg(int), default=500,
                        help="image width and height in pixels (default 500, as in the "
                             "course)")
    parser.add_argument("--repeats", type=positive_arg(int), default=5,
                        help="renders per measurement, of which the median time counts "
                             "(default 5)")
    parser.add_argument("--workers", type=positive_arg(int), default=usable_cores(),
                        help="processes for the 'all cores' measurements (default: all "
                             f"usable cores, here {usable_cores()})")
    parser.add_argument("--out", type=Path, default=OUT_DIR,
                        help="folder for the table (default: out/ of the repository)")
    return parser.parse_args(argv)


def main(argv: list | None = None) -> int:
    args = parse_args(argv)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="pyrt-benchmark-") as folder:
        table = speed_table(args.size, args.repeats, args.workers, Path(folder))
        scaling = many_objects(args.repeats, Path(folder))
    write_report(args.out / "benchmark.md", "PyRT speed",
                 table + "\n\n## Many objects\n\n" + scaling)
    progress(f"Benchmark finished in {time.perf_counter() - start:.0f} s")
    return 0


if __name__ == "__main__":
    run_command(main)
