"""Each figure of the course, rendered at 500 x 500 by `python AppRenderer.py --all-figures`
as a student renders it, matches its reference image in references/ (made by
tools/make_references.py) to within one 8-bit step per channel, compared by
pyrt.compare.compare_with_reference.

On a mismatch the expected image, the rendered one and their difference (a heat map:
black where they match, yellow where they differ most) are written to tests/failures/."""
import shutil
from pathlib import Path

import pytest

from AppRenderer import FILENAME, figure_integrator
from tools.make_references import FIGURES
from pyrt.compare import compare_with_reference

FAILURES = Path(__file__).resolve().parent / "failures"


def save_failure(figure, png, comparison):
    """Writes the expected image, the rendered one and their difference; returns the paths."""
    FAILURES.mkdir(exist_ok=True)
    paths = [FAILURES / f"{figure.name}_{kind}.png"
             for kind in ("expected", "actual", "difference")]
    shutil.copyfile(figure.reference, paths[0])
    shutil.copyfile(png, paths[1])
    comparison.save_difference(paths[2])
    return paths


@pytest.mark.parametrize("figure", FIGURES, ids=lambda figure: figure.name)
def test_figure_matches_its_reference_image(figure, all_figures):
    assert figure.reference.is_file(), (
        f"{figure.reference} is missing; create it with `python tools/make_references.py`")
    run, out = all_figures
    assert run.returncode == 0, run.stderr
    png = Path(figure_integrator(figure, str(out / FILENAME)).get_filename() + ".png")
    comparison = compare_with_reference(png, figure.reference)
    if not comparison.matches:
        paths = save_failure(figure, png, comparison)
        pytest.fail(f"{comparison.summary}; see " + ", ".join(map(str, paths)))
