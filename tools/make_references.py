"""Renders the course's figures into references/, the images test_references.py expects.

Every entry of AppRenderer.FIGURES is rendered at 500 x 500 pixels with AppRenderer's own
scenes and integrators, and its PNG is written to references/<figure>_<integrator>.png:

    figure1_phong.png         Phong on the Cornell box (Figure 1)
    figure2_lazy.png          Lazy on the sphere scene (Figure 2)
    figure3_intersection.png  Intersection on the sphere scene (Figure 3)
    figure4_depth.png         Depth, max_depth 5, on the sphere scene (Figure 4, left)
    figure4_normal.png        Normal on the sphere scene (Figure 4, right)
    figure5_phong.png         Phong on the sphere scene (Figure 5)

These images are the course's expected results, and the tests compare every change with
them. Into tests/data/, what only the tests read, it writes the linear image (.npy) of a
small Cornell box, Phong, with SAMPLED_REFERENCE_SAMPLES jittered rays per pixel: what the
anti-aliasing tests measure the error of fewer samples against, stored so that a bias of
the sampling shows as an error that no number of samples removes.

    cornell_phong_32x32_1024spp.npy

Given the folder of the course's own renders (the course framework's images of Figures 1,
3, 4 and 5, as linear .npz files), it also stores the course's Figure 1 on its seams, the
pixels within SEAM_BAND of the image's diagonals, where the Cornell box's walls meet:
what test_acceleration.py checks PyRT's Figure 1 against.

    course_figure1_seams.npz      arrays y, x and rgb (float64) of those pixels

Regenerate them only when an intended change alters the course images, never to make a
failing test pass; look at every new image before committing it, and give the reason for
the change in the commit message.

Run it from the repository's root folder:

    python tools/make_references.py [--course-renders ../shared/course-renders]
"""
import argparse
import shutil
import sys
import tempfile
from pathlib import Path
from typing import NamedTuple, Optional

REPO = Path(__file__).resolve().parent.parent
TESTS = REPO / "tests"
for folder in (REPO, TESTS):  # the repository's modules, and the tests' helpers
    if str(folder) not in sys.path:
        sys.path.insert(0, str(folder))

import numpy as np  # noqa: E402

import AppRenderer  # noqa: E402  (needs the repository on the import path first)
from pyrt.compare import REFERENCE_DIR, REFERENCE_SIZE as SIZE  # noqa: E402
from PyRT_Integrators import PhongIntegrator  # noqa: E402
from helpers import small_cornell_box  # noqa: E402

SAMPLED_REFERENCE_SIZE = 32
SAMPLED_REFERENCE_SAMPLES = 1024
DATA_DIR = TESTS / "data"  # what only the tests read
SAMPLED_REFERENCE = DATA_DIR / "cornell_phong_{0}x{0}_{1}spp.npy".format(
    SAMPLED_REFERENCE_SIZE, SAMPLED_REFERENCE_SAMPLES)
COURSE_SEAMS = DATA_DIR / "course_figure1_seams.npz"
SEAM_BAND = 3  # pixels either side of the diagonals


class Figure(NamedTuple):
    """One image of the course: an entry of AppRenderer.FIGURES."""

    figure: str
    integrator: str
    scene: str
    max_depth: Optional[float]

    @property
    def name(self):
        return AppRenderer.reference_name(self)

    @property
    def reference(self):
        return REFERENCE_DIR / f"{self.name}.png"


FIGURES = [Figure(*entry) for entry in AppRenderer.FIGURES]


def render_figure(figure, folder, size=SIZE, workers=None, progress=False):
    """Renders figure at size x size pixels into folder; returns the path of its PNG."""
    integrator = AppRenderer.make_integrator(figure.integrator, str(Path(folder) / figure.name),
                                             figure.max_depth)
    integrator.add_scene(AppRenderer.SCENES[figure.scene](size, size))
    integrator.render(workers=workers, progress=progress)
    return Path(integrator.get_filename() + ".png")


def render_sampled_reference(folder):
    """The linear image of SAMPLED_REFERENCE: Phong on small_cornell_box, many samples."""
    integrator = PhongIntegrator(str(Path(folder) / "sampled"))
    integrator.add_scene(small_cornell_box(SAMPLED_REFERENCE_SIZE))
    integrator.render(samples_per_pixel=SAMPLED_REFERENCE_SAMPLES)
    return Path(integrator.get_filename() + ".npy")


def write_course_seams(course_renders):
    """Stores the pixels of the course's Figure 1 (figure1_phong.npz in the folder
    course_renders) within SEAM_BAND of the diagonals x = y and x = SIZE - 1 - y."""
    course = np.load(Path(course_renders) / "figure1_phong.npz")["image"]
    y, x = np.mgrid[0:SIZE, 0:SIZE]
    band = (np.abs(x - y) <= SEAM_BAND) | (np.abs(x + y - (SIZE - 1)) <= SEAM_BAND)
    np.savez_compressed(COURSE_SEAMS, y=y[band], x=x[band], rgb=course[band])
    print(f"Wrote {COURSE_SEAMS.relative_to(REPO)}")


def main(argv=None):
    parser = argparse.ArgumentParser(description="Render the reference images of the tests.")
    parser.add_argument("--course-renders", type=Path,
                        help="the folder of the course's own renders: also store the seams "
                             "of its Figure 1")
    args = parser.parse_args(argv)
    REFERENCE_DIR.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory() as folder:
        for figure in FIGURES:
            shutil.copyfile(render_figure(figure, folder, progress=True), figure.reference)
            print(f"Wrote {figure.reference.relative_to(REPO)}")
        shutil.copyfile(render_sampled_reference(folder), SAMPLED_REFERENCE)
        print(f"Wrote {SAMPLED_REFERENCE.relative_to(REPO)}")
    if args.course_renders:
        write_course_seams(args.course_renders)


if __name__ == "__main__":
    main()
