"""The checks of Practice 1: each step of Assignment 1 rendered small with your own code
and compared with the image that the finished framework renders.

`python -m pytest` runs them from the folder of AppRenderer.py (tests/test_practice1.py
holds one test per check, named after its assignment step). Each check builds the
course's scenes itself, renders them at SIZE x SIZE pixels with your integrators and your
render() loop, and compares the linear image (scene.rendered_image, what save_image writes
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
import traceback
from dataclasses import dataclass, field
from math import sqrt
from pathlib import Path

import numpy as np
from matplotlib.image import imsave

SIZE = 40  # pixels, width and height of every image checked
PROJECT = Path(__file__).resolve().parent.parent  # the folder of AppRenderer.py
EXPECTED = Path(__file__).resolve().parent / "expected" / "practice1.npz"
OUT = PROJECT / "out" / "checks"
STUDENT_FILES = ("PyRT_Common.py", "PyRT_Core.py", "PyRT_Integrators.py", "AppRenderer.py")

ABSOLUTE_TOLERANCE = 1e-9
RELATIVE_TOLERANCE = 1e-6
SEAM_WIDTH = 1e-7  # pixels: how far from a seam pixel's centre its alternative rays go
SEAM_TOLERANCE = 1e-3  # relative: a colour this far from the expected one is another answer
MISTAKE_SHARE = 1 / 20  # an image is taken for a known mistake when it differs at most here
PNG_SCALE = 8  # the PNGs of a check show each pixel as a PNG_SCALE x PNG_SCALE square
SHOWN_PIXELS = 3  # differing pixels listed in a message


# ------------------------------------------------------------------------------------------
# What is checked
# ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Image:
    """One image of the checks: the step it belongs to, what it shows, its scene and the
    integrator (a class name of PyRT_Integrators, with its extra arguments) that renders
    it. The "probe" image has no integrator of the course: RayProbe renders it."""

    step: str
    title: str
    scene: str
    integrator: str
    arguments: tuple = ()


IMAGES = {
    "lazy": Image("1.1", "the Lazy image (Figure 2)", "sphere", "LazyIntegrator"),
    "probe": Image("1.2", "the rays that render() traces", "sphere", "RayProbe"),
    "intersection": Image("1.2", "the Intersection image (Figure 3)", "sphere",
                          "IntersectionIntegrator"),
    "depth": Image("1.3", "the Depth image, max_depth 5 (Figure 4)", "sphere",
                   "DepthIntegrator", (5,)),
    "normal": Image("1.3", "the Normal image (Figure 4)", "sphere", "NormalIntegrator"),
    "phong_sphere": Image("1.4", "the Phong image of the sphere scene (Figure 5)", "sphere",
                          "PhongIntegrator"),
    "phong_cornell": Image("1.4", "the Phong image of the Cornell box (Figure 1)", "cornell",
                           "PhongIntegrator"),
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
    "phong_sphere": ("no_ambient", "no_shadows", "no_inverse_square"),
    "phong_cornell": ("no_ambient", "no_shadows", "no_inverse_square"),
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
                       "larger of it and 0",
    "unmapped_normals": "the normals are not mapped to [0, 1]: the colour is the normal "
                        "itself, whose components lie in [-1, 1], where the formula is "
                        "(n + (1, 1, 1)) / 2",
    "no_ambient": "the ambient term, kd (x) i_a, is missing",
    "no_shadows": "there are no shadows: every light counts, even when an object lies "
                  "between the point and the light (a shadow ray and scene.any_hit tell)",
    "no_inverse_square": "the light's contribution is not divided by r^2, the squared "
                         "distance from the point to the light",
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


# ------------------------------------------------------------------------------------------
# Running a check
# ------------------------------------------------------------------------------------------
def run_check(name, out=OUT):
    """The Check called `name` (any_hit or a name of IMAGES), run on the student's modules;
    its PNGs go into out/<name>/. Errors of the student's code become the check's verdict."""
    check = Check(name, step_of(name), title(name))
    folder = Path(out) / name
    try:
        if name == "any_hit":
            return _check_any_hit(check)
        return _check_image(check, folder)
    except KeyboardInterrupt:
        raise
    except BaseException as error:  # SystemExit too: the student's code called sys.exit
        check.error = student_traceback(error)
        return check.fail(_error_reason(error))


def run_step(step, out=OUT):
    """The Checks of an assignment step ("1.1" to "1.4"), in order."""
    return [run_check(name, out) for name in STEPS[step]]


def _error_reason(error):
    if isinstance(error, SystemExit):
        return f"your code called sys.exit({error.code!r}), which ends the program"
    if isinstance(error, MemoryError):
        return "your code ran out of memory"
    if isinstance(error, SyntaxError):
        where = f"{Path(error.filename or '?').name}, line {error.lineno}"
        return f"{where} is not valid Python: {error.msg}"
    reason = f"your code raised {type(error).__name__}: {error}"
    if "None" in str(error):
        reason += (" (a compute_color that still is the handout's `pass` returns None, "
                   "where an RGBColor is needed)")
    return reason


def student_traceback(error):
    """The lines of the error's traceback that lie in the student's files (the four
    course modules beside tests/), each file named as in the student's folder, then the
    error itself."""
    frames = [traceback.FrameSummary(Path(frame.filename).name, frame.lineno, frame.name,
                                     line=frame.line)
              for frame in traceback.extract_tb(error.__traceback__)
              if Path(frame.filename).name in STUDENT_FILES
              and Path(frame.filename).resolve().parent == PROJECT]
    lines = traceback.format_list(frames)
    if isinstance(error, SyntaxError) and error.text:
        lines.append(f'  File "{Path(error.filename or "?").name}", line {error.lineno}\n'
                     f"    {error.text.strip()}\n")
    return "".join(lines) + "".join(traceback.format_exception_only(type(error), error))


def course_modules():
    """The student's PyRT_Common, PyRT_Core and PyRT_Integrators, imported."""
    import PyRT_Common
    import PyRT_Core
    import PyRT_Integrators
    return PyRT_Common, PyRT_Core, PyRT_Integrators


