"""What your code computes for the checks of Practices 3 and 4, as plain data.

practice3_checks.py judges this data. Here your own modules run:
- "inv_q": your GP(SobolevCov(), Constant(1), noise).compute_inv_Q() on given positions;
- "z": your compute_z() on given positions for p = Constant(1) and p = CosineLobe(1), each
  after random.seed (the course's set-up draws its directions with sample_set_hemisphere);
- "bmc_sum": your compute_integral_BMC() on given weights and colours;
- "workbench": your workbench's compute_estimate_bmc(gp, sample_pos_, sample_values_) with
  a GP of the kit; a workbench without it (the course's script) is read, not run: which
  of the course's calls of a BMC estimate its code makes;
- "bmc_furnace", "bmc_box", "bmc_pool", "bmcis_furnace": your
  BayesianMonteCarloIntegrator (3.3 in the furnace and in a box of emitting walls, 3.3.2)
  and BMCISIntegrator (4.2) with GPs of the kit, whose weights practice3_scenes.py
  computed: a mistake of your GaussianProcess.py costs Assignment 3.1 alone;
- "workbench_mc_is", "workbench_bmc_is": the pdf, p and f of the MC IS and BMC IS methods
  of your workbench's practice4_methods() at given directions (a script without it: read
  as for "workbench");
- "cmcis_furnace": classic Monte Carlo with cosine sampling (4.1): your CMCISIntegrator,
  or CMCIntegrator(..., pdf=CosinePDF(1)) when you have none and your CMCIntegrator takes
  pdf.
For 3.3.2 the directions of the rays your integrator casts from the floor are kept, and
which GP of the pool each pixel used.
"""
import math
import random
from pathlib import Path

import numpy as np

import practice1_render
import practice2_render
import practice3_scenes as scenes

Rendered = practice1_render.Rendered
ERROR_TEXT = practice1_render.ERROR_TEXT
GP_MODULE = "GaussianProcess"
NAMES = ("inv_q", "z", "bmc_sum", "workbench", "bmc_furnace", "bmc_box", "bmc_pool",
         "cmcis_furnace", "bmcis_furnace", "workbench_mc_is", "workbench_bmc_is")


def gaussian_process():
    """The student's GaussianProcess module, imported."""
    import importlib
    return importlib.import_module(GP_MODULE)


class KitGP:
    """A GP of the kit handed to the student's integrators and workbench: the sample
    positions (the student's Vector3D) and the weights practice3_scenes computed for them,
    with the course's attributes and methods; it notes each compute_integral_BMC in used
    (its index in the pool)."""

    def __init__(self, common, gp_set, p_func, index=0, used=None):
        self.common = common
        self.samples_pos = [common.Vector3D(*p) for p in gp_set.positions]
        self.weights = np.array(gp_set.weights)
        self.z = self.weights.copy()  # z^T Q^-1 = weights with invQ the identity
        self.invQ = np.identity(len(self.weights))
        self.p_func = p_func
        self.noise = scenes.GP_NOISE
        self.samples_val = None
        self.index = index
        self.used = used if used is not None else []
        self.known = {tuple(gp_set.positions): gp_set.weights}

    def add_sample_pos(self, samples_pos_):
        """Positions of the kit's own sets only: their weights are known."""
        key = tuple((float(p.x), float(p.y), float(p.z)) for p in samples_pos_)
        if key not in self.known:
            raise ValueError("the kit's GP knows the weights of its own sample set only: "
                             "pass it the positions the check gave")
        self.samples_pos = list(samples_pos_)

    def add_sample_val(self, samples_val_):
        self.samples_val = samples_val_

    def compute_integral_BMC(self):
        self.used.append(self.index)
        channels = np.zeros(3)
        for w, value in zip(self.weights, self.samples_val or ()):
            if not hasattr(value, "r") and not isinstance(value, (int, float)):
                raise TypeError(f"the GP's values (add_sample_val) hold {value!r}, where "
                                "RGBColors are needed (a stub's pass returns None)")
            channels += w * np.array(_channels(value))
        return self.common.RGBColor(*channels)


def _channels(value):
    if hasattr(value, "r"):
        return float(value.r), float(value.g), float(value.b)
    return float(value), 0.0, 0.0


def collect(name, draw, out, traced=False):
    """The Rendered of the check `name` at draw; images of the scenes' maps are written
    into out/. Errors of the student's code are kept as text. traced: unused."""
    rendered = Rendered(name)
    try:
        COLLECTORS[name](rendered, draw, Path(out) / name)
    except KeyboardInterrupt:
        raise
    except BaseException as error:  # SystemExit too: the student's code called sys.exit
        rendered.error = practice1_render.describe_error(error)
    return rendered


