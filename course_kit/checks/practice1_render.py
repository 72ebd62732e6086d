"""What your code renders and answers for the checks of Practice 1, as plain data.

practice1_checks.py judges this data. Here your own modules run: each check builds the
course's scenes itself through the course's API, renders them with your integrators and
your render() loop, asks your any_hit, and keeps what comes out (images as numpy arrays,
answers, the text of an error) without judging any of it. A Draw says at what size and
where the scenes are rendered, and which any_hit cases are asked; the checks you run
yourself use PUBLISHED, the draw of the expected images in tests/expected/.
"""
import sys
import traceback
from dataclasses import dataclass, field
from math import sqrt
from pathlib import Path
from typing import NamedTuple, Tuple

import numpy as np

SIZE = 40  # pixels, width and height of every image of the published checks
STUDENT_FILES = ("PyRT_Common.py", "PyRT_Core.py", "PyRT_Integrators.py", "AppRenderer.py",
                 "AppWorkbench.py")
ERROR_TEXT = 4000  # characters of an error's text and traceback kept


class AnyHitCase(NamedTuple):
    """A question to any_hit: the centres of the unit spheres of its scene, the direction
    of its ray from the camera, and its t_min and t_max (None: the Ray's own). What it
    is and its right answer are not part of it: the code that answers never sees them."""

    centres: Tuple[Tuple[float, float, float], ...]
    direction: Tuple[float, float, float]
    t_min: object
    t_max: object


class Draw(NamedTuple):
    """The inputs of the checks: the images' size, the offset by which every object and
    light of the course's scenes is moved, and the any_hit cases."""

    size: int
    offset: Tuple[float, float, float]
    any_hit: Tuple[AnyHitCase, ...]


def any_hit_cases(distance, direction, aside):
    """The any_hit cases, each (what it is, the AnyHitCase, the right answer), around a unit sphere at `distance`
    from the camera along the unit `direction`, and a second sphere moved by the vector
    `aside` (of length 3, at right angles to direction), which the ray along direction
    misses."""
    centre = tuple(distance * d for d in direction)
    beside = tuple(c + a for c, a in zip(centre, aside))
    away = tuple(-d for d in direction)
    near, far = distance - 1.0, distance + 1.0
    return (
        (f"a ray from the camera straight at a sphere {near:.3g} to {far:.3g} away",
         AnyHitCase((centre,), direction, None, None), True),
        ("a ray pointing away from every object", AnyHitCase((centre,), away, None, None),
         False),
        (f"a ray towards the sphere with t_max {near - 1:.3g}, ending before it",
         AnyHitCase((centre,), direction, None, near - 1.0), False),
        (f"a ray towards the sphere with t_min {far + 1:.3g}, starting beyond it",
         AnyHitCase((centre,), direction, far + 1.0, None), False),
        (f"a ray towards the sphere with t_min {distance:.3g}, which meets its far side "
         f"at {far:.3g}", AnyHitCase((centre,), direction, distance, None), True),
        ("a ray that misses the first object of object_list and hits the second",
         AnyHitCase((beside, centre), direction, None, None), True),
    )


def draw_from_json(value):
    """The Draw that json.loads gives back as lists (json.dumps writes a Draw as lists)."""
    size, offset, cases = value
    return Draw(int(size), tuple(float(v) for v in offset), tuple(
        AnyHitCase(tuple(tuple(float(v) for v in c) for c in centres),
                   tuple(float(v) for v in direction), t_min, t_max)
        for centres, direction, t_min, t_max in cases))


# The published checks' inputs (the expected images in tests/expected/), with any_hit's
# right answers
PUBLISHED_CASES = (any_hit_cases(5.0, (0.0, 0.0, -1.0), (3.0, 0.0, 0.0))
                   + any_hit_cases(7.0, (0.6, 0.0, -0.8), (0.0, 3.0, 0.0)))
PUBLISHED = Draw(SIZE, (0.0, 0.0, 0.0), tuple(case for _, case, _ in PUBLISHED_CASES))


# ------------------------------------------------------------------------------------------
# The student's modules and the course's scenes, built through the course's API
# ------------------------------------------------------------------------------------------
def course_modules():
    """The student's PyRT_Common, PyRT_Core and PyRT_Integrators, imported."""
    import PyRT_Common
    import PyRT_Core
    import PyRT_Integrators
    return PyRT_Common, PyRT_Core, PyRT_Integrators


