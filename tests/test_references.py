"""Each figure of the course, rendered at 500 x 500, matches its reference image in
tests/reference/ (made by tests/make_references.py) to within one 8-bit step per channel.

On a mismatch the expected image, the rendered one and their difference (scaled so that
the largest difference is white) are written to tests/failures/ for a look."""
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest

from helpers import PNG_TOLERANCE
from make_references import FIGURES, render_figure

FAILURES = Path(__file__).resolve().parent / "failures"


def save_failure(name, expected, actual):
    """Writes expected, actual and their amplified difference; returns their paths."""
    FAILURES.mkdir(exist_ok=True)
    difference = np.abs(actual[:, :, :3] - expected[:, :, :3])
    paths = [FAILURES / f"{name}_{kind}.png" for kind in ("expected", "actual", "difference")]
    plt.imsave(paths[0], expected)
    plt.imsave(paths[1], actual)
    plt.imsave(paths[2], difference / max(float(difference.max()), 1e-12))
    return paths


@pytest.mark.parametrize("figure", FIGURES, ids=lambda figure: figure.name)
def test_figure_matches_its_reference_image(figure, tmp_path):
    assert figure.reference.is_file(), (
        f"{figure.reference} is missing; create it with `python tests/make_references.py`")
    expected = plt.imread(figure.reference).astype(float)
    actual = plt.imread(render_figure(figure, tmp_path)).astype(float)
    assert actual.shape == expected.shape, (
        f"{figure.name}: rendered image has shape {actual.shape}, "
        f"the reference {expected.shape}")
    worst = float(np.abs(actual - expected).max())
    if worst > PNG_TOLERANCE:
        differing = int((np.abs(actual - expected) > PNG_TOLERANCE).any(axis=2).sum())
        paths = save_failure(figure.name, expected, actual)
        pytest.fail(f"{figure.name}: {differing} pixel(s) differ from the reference by up to "
                    f"{worst * 255:.1f}/255; see " + ", ".join(map(str, paths)))
