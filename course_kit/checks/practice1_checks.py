"""The checks of Practice 1: each step of Assignment 1 rendered small with your own code
and compared with the image that the finished framework renders.

`python -m pytest` runs them from the folder of AppRenderer.py (tests/test_practice1.py
holds one test per check, named after its assignment step). Each check builds the
course's scenes itself, renders them at 40 x 40 pixels with your integrators and your
render() loop (practice1_render.py, which keeps what your code makes as plain data), and
this module judges it: it compares the linear image (scene.rendered_image, what save_image writes
to the .npy file) with the expected one in tests/expected/practice1.npz.

The rule for a correct image: every channel of every pixel equals the expected value to
within ABSOLUTE_TOLERANCE + RELATIVE_TOLERANCE x |expected value| (the same colour
computed in another order differs in its last digits), except on the seams: the pixels
whose centre lies within SEAM_WIDTH of a pixel of an edge, where two surfaces (or a
surface and the background, or light and shadow) meet. A ray there may hit either side,
so such a pixel may also take any of the colours that the rays around its centre see, or
that the course's own arithmetic gives its ray (course_kit/arithmetic.py), with any of the
shadow rays students write: the crack between two walls that lets a ray through to the
background included.

The course tells you to check an image by comparing it with its figure, and the course's
save_image shows an image through its tonemapper, which maps the image's smallest value
to 0 and its largest to 1. So an image that differs from the expected one only by such a
scale and shift (a red of RGBColor(255, 0, 0) instead of RGBColor(1, 0, 0)) makes the
figure's PNG and is right; the check then adds a note saying what differs.

When an image differs, the check says how many pixels differ and where, writes your image,
the expected one and their difference into out/checks/<check>/, names the mistake when
it recognises it, and tells the history of the first pixel that differs: every question
your compute_color asked the scene there, and the answers (pyrt/explain.py).
"""
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from matplotlib.image import imsave

import practice1_render as render

PROJECT = Path(__file__).resolve().parent.parent  # the folder of AppRenderer.py
EXPECTED = Path(__file__).resolve().parent / "expected" / "practice1.npz"
OUT = PROJECT / "out" / "checks"

ABSOLUTE_TOLERANCE = 1e-9
RELATIVE_TOLERANCE = 1e-6
SEAM_WIDTH = 1e-7  # pixels: how far from a seam pixel's centre its alternative rays go
SEAM_TOLERANCE = 1e-3  # relative: a colour this far from the expected one is another answer
MISTAKE_SHARE = 1 / 20  # an image is taken for a known mistake when it differs at most here
PNG_SCALE = 8  # the PNGs of a check show each pixel as a PNG_SCALE x PNG_SCALE square
SHOWN_PIXELS = 3  # differing pixels listed in a message
# A light's falloff is fitted from pixels whose distance to the light differs from 1 by
# this much in log, at least this many of them, and taken when nine in ten of their
# exponents lie within FALLOFF_SPREAD
FALLOFF_MIN_LOG_R = 0.05
FALLOFF_MIN_PIXELS = 20
FALLOFF_SPREAD = 0.1


# ------------------------------------------------------------------------------------------
# What is checked
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Image:
    """One image of the checks: the step it belongs to and what it shows
    (practice1_render.RENDERED says how it is rendered)."""

    step: str
    title: str


