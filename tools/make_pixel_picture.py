"""Draws docs/pixel_436_420.png, the picture of a pixel's rays that the README shows.

The pixel is (436, 420) of a student's Phong image of the sphere scene (500 x 500), a dark
speckle on the floor: the student's shadow ray starts on the surface (t_min = 0), meets
the floor it leaves at distance 0 and hides the light, shadow acne. docs/working-with-pyrt.md
quotes the story of the same pixel, which this prints; both come from explain_pixel, so run
this again when the picture or the story changes, look at the new picture, and say why in
the commit message.

Run it from the repository's root folder:

    python tools/make_pixel_picture.py
"""
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
TESTS = REPO / "tests"
for folder in (REPO, TESTS):  # the repository's modules, and the tests' helpers
    if str(folder) not in sys.path:
        sys.path.insert(0, str(folder))

from AppRenderer import sphere_test_scene  # noqa: E402  (needs the repository on the path)
from helpers import ShadowRayFrom  # noqa: E402
from pyrt.explain import explain_pixel  # noqa: E402
from pyrt.explain_picture import save_picture  # noqa: E402

PIXEL = (436, 420)
PICTURE = REPO / "docs" / "pixel_{}_{}.png".format(*PIXEL)


class MyPhongIntegrator(ShadowRayFrom):
    """The student's Phong: its shadow ray starts on the surface, with t_min 0."""

    def __init__(self):
        super().__init__(0.0)


def main():
    """Prints the pixel's story and saves its picture as PICTURE."""
    integrator = MyPhongIntegrator()
    integrator.add_scene(sphere_test_scene())
    history = explain_pixel(integrator, *PIXEL)
    print(history)
    print(f"Saved {save_picture(history, integrator.scene, PICTURE)}")


if __name__ == "__main__":
    main()