# ------------------------------------------------------------------------------------------
# The scenes, built through the course's API
# ------------------------------------------------------------------------------------------
def sphere_scene(size=SIZE):
    """The sphere scene of Figures 2 to 5: a grey sphere above a green floor, one light."""
    common, core, _ = course_modules()
    Vector3D, RGBColor = common.Vector3D, common.RGBColor
    scene = core.Scene()
    scene.set_ambient(RGBColor(0.5, 0.5, 0.5))
    sphere = core.Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    sphere.set_BRDF(core.Lambertian(RGBColor(0.8, 0.8, 0.8)))
    scene.add_object(sphere)
    floor = core.Parallelogram(Vector3D(-4.0, -2.0, -1.0), Vector3D(8.0, 0.0, 0.0),
                               Vector3D(0.0, 0.0, -8.0))
    floor.set_BRDF(core.Lambertian(RGBColor(0.2, 0.8, 0.2)))
    scene.add_object(floor)
    scene.add_point_light_sources(core.PointLight(Vector3D(0.0, 5.0, 0.0),
                                                  RGBColor(80.0, 80.0, 80.0)))
    scene.set_camera(core.Camera(size, size, 60))
    return scene


def cornell_box(size=SIZE, dist=0.75, side=2.0):
    """The Cornell box of Figure 1: a blue sphere in a white box with a red left wall and a
    green right wall, three lights under the ceiling."""
    common, core, _ = course_modules()
    Vector3D, RGBColor = common.Vector3D, common.RGBColor
    scene = core.Scene()
    scene.set_ambient(RGBColor(1.0, 1.0, 0.3))
    white = RGBColor(0.8, 0.8, 0.8)
    z_far = -(dist + side)
    ll = Vector3D(-side / 2, -side / 2, z_far)
    ur = Vector3D(side / 2, side / 2, z_far)
    objects = [
        (core.Sphere(Vector3D(0.0, 0.0, -(dist + side / 2)), 0.25), RGBColor(0.2, 0.2, 0.7)),
        (core.Parallelogram(ll, Vector3D(side, 0, 0), Vector3D(0, side, 0)), white),
        (core.Parallelogram(ll, Vector3D(side, 0, 0), Vector3D(0, 0, side)), white),
        (core.Parallelogram(ll, Vector3D(0, side, 0), Vector3D(0, 0, side)),
         RGBColor(0.7, 0.2, 0.2)),
        (core.Parallelogram(ur, Vector3D(-side, 0, 0), Vector3D(0, 0, side)), white),
        (core.Parallelogram(ur, Vector3D(0, -side, 0), Vector3D(0, 0, side)),
         RGBColor(0.2, 0.7, 0.2)),
    ]
    for obj, colour in objects:
        obj.set_BRDF(core.Lambertian(colour))
        scene.add_object(obj)
    for x in (0.0, -side / 4, side / 4):
        scene.add_point_light_sources(core.PointLight(
            Vector3D(x, side / 2 - 0.5, -(dist + side / 2)), RGBColor(0.5, 0.5, 0.5)))
    scene.set_camera(core.Camera(size, size, 70))
    return scene