def _matrix(rendered, value, shape):
    """value as a float array of shape, or nan with rendered.first_color saying what it
    was."""
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        array = None
    if array is None or array.shape != shape:
        rendered.first_color = repr(value)[:ERROR_TEXT]
        return np.full(shape, np.nan)
    return array


def _inv_q(rendered, draw, out):
    common = practice1_render.course_modules()[0]
    module = gaussian_process()
    gp = module.GP(module.SobolevCov(), common.Constant(1), draw.noise)
    gp.samples_pos = [common.Vector3D(*p) for p in draw.positions]
    n = len(draw.positions)
    rendered.arrays["inv_q"] = _matrix(rendered, gp.compute_inv_Q(), (n, n))


def _z(rendered, draw, out):
    common = practice1_render.course_modules()[0]
    module = gaussian_process()
    n = len(draw.positions)
    for key, p_func, offset in (("z_one", common.Constant(1), 0),
                                ("z_cos", common.CosineLobe(1), 1)):
        gp = module.GP(module.SobolevCov(), p_func)
        gp.samples_pos = [common.Vector3D(*p) for p in draw.positions]
        random.seed(draw.seed + offset)
        try:
            z = gp.compute_z()
        except (TypeError, AttributeError):
            if key != "z_one":
                raise
            gp.p_func = 1  # p as a number, multiplied in: a style of the course's
            random.seed(draw.seed + offset)
            z = gp.compute_z()
        rendered.arrays[key] = _matrix(rendered, z, (n,))


def _bmc_sum(rendered, draw, out):
    common = practice1_render.course_modules()[0]
    module = gaussian_process()
    sums = []
    for case in draw.sums:
        gp = module.GP(module.SobolevCov(), common.Constant(1))
        n = len(case.weights)
        gp.samples_pos = [common.Vector3D(0.0, 1.0, 0.0)] * n
        gp.weights = np.array(case.weights)
        gp.z, gp.invQ = np.array(case.weights), np.identity(n)  # z^T Q^-1 = the weights
        gp.samples_val = [common.RGBColor(*v) for v in case.values]
        result = gp.compute_integral_BMC()
        if not all(hasattr(result, channel) for channel in "rgb"):
            rendered.first_color = repr(result)[:ERROR_TEXT]
            sums.append((math.nan,) * 3)
        else:
            sums.append(_channels(result))
    rendered.arrays["sums"] = np.array(sums, dtype=np.float64)


def _workbench(rendered, draw, out):
    common = practice1_render.course_modules()[0]
    bench = practice2_render.workbench()
    estimate = getattr(bench, "compute_estimate_bmc", None)
    rendered.arrays["script"] = script_calls(bench, "compute_estimate_bmc")
    results = np.full(len(draw.pool), np.nan)
    if estimate is not None:
        for k, gp_set in enumerate(draw.pool):
            gp = KitGP(common, gp_set, common.Constant(1))
            positions = [common.Vector3D(*p) for p in gp_set.positions]
            values = [common.RGBColor(p[1], 0.0, 0.0) for p in gp_set.positions]  # cos
            value = estimate(gp, positions, values)
            results[k] = (_channels(value)[0] if hasattr(value, "r")
                          else _number(rendered, value))
    rendered.arrays["estimates"] = results


WORKBENCH_LABELS = ("MC IS", "BMC IS")  # Practice 4's methods that its students add
WORKBENCH_CHECKS = {"workbench_mc_is": "MC IS", "workbench_bmc_is": "BMC IS"}
# What a course-style workbench (a script, no function to call) is judged on: whether its
# code calls these, read from its source (never run); the last: whether it defines the
# handout's function, which is then called instead
SCRIPT_CALLS = ("GP with p = 1", "add_sample_pos", "add_sample_val",
                "compute_integral_BMC", "CosinePDF", "GP with p = CosineLobe",
                "compute_estimate_cmc", "the handout's function")


def script_calls(bench, function):
    """1.0 or 0.0 for each of SCRIPT_CALLS: whether the source of the workbench module
    bench calls it anywhere (module level or in a function; a GP's p given there, or as
    a name assigned it), and whether bench defines function."""
    import ast
    tree = ast.parse(Path(bench.__file__).read_text(encoding="utf-8"))
    assigned = {node.targets[0].id: node.value for node in ast.walk(tree)
                if isinstance(node, ast.Assign) and len(node.targets) == 1
                and isinstance(node.targets[0], ast.Name)}
    called, gp_p = set(), set()
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        name = _called_name(node.func)
        called.add(name)
        if name == "GP":
            for p in node.args[1:2] + [k.value for k in node.keywords if k.arg == "p_func"]:
                p = assigned.get(p.id, p) if isinstance(p, ast.Name) else p
                if isinstance(p, ast.Call):
                    gp_p.add(_called_name(p.func))
                elif isinstance(p, ast.Constant) and p.value == 1:
                    gp_p.add("Constant")
    flags = ["Constant" in gp_p] + [name in called for name in SCRIPT_CALLS[1:5]] + [
        "CosineLobe" in gp_p, "compute_estimate_cmc" in called, hasattr(bench, function)]
    return np.array(flags, dtype=np.float64)