IMAGES = {
    "lazy": Image("1.1", "the Lazy image (Figure 2)"),
    "probe": Image("1.2", "the rays that render() traces"),
    "intersection": Image("1.2", "the Intersection image (Figure 3)"),
    "depth": Image("1.3", "the Depth image, max_depth 5 (Figure 4)"),
    "normal": Image("1.3", "the Normal image (Figure 4)"),
    "phong_sphere": Image("1.4", "the Phong image of the sphere scene (Figure 5)"),
    "phong_cornell": Image("1.4", "the Phong image of the Cornell box (Figure 1)"),
}
# The checks of each step, in order: the names of IMAGES, and "any_hit"
STEPS = {
    "1.1": ("lazy",),
    "1.2": ("any_hit", "probe", "intersection"),
    "1.3": ("depth", "normal"),
    "1.4": ("phong_sphere", "phong_cornell"),
}
# The mistakes whose images course_kit/references.py renders with the finished framework for
# the expected data, by image; every ray-traced image also has "corner_rays"
RENDERED_MISTAKES = {
    "depth": ("unclamped_depth",),
    "normal": ("unmapped_normals",),
    "phong_sphere": ("no_ambient", "no_shadows", "no_inverse_square", "inverse_distance"),
    "phong_cornell": ("no_ambient", "no_shadows", "no_inverse_square", "inverse_distance"),
}
LIKELY = {
    "green": "every pixel is GREEN: render() still paints the handout's GREEN. Assignment "
             "1.1 asks it to colour pixel (x, y) with (x/width, y/height, 0), and 1.2 with "
             "compute_color of the ray through the pixel's centre",
    "lazy_loop": "render() still paints the colours of Assignment 1.1, (x/width, y/height, "
                 "0), instead of asking compute_color for the colour of the ray through "
                 "each pixel (Assignment 1.2)",
    "not_from_camera": "some rays do not start at the camera, (0, 0, 0), where every "
                       "camera ray starts",
    "upside_down": "the image is upside down: y counts the rows from the top of the image, "
                   "while the camera's +y points up",
    "mirrored": "the image is mirrored, left and right swapped",
    "transposed": "the image is transposed, x and y swapped: set_pixel(color, x, y) takes "
                  "the column x first, then the row y",
    "corner_rays": "the rays go through the top-left corners of the pixels instead of their "
                   "centres: camera.get_direction(x, y) gives the direction through the "
                   "centre of pixel (x, y)",
    "unclamped_depth": "the depth is not clamped at 0: beyond max_depth the grey "
                       "1 - hit_distance / max_depth is negative, and the formula takes the "
                       "larger of it and 0 (for a ray that hits nothing, hit_distance is "
                       "HUGEVALUE or infinite, so its grey is far below 0 unless clamped "
                       "or coloured BLACK)",
    "unmapped_normals": "the normals are not mapped to [0, 1]: the colour is the normal "
                        "itself, whose components lie in [-1, 1], where the formula is "
                        "(n + (1, 1, 1)) / 2",
    "no_ambient": "the ambient term, kd (x) i_a, is missing",
    "no_shadows": "there are no shadows: every light counts, even when an object lies "
                  "between the point and the light (a shadow ray and scene.any_hit tell)",
    "no_inverse_square": "the light's contribution is not divided by r^2, the squared "
                         "distance from the point to the light",
    "inverse_distance": "the light's contribution is divided by r, the distance from the "
                        "point to the light, where the falloff is 1/r^2: divide by r * r",
}
BLACK_HINTS = {
    "lazy": "the image is black: LazyIntegrator.compute_color returns BLACK, so in "
            "Assignment 1.1 render() computes the colour of each pixel itself",
    "probe": "the image is black: render() gives the pixels no colour of compute_color",
    "intersection": "the image is black: any_hit answers False for every camera ray, or "
                    "compute_color never returns RED",
}
BLACK_HINT = "the image is black: compute_color returns BLACK for every ray"


@dataclass
class Check:
    """The verdict of one check: passed or not, a one-line reason when not, a note when
    it passed with something worth knowing, the message for the student, the error and
    the student's own traceback lines when their code raised, the PNGs written (render,
    expected, difference), and for a wrong image the story of its first wrong pixel,
    story_pixel (x, y), as the student's code tells it."""

    name: str
    step: str
    title: str
    passed: bool = False
    reason: str = ""
    note: str = ""
    message: str = ""
    error: str = ""
    images: dict = field(default_factory=dict)
    story: str = ""
    story_pixel: tuple = ()

    def fail(self, reason, details=""):
        self.passed, self.reason = False, reason
        self.message = f"Assignment {self.step}, {self.title}: {reason}" + (
            f"\n{details}" if details else "")
        return self

    def succeed(self, note=""):
        self.passed, self.reason, self.note = True, "", note
        self.message = f"Assignment {self.step}, {self.title}: right" + (
            f" ({note})" if note else "")
        return self

    def report(self):
        """All the student needs to know: the message, the error, the PNGs' paths."""
        parts = [self.message]
        if self.error:
            parts.append("The error, with the lines of your code it passed through:\n"
                         + self.error.rstrip("\n"))
        if self.images:
            parts.append("  images: " + ", ".join(str(path) for path in self.images.values()))
        if self.story:
            parts.append(self.story)
        return "\n".join(parts)