SCENES = {"sphere": sphere_scene, "cornell": cornell_box}


def ray_probe(integrators):
    """A subclass of integrators.Integrator (so with its render()) that colours each pixel
    by the ray render() hands to compute_color: its unit direction d as (d + 1) / 2, or
    (-1, -1, -1) when the ray does not start at the camera, (0, 0, 0)."""
    RGBColor = course_modules()[0].RGBColor

    class RayProbe(integrators.Integrator):
        def __init__(self, filename_):
            super().__init__(filename_ + "_RayProbe")

        def compute_color(self, ray):
            if components(ray.o) != (0.0, 0.0, 0.0):
                return RGBColor(-1.0, -1.0, -1.0)
            x, y, z = components(ray.d)
            length = sqrt(x * x + y * y + z * z)
            return RGBColor((x / length + 1) / 2, (y / length + 1) / 2, (z / length + 1) / 2)

    return RayProbe


def components(vector):
    """(x, y, z) of a Vector3D, or of a numpy array of three numbers: the 2021-22 base
    code's Ray() starts with arrays for its origin and direction."""
    if hasattr(vector, "x"):
        return float(vector.x), float(vector.y), float(vector.z)
    x, y, z = (float(value) for value in vector)
    return x, y, z


def make_integrator(name, filename, integrators):
    """The integrator of IMAGES[name], from the module `integrators`."""
    image = IMAGES[name]
    if image.integrator == "RayProbe":
        return ray_probe(integrators)(filename)
    return getattr(integrators, image.integrator)(filename, *image.arguments)


def traced_image(integrator, scene, offset=(0.0, 0.0)):
    """The image of integrator.compute_color for a ray from the camera through each
    pixel's centre moved by offset = (dx, dy) pixels, traced here, one pixel at a time,
    instead of by the integrator's render()."""
    common = course_modules()[0]
    integrator.add_scene(scene)
    camera = scene.camera
    image = np.zeros((camera.height, camera.width, 3))
    dx, dy = offset
    for y in range(camera.height):
        for x in range(camera.width):
            direction = camera.get_direction(x + dx, y + dy)
            color = integrator.compute_color(common.Ray(common.Vector3D(0.0, 0.0, 0.0),
                                                        direction))
            image[y, x] = (color.r, color.g, color.b)
    return image


def judge_compute_color(integrator, name, data):
    """The Verdict on the image of IMAGES[name] traced by traced_image with the student's
    compute_color on a fresh scene; None when that cannot be traced (compute_color
    raises or returns something else than a colour)."""
    try:
        image = traced_image(integrator, SCENES[IMAGES[name].scene]())
    except Exception:  # the student's render() was judged; this only looks further
        return None
    return judge(image, name, data)


def render(integrator, scene):
    """Renders scene with the integrator's own render() and returns a copy of the linear
    image."""
    integrator.add_scene(scene)
    integrator.render()
    return np.array(scene.rendered_image, dtype=float)


# ------------------------------------------------------------------------------------------
# The checks
# ------------------------------------------------------------------------------------------
def _check_any_hit(check):
    common, core, _ = course_modules()
    Vector3D = common.Vector3D
    origin, ahead = Vector3D(0.0, 0.0, 0.0), Vector3D(0.0, 0.0, -1.0)

    def scene_of(*centres):
        scene = core.Scene()
        for centre in centres:
            scene.add_object(core.Sphere(Vector3D(*centre), 1.0))
        return scene

    def ray(direction=ahead, t_min=None, t_max=None):
        r = common.Ray(Vector3D(origin.x, origin.y, origin.z),
                       Vector3D(direction.x, direction.y, direction.z))
        if t_min is not None:
            r.t_min = t_min
        if t_max is not None:
            r.t_max = t_max
        return r

    one, two = (0.0, 0.0, -5.0), (3.0, 0.0, -5.0)  # unit spheres; the ray ahead misses two
    cases = [
        ("a ray from the camera straight at a sphere 4 to 6 away", scene_of(one), ray(), True),
        ("a ray pointing away from every object", scene_of(one),
         ray(Vector3D(0.0, 0.0, 1.0)), False),
        ("a ray towards the sphere with t_max 3, ending before it", scene_of(one),
         ray(t_max=3.0), False),
        ("a ray towards the sphere with t_min 7, starting beyond it", scene_of(one),
         ray(t_min=7.0), False),
        ("a ray towards the sphere with t_min 5, which meets its far side at 6",
         scene_of(one), ray(t_min=5.0), True),
        ("a ray that misses the first object of object_list and hits the second",
         scene_of(two, one), ray(), True),
    ]
    wrong = []  # (description, the right answer)
    for description, scene, case_ray, expected in cases:
        answer = scene.any_hit(case_ray)
        if not isinstance(answer, (bool, np.bool_)):
            return check.fail(f"any_hit returned {answer!r} for {description}; it must "
                              "return True or False")
        if answer != expected:
            wrong.append((description, expected))
    if not wrong:
        return check.succeed()
    reason = f"any_hit is wrong for {len(wrong)} of {len(cases)} rays"
    if [case for case in cases if case[3]] == [case for case in cases if (case[0], True)
                                               in wrong]:
        reason += " (it answers False for every ray that hits, as the handout's any_hit does)"
    return check.fail(reason, "\n".join(
        f"  {description}: any_hit answered {not expected}, the right answer is {expected}"
        for description, expected in wrong))