def _called_name(func):
    """The name a call calls: f of f(...) and of x.f(...)."""
    return getattr(func, "id", None) or getattr(func, "attr", None)


def _workbench_method(rendered, draw, out):
    """For the method of the check (WORKBENCH_CHECKS) of the workbench's
    practice4_methods() (the handout's function of 4.1 and 4.2), at the directions of
    the draw's first GP: the pdf's value, p (nan for a classic method) and f, the product
    of the GP's value functions (the whole integrand, PRACTICE4_INTEGRAND's, when it names
    none); nan for a method that is not there; and the script's calls."""
    common = practice1_render.course_modules()[0]
    bench = practice2_render.workbench()
    rendered.arrays["script"] = script_calls(bench, "practice4_methods")
    directions = [common.Vector3D(*p) for p in draw.pool[0].positions]
    row = np.full((3, len(directions)), np.nan)
    methods_of = getattr(bench, "practice4_methods", None)
    methods = methods_of() if methods_of is not None else None
    label = WORKBENCH_CHECKS[rendered.name]
    for method in methods or ():  # a stub's pass returns None: no methods
        if method.label != label:
            continue
        row[0] = [method.pdf.get_val(d) for d in directions]
        if method.p_func is None:
            break
        row[1] = [method.p_func.eval(d) if hasattr(method.p_func, "eval")
                  else float(method.p_func) for d in directions]
        functions = method.value_functions or bench.PRACTICE4_INTEGRAND.functions
        row[2] = [math.prod(f.eval(d) for f in functions) for d in directions]
        break
    rendered.arrays.update(pdf=row[0], p=row[1], f=row[2])


def _number(rendered, value):
    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
            value, bool):
        return float(value)
    rendered.first_color = repr(value)[:ERROR_TEXT]
    return math.nan


# ------------------------------------------------------------------------------------------
# The integrators
# ------------------------------------------------------------------------------------------
def _furnace(draw, out):
    return practice2_render.scene_of("furnace", draw, out)


def _floor(draw, out):
    common, core, _ = practice1_render.course_modules()
    scene = core.Scene()
    floor = core.InfinitePlane(common.Vector3D(0.0, draw.floor.floor_y, 0.0),
                               common.Vector3D(0.0, 1.0, 0.0))
    floor.set_BRDF(core.Lambertian(common.RGBColor(*draw.floor.albedo)))
    scene.add_object(floor)
    scene.set_environment_map(practice2_render.write_sky(out, draw.floor.sky))
    scene.set_camera(core.Camera(draw.size, draw.size, practice2_render.scenes.FOV))
    return scene


def _box(draw, out):
    """The furnace's sphere inside 3.3's closed box of emitting walls, no map."""
    common, core, _ = practice1_render.course_modules()
    Vector3D = common.Vector3D
    scene = core.Scene()
    f = draw.furnace
    sphere = core.Sphere(Vector3D(*f.centre), f.radius)
    sphere.set_BRDF(core.Lambertian(common.RGBColor(*f.albedo)))
    scene.add_object(sphere)
    low, high = Vector3D(*scenes.BOX_LOW), Vector3D(*scenes.BOX_HIGH)
    size = [h - l for l, h in zip(scenes.BOX_LOW, scenes.BOX_HIGH)]
    x, y, z = (Vector3D(size[0], 0.0, 0.0), Vector3D(0.0, size[1], 0.0),
               Vector3D(0.0, 0.0, size[2]))
    for corner, s1, s2 in ((low, x, y), (low, y, z), (low, z, x), (high, x * -1.0, y * -1.0),
                           (high, y * -1.0, z * -1.0), (high, z * -1.0, x * -1.0)):
        wall = core.Parallelogram(corner, s1, s2, common.RGBColor(*scenes.box_emission(draw)))
        wall.set_BRDF(core.Lambertian(common.RGBColor(0.0, 0.0, 0.0)))
        scene.add_object(wall)
    scene.set_camera(core.Camera(draw.size, draw.size, practice2_render.scenes.FOV))
    return scene


def _image(rendered, integrator, scene, each_pixel=None):
    """compute_color on the camera ray through each pixel's centre (rows y), into
    rendered.arrays["image"]; each_pixel(x, y) after each pixel."""
    common = practice1_render.course_modules()[0]
    integrator.add_scene(scene)
    size = scene.camera.width
    image = np.zeros((size, size, 3))
    for y in range(size):
        for x in range(size):
            color = integrator.compute_color(common.Ray(common.Vector3D(0.0, 0.0, 0.0),
                                                        scene.camera.get_direction(x, y)))
            if not all(hasattr(color, channel) for channel in "rgb"):
                rendered.first_color = repr(color)[:ERROR_TEXT]
                return False
            image[y, x] = _channels(color)
            if each_pixel is not None:
                each_pixel(x, y)
    rendered.arrays["image"] = image
    return True