def sphere_scene(size=SIZE, offset=(0.0, 0.0, 0.0)):
    """The sphere scene of Figures 2 to 5: a grey sphere above a green floor, one light;
    every position moved by offset."""
    common, core, _ = course_modules()
    RGBColor = common.RGBColor

    def at(x, y, z):
        return common.Vector3D(x + offset[0], y + offset[1], z + offset[2])

    scene = core.Scene()
    scene.set_ambient(RGBColor(0.5, 0.5, 0.5))
    sphere = core.Sphere(at(0.0, 0.0, -5.0), 2.0)
    sphere.set_BRDF(core.Lambertian(RGBColor(0.8, 0.8, 0.8)))
    scene.add_object(sphere)
    floor = core.Parallelogram(at(-4.0, -2.0, -1.0), common.Vector3D(8.0, 0.0, 0.0),
                               common.Vector3D(0.0, 0.0, -8.0))
    floor.set_BRDF(core.Lambertian(RGBColor(0.2, 0.8, 0.2)))
    scene.add_object(floor)
    scene.add_point_light_sources(core.PointLight(at(0.0, 5.0, 0.0),
                                                  RGBColor(80.0, 80.0, 80.0)))
    scene.set_camera(core.Camera(size, size, 60))
    return scene


def cornell_box(size=SIZE, offset=(0.0, 0.0, 0.0), dist=0.75, side=2.0):
    """The Cornell box of Figure 1: a blue sphere in a white box with a red left wall and a
    green right wall, three lights under the ceiling; every position moved by offset."""
    common, core, _ = course_modules()
    Vector3D, RGBColor = common.Vector3D, common.RGBColor

    def at(x, y, z):
        return Vector3D(x + offset[0], y + offset[1], z + offset[2])

    scene = core.Scene()
    scene.set_ambient(RGBColor(1.0, 1.0, 0.3))
    white = RGBColor(0.8, 0.8, 0.8)
    z_far = -(dist + side)
    ll = at(-side / 2, -side / 2, z_far)
    ur = at(side / 2, side / 2, z_far)
    objects = [
        (core.Sphere(at(0.0, 0.0, -(dist + side / 2)), 0.25), RGBColor(0.2, 0.2, 0.7)),
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
            at(x, side / 2 - 0.5, -(dist + side / 2)), RGBColor(0.5, 0.5, 0.5)))
    scene.set_camera(core.Camera(size, size, 70))
    return scene


SCENES = {"sphere": sphere_scene, "cornell": cornell_box}
# The checks' images: (scene, the integrator of PyRT_Integrators that renders it, its
# extra arguments). The "probe" image has no integrator of the course: RayProbe renders it
RENDERED = {
    "lazy": ("sphere", "LazyIntegrator", ()),
    "probe": ("sphere", "RayProbe", ()),
    "intersection": ("sphere", "IntersectionIntegrator", ()),
    "depth": ("sphere", "DepthIntegrator", (5,)),
    "normal": ("sphere", "NormalIntegrator", ()),
    "phong_sphere": ("sphere", "PhongIntegrator", ()),
    "phong_cornell": ("cornell", "PhongIntegrator", ()),
}


def scene_of(name, draw):
    """A new scene of the image `name`, at the draw's size and offset."""
    return SCENES[RENDERED[name][0]](draw.size, draw.offset)


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
    """The integrator of the image `name`, from the module `integrators`."""
    _, integrator, arguments = RENDERED[name]
    if integrator == "RayProbe":
        return ray_probe(integrators)(filename)
    return getattr(integrators, integrator)(filename, *arguments)


def traced_image(integrator, scene, offset=(0.0, 0.0), pixels=None):
    """The image of integrator.compute_color for a ray from the camera through each
    pixel's centre moved by offset = (dx, dy) pixels, traced here, one pixel at a time,
    instead of by the integrator's render(); only at pixels ((y, x) pairs, the others
    black) when given."""
    common = course_modules()[0]
    integrator.add_scene(scene)
    camera = scene.camera
    image = np.zeros((camera.height, camera.width, 3))
    dx, dy = offset
    if pixels is None:
        pixels = [(y, x) for y in range(camera.height) for x in range(camera.width)]
    for y, x in pixels:
        direction = camera.get_direction(x + dx, y + dy)
        color = integrator.compute_color(common.Ray(common.Vector3D(0.0, 0.0, 0.0),
                                                    direction))
        image[y, x] = (color.r, color.g, color.b)
    return image


def render(integrator, scene):
    """Renders scene with the integrator's own render() and returns a copy of the linear
    image."""
    integrator.add_scene(scene)
    integrator.render()
    return np.array(scene.rendered_image, dtype=float)


# ------------------------------------------------------------------------------------------
# What a check keeps
# ------------------------------------------------------------------------------------------
@dataclass
class Rendered:
    """What the student's code made for one check: its arrays ("image", what render()
    made; "traced", compute_color on the camera rays traced by the check; "answers", of
    any_hit, 1 or 0), and as text: the error it raised (see describe_error), and what
    compute_color or any_hit returned that is no answer of theirs (first_color: its repr
    for the first camera ray; not_bool: the repr for each any_hit case)."""

    name: str
    arrays: dict = field(default_factory=dict)
    error: dict = None
    first_color: str = None
    not_bool: str = None