def title(name):
    return "any_hit, tested on its own" if name == "any_hit" else IMAGES[name].title


def step_of(name):
    return "1.2" if name == "any_hit" else IMAGES[name].step


def ray_traced(name):
    """Whether the image `name` is one of an integrator that traces rays (the Lazy image
    and the probe's have no rays of the course's)."""
    return name not in ("lazy", "probe")


# ------------------------------------------------------------------------------------------
# Running a check: your code renders (practice1_render.py), then the check judges
# ------------------------------------------------------------------------------------------
def run_check(name, out=OUT):
    """The Check called `name` (any_hit or a name of IMAGES), run on the student's modules
    with the published draw; its PNGs go into out/<name>/."""
    data = expected_data()
    rendered = render.collect(name, render.PUBLISHED, out)
    probe = render.collect("probe", render.PUBLISHED, Path(out) / "lazy_loop") if (
        name == "lazy" and "image" in rendered.arrays
        and not np.any(rendered.arrays["image"])) else None
    check = judge_rendered(rendered, data, render.PUBLISHED_CASES, Path(out) / name, probe)
    if check.story_pixel:
        check.story = story(check, data[name], render.pixel_history(
            name, render.PUBLISHED, *check.story_pixel))
    return check


def run_step(step, out=OUT):
    """The Checks of an assignment step ("1.1" to "1.4"), in order."""
    return [run_check(name, out) for name in STEPS[step]]


def error_reason(error):
    """The one-line reason of a check whose code raised error (practice1_render's
    describe_error)."""
    if error["kind"] == "SystemExit":
        return f"your code called sys.exit({error.get('code', 'None')}), which ends the program"
    if error["kind"] == "MemoryError":
        return "your code ran out of memory"
    if error["kind"] == "SyntaxError":
        return (f"{error.get('file', '?')}, line {error.get('line', '?')} is not valid "
                f"Python: {error['text']}")
    reason = f"your code raised {error['type']}: {error['text']}"
    if "None" in error["text"]:
        reason += (" (a compute_color that still is the handout's `pass` returns None, "
                   "where an RGBColor is needed)")
    return reason


def judge_rendered(rendered, data, cases, folder, probe=None):
    """The Check of what the student's code made for one check (a practice1_render
    Rendered), judged against data, the expected data of its draw, and cases, the draw's
    any_hit cases with their right answers. Its PNGs go into folder;
    probe: the Rendered of the ray probe, for a black Lazy image. A wrong image gets
    story_pixel, the first wrong pixel, whose story is told by another run of the
    student's code."""
    check = Check(rendered.name, step_of(rendered.name), title(rendered.name))
    if rendered.error is not None:
        check.error = rendered.error["traceback"]
        return check.fail(error_reason(rendered.error))
    if rendered.name == "any_hit":
        return _judge_any_hit(check, rendered, cases)
    if rendered.first_color is not None:
        stub = " (the handout's `pass` returns None)" if rendered.first_color == "None" else ""
        return check.fail(f"{render.RENDERED[rendered.name][1]}.compute_color returned "
                          f"{rendered.first_color}{stub} for a ray from the camera straight "
                          "at the sphere; it must return an RGBColor")
    if "image" not in rendered.arrays:
        return check.fail("no image came back from render()")
    image = rendered.arrays["image"]
    verdict = judge(image, check.name, data)
    if verdict.right:
        return check.succeed(verdict.note)
    reason = verdict.reason
    if ray_traced(check.name) and "traced" in rendered.arrays:
        # A mistake of render() shows in every image it makes, but the check of its rays
        # (Assignment 1.2) is where it counts: here compute_color is judged on its own
        own_rays = judge(rendered.arrays["traced"], check.name, data)
        if own_rays.right:
            return check.succeed(
                "compute_color is right: the image that your render() makes differs ("
                + reason + "), which the check of render()'s rays in Assignment 1.2 "
                "counts, not this one" + (f"; {own_rays.note}" if own_rays.note else ""))
    if check.name == "lazy" and not np.any(image) and probe is not None:
        # LazyIntegrator.compute_color returns BLACK: once render() asks compute_color
        # (Assignment 1.2), the Lazy image is black, and 1.1 lives on in 1.2's loop
        loop = judge_rendered(probe, data, cases, folder.parent / "lazy_loop")
        if loop.passed:
            return check.succeed("LazyIntegrator renders black because render() now asks "
                                 "compute_color, as Assignment 1.2 asks; its loop is the "
                                 "loop of 1.1, finished")
        reason = ("the image is black, which is right once render() asks compute_color "
                  "(Assignment 1.2), but render() fails the check of its rays: "
                  + loop.reason)
    check.images = write_pngs(folder, image, data[check.name], verdict.wrong)
    if ray_traced(check.name):
        y, x = (int(i) for i in np.argwhere(verdict.wrong)[0])
        check.story_pixel = (x, y)
    return check.fail(reason, verdict.details)