def _bmc_image(rendered, draw, out, cls_name, gp_set, p_func_of, scene_of=_furnace):
    common, _, integrators = practice1_render.course_modules()
    cls = getattr(integrators, cls_name, None)
    if cls is None:
        raise AttributeError(f"PyRT_Integrators.py defines no {cls_name}(n, myGP, "
                             "filename_, experiment_name='')")
    p_func = p_func_of(common)
    for style in (lambda gp: gp, lambda gp: [gp]):  # one GP, else a pool of one
        gp = KitGP(common, gp_set, p_func)
        integrator = cls(len(gp_set.positions), style(gp), str(out / cls_name))
        try:
            return _image(rendered, integrator, scene_of(draw, out))
        except (TypeError, AttributeError, IndexError, KeyError):
            if style(gp) is not gp:
                raise


def _bmc_furnace(rendered, draw, out):
    _bmc_image(rendered, draw, out, "BayesianMonteCarloIntegrator", draw.pool[0],
               lambda common: common.Constant(1))


def _bmc_box(rendered, draw, out):
    _bmc_image(rendered, draw, out, "BayesianMonteCarloIntegrator", draw.pool[0],
               lambda common: common.Constant(1), _box)


def _bmcis_furnace(rendered, draw, out):
    _bmc_image(rendered, draw, out, "BMCISIntegrator", draw.pool_is[0],
               lambda common: common.CosineLobe(1))


def _cmcis_furnace(rendered, draw, out):
    import inspect
    common, _, integrators = practice1_render.course_modules()
    filename = str(out / "cmcis")
    cmc = integrators.CMCIntegrator
    if hasattr(integrators, "CMCISIntegrator"):
        integrator = integrators.CMCISIntegrator(scenes.N_SAMPLES, filename)
    elif "pdf" in inspect.signature(cmc).parameters:
        integrator = cmc(scenes.N_SAMPLES, filename, pdf=common.CosinePDF(1))
    else:
        raise AttributeError("PyRT_Integrators.py has no classic Monte Carlo with "
                             "importance sampling: neither CMCIntegrator(n, filename_, "
                             "pdf=CosinePDF(1)) nor CMCISIntegrator(n, filename_)")
    _image(rendered, integrator, _furnace(draw, out))


def _bmc_pool(rendered, draw, out):
    """3.3.2: a pool of the kit's GPs; for each floor pixel the GP used and the directions
    of the sample rays cast (those that leave the floor upwards)."""
    common, _, integrators = practice1_render.course_modules()
    used = []
    pool = [KitGP(common, gp_set, common.Constant(1), index, used)
            for index, gp_set in enumerate(draw.pool)]
    integrator = integrators.BayesianMonteCarloIntegrator(draw.n_samples, pool,
                                                          str(out / "pool"))
    scene = _floor(draw, out)
    cast = []
    for method in ("closest_hit", "any_hit"):
        original = getattr(scene, method)

        def recording(ray, *args, original=original, **kwargs):
            d = ray.d
            cast.append((float(d.x), float(d.y), float(d.z)))
            return original(ray, *args, **kwargs)
        setattr(scene, method, recording)
    n = draw.n_samples
    directions = np.full((draw.size, draw.size, n, 3), np.nan)
    chosen = np.full((draw.size, draw.size), -1)

    def each_pixel(x, y):
        upwards = [d for d in cast if d[1] > 0.0][:n]
        if upwards:
            directions[y, x, :len(upwards)] = upwards
        if used:
            chosen[y, x] = used[-1]
        cast.clear()
        used.clear()

    if _image(rendered, integrator, scene, each_pixel):
        rendered.arrays["directions"] = directions
        rendered.arrays["chosen"] = chosen.astype(np.float64)


COLLECTORS = {"inv_q": _inv_q, "z": _z, "bmc_sum": _bmc_sum, "workbench": _workbench,
              "bmc_furnace": _bmc_furnace, "bmc_box": _bmc_box, "bmc_pool": _bmc_pool,
              "cmcis_furnace": _cmcis_furnace, "bmcis_furnace": _bmcis_furnace,
              "workbench_mc_is": _workbench_method, "workbench_bmc_is": _workbench_method}

# What the step server asks of every practice's render module
draw_from_json = scenes.draw_from_json
PUBLISHED = scenes.PUBLISHED


def pixel_history(name, draw, x, y):
    """No pixel's history is told in Practices 3 and 4: their images are judged whole."""
    return ""
