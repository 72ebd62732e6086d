"""Compare your images with the expected images of the course's figures.

Each assignment of Practice 1 is checked by comparing a render with a figure of the course
(Figures 1-5). Their expected images are in references/, one PNG per image:
figure1_phong, figure2_lazy, figure3_intersection, figure4_depth, figure4_normal and
figure5_phong. `compare_with_reference` compares one image with one of them (or with any
other image of the same size) and tells how many pixels differ and by how much:

    from pyrt.compare import compare_with_reference

    result = compare_with_reference("out/rendered_image_Phong.png", "figure1_phong",
                                    difference_png="out/difference.png")
    print(result.summary)      # figure1_phong: matches (largest difference 0/255)

Differences are counted in 8-bit steps, 1/255 each, the smallest difference a PNG can hold.
Two images match when no channel of any pixel is more than one step apart: matplotlib
stores a channel v as floor(255 v), so the same colour computed in a slightly different
order may land one step lower.

`compare_figures` compares several images with their figures, and `write_sheet` draws the
comparison sheet of `python AppRenderer.py --all-figures`: one row per figure with the
render, the reference and a heat map of their difference.
"""
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Sequence, Union

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

REPOSITORY = Path(__file__).resolve().parent.parent  # the folder of AppRenderer.py
REFERENCE_DIR = REPOSITORY / "references"
REFERENCE_SIZE = 500  # the references are REFERENCE_SIZE x REFERENCE_SIZE pixels
TOLERANCE_STEPS = 1   # differences of at most this many 8-bit steps do not count
HEAT_MAP = "inferno"  # black where the images agree, yellow where they differ most

# A PNG file, or its pixels as an array (see _pixels for the arrays accepted)
Image = Union[str, Path, np.ndarray]


# ------------------------------------------------------------------------------------------
# Comparing one image with a reference
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Comparison:
    """How an image compares with a reference image, pixel by pixel.

    name: the reference's name: the figure ("figure1_phong"), the file name without .png, or
        "image" for an array.
    differing_pixels: how many pixels have a channel more than one 8-bit step away from the
        reference.
    max_steps: the largest difference of any channel of any pixel, in 8-bit steps (0-255).
    image, reference: the two images compared, 8-bit RGB arrays of shape (height, width, 3).
    difference: for each pixel, the largest difference of its three channels in 8-bit
        steps, an array of shape (height, width)."""

    name: str
    differing_pixels: int
    max_steps: int
    image: np.ndarray = field(repr=False)
    reference: np.ndarray = field(repr=False)
    difference: np.ndarray = field(repr=False)

    @property
    def matches(self) -> bool:
        """True when no pixel differs from the reference by more than one 8-bit step."""
        return self.differing_pixels == 0

    @property
    def summary(self) -> str:
        """One line: whether the image matches, or how many pixels differ and by how much."""
        if self.matches:
            return f"{self.name}: matches (largest difference {self.max_steps}/255)"
        total = self.difference.size
        verb = "differs" if self.differing_pixels == 1 else "differ"
        return (f"{self.name}: {self.differing_pixels} of {total} pixels {verb}, "
                f"by up to {self.max_steps}/255")

    def heat_map(self):
        """(values, largest): the difference as drawn in a heat map. Differences within the
        tolerance are drawn as 0, so that an image that matches shows no difference; the
        colour scale runs from 0 to `largest` steps."""
        values = np.where(self.difference > TOLERANCE_STEPS, self.difference, 0)
        return values, max(self.max_steps, 1)

    def save_difference(self, path) -> Path:
        """Writes the difference as a heat map PNG of the image's size, one pixel for each
        pixel: black where the images match, brighter where they differ more, pale yellow
        for the largest difference. Returns the path."""
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        values, largest = self.heat_map()
        plt.imsave(path, values, cmap=HEAT_MAP, vmin=0, vmax=largest)
        return path