def collect(name, draw, out, traced=True):
    """The Rendered of the check `name` (any_hit or a name of RENDERED) with draw's inputs,
    with the image of compute_color traced on its own (traced_image) when traced; the
    course's save_image writes into out/<name>/. Errors of the student's code are kept as
    text."""
    rendered = Rendered(name)
    try:
        if name == "any_hit":
            _ask_any_hit(rendered, draw)
        else:
            _render_image(rendered, draw, Path(out) / name, traced)
    except KeyboardInterrupt:
        raise
    except BaseException as error:  # SystemExit too: the student's code called sys.exit
        rendered.error = describe_error(error)
    return rendered


def _ask_any_hit(rendered, draw):
    common, core, _ = course_modules()
    Vector3D = common.Vector3D
    answers = []
    for case in draw.any_hit:
        scene = core.Scene()
        for centre in case.centres:
            scene.add_object(core.Sphere(Vector3D(*centre), 1.0))
        ray = common.Ray(Vector3D(0.0, 0.0, 0.0), Vector3D(*case.direction))
        if case.t_min is not None:
            ray.t_min = case.t_min
        if case.t_max is not None:
            ray.t_max = case.t_max
        answer = scene.any_hit(ray)
        if not isinstance(answer, (bool, np.bool_)):
            rendered.not_bool = f"any_hit returned {answer!r}"[:ERROR_TEXT]
            rendered.arrays["answers"] = np.array(answers + [-1], dtype=np.int64)
            return
        answers.append(int(bool(answer)))
    rendered.arrays["answers"] = np.array(answers, dtype=np.int64)


def _render_image(rendered, draw, folder, traced):
    common, _, integrators = course_modules()
    # The course's save_image writes into the folder it is given and creates none
    folder.mkdir(parents=True, exist_ok=True)
    scene = scene_of(rendered.name, draw)
    integrator = make_integrator(rendered.name, str(folder / "render"), integrators)
    ray_traced = RENDERED[rendered.name][1] not in ("LazyIntegrator", "RayProbe")
    if ray_traced:
        integrator.add_scene(scene)
        color = integrator.compute_color(common.Ray(common.Vector3D(0.0, 0.0, 0.0),
                                                    common.Vector3D(0.0, 0.0, -1.0)))
        if not all(hasattr(color, channel) for channel in "rgb"):
            rendered.first_color = repr(color)[:ERROR_TEXT]
            return
    rendered.arrays["image"] = render(integrator, scene)
    if ray_traced and traced:
        try:
            rendered.arrays["traced"] = traced_image(integrator, scene_of(rendered.name,
                                                                          draw))
        except Exception:  # the student's render() was judged; this only looks further
            pass


def describe_error(error):
    """An error of the student's code as text: {"kind": SystemExit, MemoryError,
    SyntaxError or other, "type": its class's name, "text": str(error), "code": sys.exit's
    argument as text, "file" and "line" of a syntax error, "traceback": the lines of the
    student's own files it passed through, then the error}."""
    kind = next((kind.__name__ for kind in (SystemExit, MemoryError, SyntaxError)
                 if isinstance(error, kind)), "other")
    described = {"kind": kind, "type": type(error).__name__, "text": str(error),
                 "traceback": student_traceback(error)}
    if isinstance(error, SystemExit):
        described["code"] = repr(error.code)
    if isinstance(error, SyntaxError):
        described.update(file=Path(error.filename or "?").name, line=str(error.lineno),
                         text=str(error.msg))
    return {key: value[:ERROR_TEXT] for key, value in described.items()}


def student_traceback(error):
    """The lines of the error's traceback that lie in the student's files (the four
    course modules, in the folder of the PyRT_Common.py imported), each file named as in
    the student's folder, then the error itself."""
    common = sys.modules.get("PyRT_Common")
    project = Path(common.__file__).resolve().parent if common else Path.cwd().resolve()
    frames = [traceback.FrameSummary(Path(frame.filename).name, frame.lineno, frame.name,
                                     line=frame.line)
              for frame in traceback.extract_tb(error.__traceback__)
              if Path(frame.filename).name in STUDENT_FILES
              and Path(frame.filename).resolve().parent == project]
    lines = traceback.format_list(frames)
    if isinstance(error, SyntaxError) and error.text:
        lines.append(f'  File "{Path(error.filename or "?").name}", line {error.lineno}\n'
                     f"    {error.text.strip()}\n")
    return "".join(lines) + "".join(traceback.format_exception_only(type(error), error))


def pixel_history(name, draw, x, y):
    """What the student's integrator of the image `name` asks the scene, and is answered,
    for pixel (x, y) (pyrt/explain.py), as text; "" when it cannot be told (no
    pyrt/explain.py beside the modules, a scene it cannot read)."""
    try:
        from pyrt.explain import explain_pixel
        integrator = make_integrator(name, "unused", course_modules()[2])
        integrator.add_scene(scene_of(name, draw))
        return str(explain_pixel(integrator, x, y))[:4 * ERROR_TEXT]
    except Exception:
        return ""