def _judge_any_hit(check, rendered, cases):
    answers = [int(answer) for answer in rendered.arrays.get("answers", ())]
    if rendered.not_bool is not None:
        description, _, _ = cases[max(0, min(len(answers), len(cases)) - 1)]
        return check.fail(f"{rendered.not_bool} for {description}; it must return "
                          "True or False")
    if len(answers) != len(cases):
        return check.fail(f"any_hit gave {len(answers)} answers to {len(cases)} rays")
    wrong = [(description, right) for (description, _, right), answer
             in zip(cases, answers) if bool(answer) != right]
    if not wrong:
        return check.succeed()
    reason = f"any_hit is wrong for {len(wrong)} of {len(cases)} rays"
    if [case for case, _, right in cases if right] == [case for case, right in wrong if right]:
        reason += " (it answers False for every ray that hits, as the handout's any_hit does)"
    return check.fail(reason, "\n".join(
        f"  {description}: any_hit answered {not right}, the right answer is {right}"
        for description, right in wrong))


def story(check, expected, history):
    """The story of check's first wrong pixel: the colour expected there, then history,
    what the student's code asked and was answered there ("" when it could not be told)."""
    if not history:
        return ""
    x, y = check.story_pixel
    return (f"Pixel ({x}, {y}) is the first that differs; the expected colour there "
            f"is {_rgb(expected[y, x])}. What your code asked and was answered:\n"
            f"{history}")


# ------------------------------------------------------------------------------------------
# Comparing images
# ------------------------------------------------------------------------------------------
def expected_data():
    """The expected images and what goes with them (see course_kit/references.py), as a
    dict of arrays."""
    with np.load(EXPECTED) as data:
        return {key: data[key] for key in data.files}


def close(image, expected, relative=RELATIVE_TOLERANCE):
    """Per pixel: whether every channel of image equals expected within the tolerance."""
    return np.all(np.abs(image - expected)
                  <= ABSOLUTE_TOLERANCE + relative * np.abs(expected), axis=2)


def right_pixels(image, name, data):
    """Per pixel: whether image is right there, by the rule of this module's docstring."""
    right = close(image, data[name])
    if right.all():
        return right
    for (y, x), colours in seams_among(data, name, ~right):
        right[y, x] = bool(close(np.broadcast_to(image[y, x], colours.shape)[None],
                                 colours[None], SEAM_TOLERANCE).any())
    return right


def seams_among(data, name, pixels):
    """[((y, x), the colours its rays may see)] of the seam pixels of the image `name`
    where the mask `pixels` is True: from data's seams_at where it has one (the grader's
    expected data, made at grading time, works them out when asked), else stored."""
    if hasattr(data, "seams_at"):
        return data.seams_at(name, pixels)
    return [((y, x), colours) for (y, x), colours
            in zip(data[f"{name}.seam_pixels"], data[f"{name}.seam_colors"])
            if pixels[y, x]]