def compare_with_reference(image: Image, reference: Image,
                           difference_png=None) -> Comparison:
    """Compares an image with a reference image, pixel by pixel, and returns a Comparison:
    `matches`, `differing_pixels`, `max_steps` (the largest difference in 8-bit steps) and
    a one-line `summary`.

    image: the display image, either a PNG file (the .png a render writes) or its pixels:
        an array of shape (height, width, 3) (or 4, the alpha channel is ignored) holding
        floats in [0, 1], as plt.imread reads a PNG, or 8-bit integers (uint8, 0-255).
        The .npy file and scene.rendered_image hold the linear image, before the display
        mapping: compare the .png written beside them instead.
    reference: a figure name such as "figure1_phong" (its PNG in references/), a PNG
        file, or an array as for `image`.
    difference_png: if given, the path where the difference is written as a heat map (see
        Comparison.save_difference).

    Raises ValueError when the two images have different sizes, FileNotFoundError when a
    file or figure does not exist."""
    name, expected = _reference(reference)
    actual = _pixels(image, "the image")
    if actual.shape != expected.shape:
        raise ValueError(
            f"{name}: the image is {_size(actual)} pixels but the reference is "
            f"{_size(expected)}; render the image at {_size(expected)} "
            f"(--width {expected.shape[1]} --height {expected.shape[0]}) to compare them")
    # int16, because uint8 arithmetic would wrap around below 0
    difference = np.abs(actual.astype(np.int16) - expected).max(axis=2)
    result = Comparison(name, int((difference > TOLERANCE_STEPS).sum()),
                        int(difference.max()), actual, expected, difference)
    if difference_png is not None:
        result.save_difference(difference_png)
    return result


def reference_path(reference) -> Path:
    """The PNG of a reference: a bare name such as "figure1_phong" is that figure's image
    in references/, anything else (a name with .png or a folder) is a path."""
    path = Path(reference)
    if path.suffix == "" and path.parent == Path("."):
        return REFERENCE_DIR / f"{path.name}.png"
    return path


def _reference(reference):
    """(name, 8-bit pixels) of a reference given as compare_with_reference takes it."""
    if isinstance(reference, np.ndarray):
        return "image", _pixels(reference, "the reference")
    path = reference_path(reference)
    if not path.is_file():
        figures = ", ".join(sorted(p.stem for p in REFERENCE_DIR.glob("*.png")))
        raise FileNotFoundError(f"no reference image {path}; the course's figures are: "
                                f"{figures}")
    return path.stem, _pixels(path, "the reference")


def _pixels(image, what):
    """The 8-bit RGB pixels, shape (height, width, 3), of a display image given as a PNG
    path or an array. Float arrays must lie in [0, 1] and are rounded to the nearest 8-bit
    step (plt.imread gives exactly k/255); uint8 arrays are used as they are; a grey image
    of shape (height, width) counts as three equal channels."""
    if isinstance(image, (str, Path)):
        if Path(image).suffix.lower() == ".npy":
            raise ValueError(f"{what}: {image} holds the linear image, not the one shown; "
                             f"compare the .png saved beside it")
        image = plt.imread(str(image))
    pixels = np.asarray(image)
    if pixels.ndim == 2:
        pixels = np.stack([pixels] * 3, axis=2)
    if pixels.ndim != 3 or pixels.shape[2] not in (3, 4):
        raise ValueError(f"{what}: expected an image of shape (height, width, 3), "
                         f"got an array of shape {pixels.shape}")
    pixels = pixels[:, :, :3]
    if pixels.dtype == np.uint8:
        return pixels
    if not np.issubdtype(pixels.dtype, np.floating):
        raise TypeError(f"{what}: expected floats in [0, 1] or uint8 values 0-255, "
                        f"got {pixels.dtype}")
    if not np.isfinite(pixels).all() or pixels.min() < 0.0 or pixels.max() > 1.0:
        raise ValueError(f"{what}: its values are not all in [0, 1], so it is not a display "
                         f"image; for a render, compare the .png it saved, not the linear "
                         f".npy or scene.rendered_image")
    return np.rint(pixels * 255.0).astype(np.uint8)


def _size(pixels):
    """'width x height' of an image array."""
    return f"{pixels.shape[1]} x {pixels.shape[0]}"


# ------------------------------------------------------------------------------------------
# Several figures, and the comparison sheet
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class MissingReference:
    """A figure without a reference image: there is nothing to compare its image with.

    name: the figure's name; path: the reference file that does not exist; image: the
    image's 8-bit RGB pixels."""

    name: str
    path: Path
    image: np.ndarray = field(repr=False)

    @property
    def matches(self) -> bool:
        """False: without a reference nothing is known to match."""
        return False

    @property
    def summary(self) -> str:
        """One line saying that the reference is missing."""
        return (f"{self.name}: no reference image to compare with "
                f"({_shown(self.path)} is missing)")


