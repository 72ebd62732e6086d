"""What your code computes for the checks of Practice 2, as plain data.

practice2_checks.py judges this data. Here your own modules run:
- "estimate": your compute_estimate_cmc on each sample set of the draw;
- "curve": the workbench's curve, the average absolute error of estimates of the integral
  of cos with your collect_samples and compute_estimate_cmc on the directions of
  sample_set_hemisphere, after random.seed(the draw's seed);
- "furnace" and "emitter": your CMCIntegrator.compute_color on a ray from the camera
  through each pixel's centre, in the scenes of practice2_scenes.py, built through the
  course's API.
Of AppWorkbench.py only the definitions run (imports, functions, classes and constants),
not its script: the checks call your functions themselves.
"""
import ast
import math
import random
import types
from pathlib import Path

import numpy as np

import practice1_render
import practice2_scenes as scenes

Rendered = practice1_render.Rendered
ERROR_TEXT = practice1_render.ERROR_TEXT
WORKBENCH = "AppWorkbench.py"
# The definitions of AppWorkbench.py that the checks run
DEFINITIONS = (ast.Import, ast.ImportFrom, ast.FunctionDef, ast.AsyncFunctionDef,
               ast.ClassDef)


def course_modules():
    """The student's PyRT_Common, PyRT_Core and PyRT_Integrators, imported."""
    return practice1_render.course_modules()


def workbench():
    """The student's AppWorkbench.py, beside their PyRT_Common.py, with only its
    definitions run: an import that fails is left out (the script may need what only
    the student's machine has); a syntax error is raised."""
    folder = Path(course_modules()[0].__file__).resolve().parent
    path = folder / WORKBENCH
    source = path.read_text(encoding="utf-8")
    tree = ast.parse(source, filename=str(path))
    module = types.ModuleType("AppWorkbench")
    module.__file__ = str(path)
    for node in tree.body:
        if not (isinstance(node, DEFINITIONS) or _constant_assignment(node)):
            continue
        code = compile(ast.Module([node], type_ignores=[]), str(path), "exec")
        try:
            exec(code, module.__dict__)
        except ImportError:
            if not isinstance(node, (ast.Import, ast.ImportFrom)):
                raise
    return module


def _constant_assignment(node):
    """Whether node assigns a literal (a number, a text, a tuple of them) to names."""
    if not isinstance(node, ast.Assign):
        return False
    try:
        ast.literal_eval(node.value)
    except ValueError:
        return False
    return all(isinstance(target, ast.Name) for target in node.targets)


def collect(name, draw, out, traced=False):
    """The Rendered of the check `name` at draw; images of the scenes' maps are written
    into out/. Errors of the student's code are kept as text. traced: unused (the
    integrator's images are always traced by the check itself)."""
    rendered = Rendered(name)
    try:
        if name == "estimate":
            _estimates(rendered, draw)
        elif name == "curve":
            _curve(rendered, draw)
        else:
            random.seed(draw.seed)  # the check holds for any seed: this one repeats itself
            _render(rendered, draw, Path(out))
    except KeyboardInterrupt:
        raise
    except BaseException as error:  # SystemExit too: the student's code called sys.exit
        rendered.error = practice1_render.describe_error(error)
    return rendered


def _number(rendered, value):
    """value as a float, or nan with rendered.first_color saying what it was."""
    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value,
                                                                                     bool):
        return float(value)
    if rendered.first_color is None:
        rendered.first_color = repr(value)[:ERROR_TEXT]
    return math.nan


def _estimates(rendered, draw):
    common = course_modules()[0]
    estimate = workbench().compute_estimate_cmc
    values = [_number(rendered, estimate(list(s.probs),
                                         [common.RGBColor(f, 0, 0) for f in s.values]))
              for s in draw.sample_sets]
    rendered.arrays["estimates"] = np.array(values, dtype=np.float64)