@dataclass
class Verdict:
    """How an image compares with the expected one: right or not; if right, a note when it
    differs in what the course's tonemapper removes; if not, which pixels are wrong, a
    one-line reason and the details for the student."""

    right: bool
    wrong: np.ndarray = None
    reason: str = ""
    details: str = ""
    note: str = ""


def judge(image, name, data):
    """The Verdict on image, rendered for IMAGES[name]."""
    expected = data[name]
    if image.shape != expected.shape:
        return Verdict(False, np.ones(expected.shape[:2], bool),
                       f"the image is {image.shape[1]} x {image.shape[0]} pixels, expected "
                       f"{expected.shape[1]} x {expected.shape[0]}")
    wrong = ~right_pixels(image, name, data)
    count = int(wrong.sum())
    if count == 0:
        return Verdict(True)
    note = same_after_tonemapping(image, name, data)
    if note:
        return Verdict(True, note=note)
    ys, xs = np.nonzero(wrong)
    shown = "; ".join(f"({x}, {y}) is {_rgb(image[y, x])}, expected {_rgb(expected[y, x])}"
                      for y, x in list(zip(ys, xs))[:SHOWN_PIXELS])
    reason = f"{count} of {wrong.size} pixels differ from the expected image"
    mistake = likely_mistake(image, name, data)
    if mistake:
        reason += f"; likely mistake: {mistake}"
    details = (f"  where: x {xs.min()} to {xs.max()}, y {ys.min()} to {ys.max()} (x to the "
               f"right, y down, from 0); first: {shown}")
    return Verdict(False, wrong, reason, details)


def same_after_tonemapping(image, name, data):
    """A note saying how image differs from the expected one, when it differs only in what
    the course's tonemapper removes: image = scale * expected + shift for one scale > 0 and
    one shift over all pixels and channels, the tonemapper mapping both images' smallest
    value to 0 and largest to 1. None when it differs otherwise (or is the ray probe's,
    which no figure shows)."""
    expected = data[name]
    if name == "probe" or not np.all(np.isfinite(image)):
        return None
    low, high = float(image.min()), float(image.max())
    expected_low, expected_high = float(expected.min()), float(expected.max())
    if not (high > low and expected_high > expected_low):
        return None
    scale = (high - low) / (expected_high - expected_low)
    shift = low - scale * expected_low
    if not right_pixels((image - shift) / scale, name, data).all():
        return None
    if name == "intersection":
        what = f"your red is {high:.6g} where PyRT's is {expected_high:.6g}"
    elif abs(shift) <= ABSOLUTE_TOLERANCE + RELATIVE_TOLERANCE * (high - low):
        what = f"your values are {scale:.6g} times the expected ones"
    else:
        what = (f"your values are the expected ones times {scale:.6g}, plus "
                f"{shift:.6g}")
    why = ("the values themselves are radiance, which matters once later practices add "
           "images up" if name.startswith("phong") else "PyRT's colours run from 0 to 1, "
           "which matters once lights add up in Phong")
    return (f"{what}. The course's tonemapper maps an image's smallest value to 0 and its "
            f"largest to 1, so your PNG is the figure's; but {why}")


def _rgb(pixel):
    return "(" + ", ".join(f"{value:.6g}" for value in pixel) + ")"


def likely_mistake(image, name, data):
    """The text of LIKELY (or a hint for a uniform image) for the mistake that image looks
    like, or None when it looks like none of them."""
    if np.all(image == (0.0, 1.0, 0.0)):
        return LIKELY["green"]
    if not np.any(image):
        return BLACK_HINTS.get(name, BLACK_HINT)
    if name == "probe" and np.any(np.all(image == -1.0, axis=2)):
        return LIKELY["not_from_camera"]
    expected = data[name]
    if name == "depth" and unclamped_shape(image, expected):
        return LIKELY["unclamped_depth"]
    if name == "phong_sphere":
        exponent = fitted_falloff(image, name, data)
        if exponent is not None:
            return falloff_mistake(exponent)
    candidates = {"upside_down": expected[::-1], "mirrored": expected[:, ::-1],
                  "transposed": expected.transpose(1, 0, 2)}
    if name != "lazy" and "lazy" in data:
        candidates["lazy_loop"] = data["lazy"]
    prefix = f"{name}.mistake."
    candidates.update({key[len(prefix):]: data[key] for key in sorted(data)
                       if key.startswith(prefix)})
    allowed = MISTAKE_SHARE * image.shape[0] * image.shape[1]
    for mistake, candidate in candidates.items():
        if (~close(image, candidate)).sum() <= allowed:
            return LIKELY[mistake]
    return None