def compare_figures(renders: Mapping[str, Image], reference_dir=REFERENCE_DIR):
    """Compares each image of `renders`, a mapping from figure names ("figure1_phong") to
    images as compare_with_reference takes them, with that figure's PNG in reference_dir.
    Returns a list in the same order: a Comparison for each figure, or a MissingReference
    where the reference file does not exist."""
    results = []
    for name, image in renders.items():
        path = Path(reference_dir) / f"{name}.png"
        if path.is_file():
            results.append(compare_with_reference(image, path))
        else:
            results.append(MissingReference(name, path, _pixels(image, "the image")))
    return results


def _shown(path):
    """A path as printed: relative to the repository when it is inside it."""
    path = Path(path).resolve()
    return path.relative_to(REPOSITORY) if path.is_relative_to(REPOSITORY) else path


# The sheet's layout, in pixels: images are drawn one pixel for each pixel, so that the
# PNG can be zoomed into; LABEL is the band above each panel for its two-line label.
DPI = 100
MARGIN, TITLE, LABEL, GAP = 20, 50, 50, 20
BAR_GAP, BAR_WIDTH, BAR_LABELS = 10, 16, 70  # the colour bar right of each heat map


def draw_sheet(comparisons: Sequence[Union[Comparison, MissingReference]]) -> Figure:
    """The comparison sheet as a matplotlib Figure: one row per comparison, with the image,
    the reference and the heat map of their difference with its colour bar, each panel
    labelled, every image drawn one pixel for each pixel. A MissingReference row shows the
    image and says that the reference is missing."""
    if not comparisons:
        raise ValueError("draw_sheet: no comparisons to draw")
    panel_width = max(c.image.shape[1] for c in comparisons)
    panel_height = max(c.image.shape[0] for c in comparisons)
    width = 2 * MARGIN + 3 * panel_width + 2 * GAP + BAR_GAP + BAR_WIDTH + BAR_LABELS
    height = TITLE + len(comparisons) * (LABEL + panel_height) + MARGIN
    sheet = Figure(figsize=(width / DPI, height / DPI), dpi=DPI)

    def axes(left, top, w, h):
        """New axes at a rectangle given in pixels from the top left corner."""
        return sheet.add_axes((left / width, 1 - (top + h) / height, w / width, h / height))

    matching = sum(c.matches for c in comparisons)
    sheet.text(MARGIN / width, 1 - MARGIN / height,
               f"Your renders beside the course's figures: {matching} of "
               f"{len(comparisons)} match", fontsize=14, va="top")
    columns = [MARGIN + i * (panel_width + GAP) for i in range(3)]
    for row, comparison in enumerate(comparisons):
        top = TITLE + row * (LABEL + panel_height) + LABEL
        h, w = comparison.image.shape[:2]
        panels = [axes(left, top, w, h) for left in columns]
        for panel in panels:
            panel.set_axis_off()
        panels[0].imshow(comparison.image, interpolation="none")
        panels[0].set_title(f"your render\n{comparison.name}", loc="left", fontsize=11)
        if isinstance(comparison, MissingReference):
            panels[1].set_title("reference\nmissing", loc="left", fontsize=11)
            panels[1].text(0, 0.5, f"no reference image:\n{_shown(comparison.path)}",
                           fontsize=11, va="center")
            panels[2].set_title("difference\nnothing to compare with", loc="left",
                                fontsize=11)
            continue
        panels[1].imshow(comparison.reference, interpolation="none")
        panels[1].set_title(f"reference\n{comparison.name}", loc="left", fontsize=11)
        verdict = ("matches" if comparison.matches
                   else f"{comparison.differing_pixels} pixels differ")
        panels[2].set_title(f"difference: {verdict}\nlargest: {comparison.max_steps}/255 "
                            f"(8-bit steps)", loc="left", fontsize=11)
        values, largest = comparison.heat_map()
        heat = panels[2].imshow(values, cmap=HEAT_MAP, vmin=0, vmax=largest,
                                interpolation="none")
        bar = sheet.colorbar(heat, cax=axes(columns[2] + w + BAR_GAP, top, BAR_WIDTH, h))
        bar.locator = MaxNLocator(integer=True)
        bar.update_ticks()
        bar.set_label("8-bit steps (1 step or less: black)")
    return sheet


def write_sheet(comparisons: Sequence[Union[Comparison, MissingReference]], path) -> Path:
    """Draws the comparison sheet (see draw_sheet) and writes it as a PNG; returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    draw_sheet(comparisons).savefig(path, dpi=DPI)
    return path