def _check_image(check, folder):
    common, core, integrators = course_modules()
    image_info = IMAGES[check.name]
    # The course's save_image writes into the folder it is given and creates none
    folder.mkdir(parents=True, exist_ok=True)
    scene = SCENES[image_info.scene]()
    integrator = make_integrator(check.name, str(folder / "render"), integrators)
    if image_info.integrator not in ("LazyIntegrator", "RayProbe"):
        integrator.add_scene(scene)
        color = integrator.compute_color(common.Ray(common.Vector3D(0.0, 0.0, 0.0),
                                                    common.Vector3D(0.0, 0.0, -1.0)))
        if not all(hasattr(color, channel) for channel in "rgb"):
            stub = " (the handout's `pass` returns None)" if color is None else ""
            return check.fail(f"{image_info.integrator}.compute_color returned {color!r}"
                              f"{stub} for a ray from the camera straight at the sphere; it "
                              "must return an RGBColor")
    image = render(integrator, scene)
    data = expected_data()
    verdict = judge(image, check.name, data)
    if verdict.right:
        return check.succeed(verdict.note)
    reason = verdict.reason
    if image_info.integrator not in ("LazyIntegrator", "RayProbe"):
        # A mistake of render() shows in every image it makes, but the check of its rays
        # (Assignment 1.2) is where it counts: here compute_color is judged on its own
        own_rays = judge_compute_color(integrator, check.name, data)
        if own_rays is not None and own_rays.right:
            return check.succeed(
                "compute_color is right: the image that your render() makes differs ("
                + reason + "), which the check of render()'s rays in Assignment 1.2 "
                "counts, not this one" + (f"; {own_rays.note}" if own_rays.note else ""))
    if check.name == "lazy" and not np.any(image):
        # LazyIntegrator.compute_color returns BLACK: once render() asks compute_color
        # (Assignment 1.2), the Lazy image is black, and 1.1 lives on in 1.2's loop
        probe = run_check("probe", folder.parent / "lazy_loop")
        if probe.passed:
            return check.succeed("LazyIntegrator renders black because render() now asks "
                                 "compute_color, as Assignment 1.2 asks; its loop is the "
                                 "loop of 1.1, finished")
        reason = ("the image is black, which is right once render() asks compute_color "
                  "(Assignment 1.2), but render() fails the check of its rays: "
                  + probe.reason)
    check.images = write_pngs(folder, image, data[check.name], verdict.wrong)
    if image_info.integrator not in ("LazyIntegrator", "RayProbe"):  # no rays of their own
        tell_first_wrong_pixel(check, integrator, verdict.wrong, data[check.name])
    return check.fail(reason, verdict.details)


def tell_first_wrong_pixel(check, integrator, wrong, expected):
    """Sets check.story to the history of the first wrong pixel (in reading order) as the
    student's integrator tells it, with the colour expected there. A story that cannot be
    told (no pyrt/explain.py beside the modules, a scene it cannot read) is left out: it
    never changes the verdict."""
    y, x = (int(i) for i in np.argwhere(wrong)[0])
    try:
        from pyrt.explain import explain_pixel
        history = explain_pixel(integrator, x, y)
    except Exception:
        return
    check.story_pixel = (x, y)
    check.story = (f"Pixel ({x}, {y}) is the first that differs; the expected colour there "
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
    for (y, x), colours in zip(data[f"{name}.seam_pixels"], data[f"{name}.seam_colors"]):
        if not right[y, x]:
            right[y, x] = bool(close(np.broadcast_to(image[y, x], colours.shape)[None],
                                     colours[None], SEAM_TOLERANCE).any())
    return right


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