def fitted_falloff(image, name, data):
    """The exponent p of a Phong image of one light whose light falls off as 1/r^p, fitted
    from the image itself, when it has that shape and p is not the course's 2; else None.
    The expected data tells, per pixel, the ambient term A (expected minus the image
    without ambient), the light's part at r^2 (the image without ambient) and at r^0 (the
    image without the division, minus A), so r^2 is their ratio; where the light is
    blocked the image must be the expected one."""
    expected = data[name]
    at_r2 = data[f"{name}.mistake.no_ambient"]
    ambient = expected - at_r2
    at_r0 = data[f"{name}.mistake.no_inverse_square"] - ambient
    lit = (at_r2 > ABSOLUTE_TOLERANCE) & (at_r0 > ABSOLUTE_TOLERANCE)
    with np.errstate(divide="ignore", invalid="ignore"):
        log_r = 0.5 * np.log(at_r0 / at_r2)
        own = image - ambient
        usable = lit & (own > ABSOLUTE_TOLERANCE) & (np.abs(log_r) > FALLOFF_MIN_LOG_R)
        if usable.sum() < FALLOFF_MIN_PIXELS or not close(
                image, expected)[~lit.any(axis=2)].all():
            return None
        exponents = np.log(at_r0[usable] / own[usable]) / log_r[usable]
    low, exponent, high = np.percentile(exponents, (10, 50, 90))
    if not np.isfinite(exponent) or high - low > FALLOFF_SPREAD or abs(exponent - 2) < (
            FALLOFF_SPREAD):
        return None
    return float(exponent)


def falloff_mistake(exponent):
    """The mistake of a light falling off as 1/r^exponent, in the words of LIKELY."""
    for mistake, p in (("no_inverse_square", 0), ("inverse_distance", 1)):
        if abs(exponent - p) < FALLOFF_SPREAD:
            return LIKELY[mistake]
    return (f"the light's contribution falls off as 1/r^{exponent:.2g}, where r is the "
            "distance from the point to the light and the falloff is 1/r^2: divide by "
            "r * r")


def unclamped_shape(image, expected):
    """Whether a Depth image has the shape of a depth left unclamped, whatever a miss's
    hit_distance: right wherever the expected grey is above 0 (where the clamp changes
    nothing), and below 0 (-inf included) wherever it differs there."""
    shows = expected.max(axis=2) <= 0.0  # where the clamp decides
    wrong = ~close(image, expected)
    if not shows.any() or (wrong & ~shows).any() or not (wrong & shows).any():
        return False
    with np.errstate(invalid="ignore"):
        return bool(np.all(image[wrong & shows] < 0.0))


def write_pngs(folder, image, expected, wrong):
    """Writes the student's image, the expected one (both shown on the expected image's
    range, with the course's gamma of 2.5) and their difference (black where the image is
    right, brighter where it differs more) into folder; returns their paths."""
    folder.mkdir(parents=True, exist_ok=True)
    lo, hi = float(np.min(expected)), float(np.max(expected))

    def shown(values):
        scaled = np.clip((np.nan_to_num(values) - lo) / ((hi - lo) or 1.0), 0.0, 1.0)
        return _enlarged(scaled ** (1 / 2.5))

    difference = np.where(wrong, np.nan_to_num(np.abs(image - expected), nan=1.0,
                                               posinf=1.0).max(axis=2), 0.0)
    paths = {kind: folder / f"{kind}.png" for kind in ("render", "expected", "difference")}
    imsave(paths["render"], shown(image))
    imsave(paths["expected"], shown(expected))
    imsave(paths["difference"], _enlarged(difference), cmap="inferno", vmin=0.0,
           vmax=float(difference.max()) or 1.0)
    return paths


def _enlarged(values):
    return np.repeat(np.repeat(values, PNG_SCALE, axis=0), PNG_SCALE, axis=1)