def _curve(rendered, draw):
    common = course_modules()[0]
    bench = workbench()
    functions = [common.Constant(1), common.Constant(1), common.CosineLobe(1)]
    pdf = common.UniformPDF()
    random.seed(draw.seed)
    errors = []
    for ns in scenes.CURVE_NS:
        error_sum = 0.0
        for _ in range(scenes.CURVE_ESTIMATES):
            sample_set, sample_prob = common.sample_set_hemisphere(ns, pdf)
            values = bench.collect_samples(functions, sample_set)
            error_sum += abs(_number(rendered, bench.compute_estimate_cmc(sample_prob, values))
                         - math.pi)
        errors.append(error_sum / scenes.CURVE_ESTIMATES)
    rendered.arrays["curve"] = np.array(errors, dtype=np.float64)


def scene_of(name, draw, out):
    """A new scene of the check `name` (furnace or emitter) at draw, built through the
    course's API; the furnace's environment map is written into out/."""
    common, core, _ = course_modules()
    Vector3D, RGBColor = common.Vector3D, common.RGBColor
    scene = core.Scene()
    if name == "furnace":
        f = draw.furnace
        sphere = core.Sphere(Vector3D(*f.centre), f.radius)
        sphere.set_BRDF(core.Lambertian(RGBColor(*f.albedo)))
        scene.add_object(sphere)
        scene.set_environment_map(write_sky(out, f.sky))
    else:
        e = draw.emitter
        floor = core.InfinitePlane(Vector3D(0.0, e.floor_y, 0.0), Vector3D(0.0, 1.0, 0.0))
        floor.set_BRDF(core.Lambertian(RGBColor(*e.floor_albedo)))
        scene.add_object(floor)
        sphere = core.Sphere(Vector3D(*e.centre), e.radius, RGBColor(*e.emission))
        sphere.set_BRDF(core.Lambertian(RGBColor(*e.albedo)))
        scene.add_object(sphere)
    scene.set_camera(core.Camera(draw.size, draw.size, scenes.FOV))
    return scene


def write_sky(out, value):
    """The path (text) of an environment map of one value everywhere, written into out/."""
    import cv2
    out.mkdir(parents=True, exist_ok=True)
    path = out / "furnace_sky.hdr"
    cv2.imwrite(str(path), np.full((8, 16, 3), value, dtype=np.float32))
    return str(path)


def _render(rendered, draw, out):
    integrators = course_modules()[2]
    scene = scene_of(rendered.name, draw, out)
    integrator = integrators.CMCIntegrator(draw.n_samples, str(out / rendered.name))
    image, not_a_color = traced_image(integrator, scene)
    if not_a_color is not None:
        rendered.first_color = not_a_color
    else:
        rendered.arrays["image"] = image


def traced_image(integrator, scene):
    """(the image of integrator.compute_color on a ray from the camera through each
    pixel's centre, None) or (None, the repr of the first answer that is no colour)."""
    common = course_modules()[0]
    integrator.add_scene(scene)
    camera = scene.camera
    image = np.zeros((camera.height, camera.width, 3))
    for y in range(camera.height):
        for x in range(camera.width):
            color = integrator.compute_color(common.Ray(common.Vector3D(0.0, 0.0, 0.0),
                                                        camera.get_direction(x, y)))
            if not all(hasattr(color, channel) for channel in "rgb"):
                return None, repr(color)[:ERROR_TEXT]
            image[y, x] = (float(color.r), float(color.g), float(color.b))
    return image, None


def render_loop_image(draw, out, size=8, n_samples=4):
    """The furnace rendered small through the student's own render() (Assignment 2.4's
    images come out of it): the linear image, or None when compute_color gives no colour
    yet (Assignment 2.3 comes first)."""
    common, _, integrators = course_modules()
    small = draw._replace(size=size)
    scene = scene_of("furnace", small, out)
    integrator = integrators.CMCIntegrator(n_samples, str(out / "render_loop"))
    integrator.add_scene(scene)
    color = integrator.compute_color(common.Ray(common.Vector3D(0.0, 0.0, 0.0),
                                                scene.camera.get_direction(0, 0)))
    if not all(hasattr(color, channel) for channel in "rgb"):
        return None
    integrator.render()
    return np.array(scene.rendered_image, dtype=float)


# What the step server asks of every practice's render module
draw_from_json = scenes.draw_from_json
PUBLISHED = scenes.PUBLISHED


def pixel_history(name, draw, x, y):
    """No pixel's history is told in Practice 2: its images are judged as a whole."""
    return ""
