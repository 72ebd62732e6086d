"""Submissions of Practice 1 as real students hand them in: the course's own base code of
their edition (tests/data/course_base/<edition>/, the four modules as the course hands
them out, stubs unfilled) with the student's code in place of the stubs.

A student's code is an Answers record: the whole render() method of Integrator, and the
bodies of Scene.any_hit and of the compute_color methods, written without indentation,
in the styles the course's students write them in. FIXTURES is the set the tests grade:
each submission with its edition, its styles and the verdict a teaching assistant gives
it, step by step, judging the code by hand.
"""
import re
from dataclasses import dataclass, field, replace
from pathlib import Path

BASES = Path(__file__).resolve().parent / "data" / "course_base"
EDITIONS = ("2021-22", "2023-24", "2025-26")
MODULES = ("PyRT_Common.py", "PyRT_Core.py", "PyRT_Integrators.py", "AppRenderer.py")
STEPS = ("1.1", "1.2", "1.3", "1.4")

# stub -> (module, the class whose stub it is, the first line of the stub). A render stub
# is the whole method; the others are the course's comment, kept as students keep it,
# and the line after it (pass, or any_hit's return False), which the answer replaces.
STUB_PLACES = {
    "render": ("PyRT_Integrators.py", "Integrator", "def render(self):"),
    "any_hit": ("PyRT_Core.py", "Scene", "# ASSIGNMENT 1.2: PUT YOUR CODE HERE"),
    "intersection": ("PyRT_Integrators.py", "IntersectionIntegrator",
                     "# ASSIGNMENT 1.2: PUT YOUR CODE HERE"),
    "depth": ("PyRT_Integrators.py", "DepthIntegrator", "# ASSIGNMENT 1.3: PUT YOUR CODE HERE"),
    "normal": ("PyRT_Integrators.py", "NormalIntegrator",
               "# ASSIGNMENT 1.3: PUT YOUR CODE HERE"),
    "phong": ("PyRT_Integrators.py", "PhongIntegrator", "# ASSIGNMENT 1.4: PUT YOUR CODE HERE"),
}
# The line of the older editions' AppRenderer.py that picks the integrator
APP_INTEGRATOR_LINE = "integrator = LazyIntegrator(DIRECTORY + FILENAME)"


@dataclass(frozen=True)
class Answers:
    """A student's code for each stub (None leaves the base's stub as it is), helper
    functions of their own appended to a module, and the integrator their AppRenderer.py
    was left rendering."""

    render: str = None
    any_hit: str = None
    intersection: str = None
    depth: str = None
    normal: str = None
    phong: str = None
    helpers: tuple = ()  # (module, code) pairs
    app_integrator: str = None


@dataclass(frozen=True)
class Fixture:
    """A submission of the set: its name (also its folder's), the edition whose base it
    is written on, the styles it shows, its answers, and per failed step a fragment of
    the reason a teaching assistant expects (a step left out passes)."""

    name: str
    edition: str
    styles: tuple
    answers: Answers
    fails: dict = field(default_factory=dict)

    def expected(self, step):
        """The fragment of the reason step must fail with, or None when it must pass."""
        return self.fails.get(step)


# The course's base code: the 2023-24 edition's four modules in full, and of each other
# edition what it changes there (data/course_base/README.md lists it), each change a
# function of the module's 2023-24 text, or the edition's own file where it has one
FULL_EDITION = "2023-24"
RAY_HEADER = "# -------------------------------------------------RAY CLASS\n"
VECTOR_HEADER = "# -------------------------------------------------VECTOR 3D CLASS\n"
ENVIRONMENT_HEADER = "# -------------------------------------------------ENVIRONMENT MAP CLASS\n"


def _one(text, old, new):
    """text with its one occurrence of old replaced by new."""
    assert text.count(old) == 1, old
    return text.replace(old, new)


def _rays_after_vectors(common):
    """2025-26: Ray and HitData stand after Vector3D and RGBColor, their default vectors
    Vector3D(0.0, 0.0, 0.0) instead of np.zeros(3)."""
    start, end = common.index(RAY_HEADER), common.index(VECTOR_HEADER)
    rays = common[start:end].replace("np.zeros(3)", "Vector3D(0.0, 0.0, 0.0)")
    rest = common[:start] + common[end:]
    at = rest.index(ENVIRONMENT_HEADER)
    return rest[:at] + rays + rest[at:]


def _no_vector_multiply(common):
    """2021-22 and 2025-26: Vector3D has no multiply (RGBColor has)."""
    return _one(common, "\n    # element by element multiplication\n"
                        "    def multiply(self, v):\n"
                        "        return Vector3D(self.x * v.x, self.y * v.y, self.z * v.z)\n",
                "")


def _no_get_kd(core):
    """2021-22 and 2025-26: Lambertian has no get_kd (its kd is read directly)."""
    return _one(core, "\n    def get_kd(self):\n        return self.kd\n", "")


def _ambient_unset(core):
    """2025-26: Scene.i_a is None until set_ambient."""
    return _one(core, "        self.i_a = RGBColor(0.0, 0.0, 0.0)  # ambient intensity\n",
                "        self.i_a = None  # ambient intensity, set with set_ambient()\n")


def _integrator_environment_map(integrators):
    """2021-22: the Integrator holds an environment map of its own, env_map (None until
    add_environment_map), beside the scene's."""
    text = _one(integrators, "        self.scene = None\n",
                "        self.scene = None\n        self.env_map = None\n")
    return _one(text, "    def add_scene(self, scene):\n        self.scene = scene\n",
                "    def add_scene(self, scene):\n        self.scene = scene\n\n"
                "    def add_environment_map(self, env_map_path):\n"
                "        self.env_map = EnvironmentMap(env_map_path)\n")


EDITION_CHANGES = {
    "2021-22": {"PyRT_Common.py": _no_vector_multiply, "PyRT_Core.py": _no_get_kd,
                "PyRT_Integrators.py": _integrator_environment_map},
    "2025-26": {"PyRT_Common.py": lambda common: _no_vector_multiply(_rays_after_vectors(common)),
                "PyRT_Core.py": lambda core: _no_get_kd(_ambient_unset(core))},
}


def base_text(edition, module):
    """The text of module in the course's base code of edition."""
    own = BASES / edition / module
    if own.is_file():
        return own.read_text(encoding="utf-8")
    text = (BASES / FULL_EDITION / module).read_text(encoding="utf-8")
    change = EDITION_CHANGES.get(edition, {}).get(module)
    return change(text) if change else text


def _stub_span(lines, owner, first_line, whole_method):
    """(first, end) indices of the stub's lines in lines: in class owner, from the line
    that reads first_line to the end of the method (whole_method) or over two lines."""
    in_class = next(number for number, line in enumerate(lines)
                    if re.match(rf"class {owner}\b", line))
    first = next(number for number in range(in_class, len(lines))
                 if lines[number].strip() == first_line)
    if not whole_method:
        return first, first + 2
    indent = len(lines[first]) - len(lines[first].lstrip())
    end = first + 1
    # the method goes on while its lines are blank or indented deeper than its def
    while end < len(lines) and (not lines[end].strip()
                                or len(lines[end]) - len(lines[end].lstrip()) > indent):
        end += 1
    while not lines[end - 1].strip():  # blank lines after the method stay outside it
        end -= 1
    return first, end


def fill(text, stub, answer):
    """text (a base module) with the stub STUB_PLACES[stub] replaced by answer, indented as
    the stub was; the course's comment before a body stub is kept."""
    _, owner, first_line = STUB_PLACES[stub]
    lines = text.splitlines(keepends=True)
    first, end = _stub_span(lines, owner, first_line, stub == "render")
    indent = lines[first][:len(lines[first]) - len(lines[first].lstrip())]
    kept = [] if stub == "render" else [lines[first]]
    filled = [indent + line if line.strip() else line
              for line in answer.splitlines(keepends=True)]
    return "".join(lines[:first] + kept + filled + lines[end:])


def submission_files(edition, answers):
    """{module: text} of the four course modules of a submission on edition's base."""
    texts = {module: base_text(edition, module) for module in MODULES}
    for stub, (module, _, _) in STUB_PLACES.items():
        answer = getattr(answers, stub)
        if answer is not None:
            texts[module] = fill(texts[module], stub, answer)
    for module, code in answers.helpers:
        texts[module] = texts[module].rstrip("\n") + "\n\n\n" + code
    if answers.app_integrator and APP_INTEGRATOR_LINE in texts["AppRenderer.py"]:
        texts["AppRenderer.py"] = texts["AppRenderer.py"].replace(
            APP_INTEGRATOR_LINE,
            APP_INTEGRATOR_LINE.replace("LazyIntegrator", answers.app_integrator))
    return texts


def write_course_submission(folder, edition, answers):
    """Writes the four modules of a submission into the new folder; returns the folder."""
    folder = Path(folder)
    folder.mkdir(parents=True)
    for module, text in submission_files(edition, answers).items():
        (folder / module).write_text(text, encoding="utf-8")
    return folder


def changed(text, old, new):
    """text with its one occurrence of old replaced by new: a mistake made in a right
    answer, which must still hold the code the mistake changes."""
    assert text.count(old) == 1, (old, text)
    return text.replace(old, new)


# ------------------------------------------------------------------------------------------
# Render loops, each printing its progress after every column as students do
# ------------------------------------------------------------------------------------------
# 2021-22 and 2023-24: Ray()'s default origin is a numpy array, so the student sets ray.o
# as well (Ray(direction=d) fails there: its origin minus a Vector3D raises a TypeError)
RENDER_RAY_THEN_O_AND_D = """\
def render(self):
    cam = self.scene.camera
    print('Rendering Image: ' + self.get_filename())
    for x in range(0, cam.width):
        for y in range(0, cam.height):
            ray = Ray()
            ray.o = Vector3D(0.0, 0.0, 0.0)
            ray.d = cam.get_direction(x, y)
            pixel = self.compute_color(ray)
            self.scene.set_pixel(pixel, x, y)
        print(str(round(100.0 * (x + 1) / cam.width, 2)) + '%')
    self.scene.save_image(self.get_filename())
"""
RENDER_DIRECTION_ONLY = """\
def render(self):
    cam = self.scene.camera
    for x in range(cam.width):
        for y in range(cam.height):
            direction = cam.get_direction(x, y)
            ray = Ray(direction=direction)
            color = self.compute_color(ray)
            self.scene.set_pixel(color, x, y)
        print("Progress: {:.1f}%".format(100 * (x + 1) / cam.width))
    self.scene.save_image(self.get_filename())
"""
RENDER_ORIGIN_AND_DIRECTION = """\
def render(self):
    cam = self.scene.camera
    print('Rendering Image: ' + self.get_filename())
    for x in range(0, cam.width):
        for y in range(0, cam.height):
            ray = Ray(Vector3D(0, 0, 0), cam.get_direction(x, y))
            self.scene.set_pixel(self.compute_color(ray), x, y)
        print(f'column {x + 1} of {cam.width} ({100 * (x + 1) // cam.width}%)')
    self.scene.save_image(self.get_filename())
"""
RENDER_RAY_THEN_D = """\
def render(self):
    cam = self.scene.camera
    print('Rendering Image: ' + self.get_filename())
    for x in range(0, cam.width):
        for y in range(0, cam.height):
            ray = Ray()
            ray.d = cam.get_direction(x, y)
            pixel = self.compute_color(ray)
            self.scene.set_pixel(pixel, x, y)
        print(str(round(100.0 * (x + 1) / cam.width, 2)) + '%')
    self.scene.save_image(self.get_filename())
"""
# Assignment 1.1 done, 1.2 not carried into the loop
RENDER_LAZY_COLOURS = """\
def render(self):
    cam = self.scene.camera
    print('Rendering Image: ' + self.get_filename())
    for x in range(0, cam.width):
        for y in range(0, cam.height):
            pixel = RGBColor(x / cam.width, y / cam.height, 0)
            self.scene.set_pixel(pixel, x, y)
        print(str(round(100.0 * (x + 1) / cam.width, 2)) + '%')
    self.scene.save_image(self.get_filename())
"""
# Its own camera arithmetic, through the pixel's top-left corner
RENDER_CORNER_RAYS = """\
def render(self):
    cam = self.scene.camera
    print('Rendering Image: ' + self.get_filename())
    for x in range(0, cam.width):
        for y in range(0, cam.height):
            x_s = 2 * x / cam.width - 1
            y_s = 1 - 2 * y / cam.height
            t = np.tan(cam.vertical_fov / 2)
            ray = Ray()
            ray.d = Normalize(Vector3D(x_s * t * cam.aspect_ratio, y_s * t, -1))
            pixel = self.compute_color(ray)
            self.scene.set_pixel(pixel, x, y)
        print(str(round(100.0 * (x + 1) / cam.width, 2)) + '%')
    self.scene.save_image(self.get_filename())
"""

# ------------------------------------------------------------------------------------------
# any_hit
# ------------------------------------------------------------------------------------------
ANY_HIT_RETURN_IN_LOOP = """\
for obj in self.object_list:
    if obj.intersect(ray).has_hit:
        return True
return False
"""
ANY_HIT_WHILE = """\
i = 0
hit = False
while i < len(self.object_list) and not hit:
    hit = self.object_list[i].intersect(ray).has_hit
    i += 1
return hit
"""
ANY_HIT_FLAG_AND_BREAK = """\
intersected = False
for primitive in self.object_list:
    hit_data = primitive.intersect(ray)
    if hit_data.has_hit == True:
        intersected = True
        break
return intersected
"""
ANY_HIT_FIRST_OBJECT_ONLY = """\
hit_data = self.object_list[0].intersect(ray)
return hit_data.has_hit
"""

# ------------------------------------------------------------------------------------------
# The Intersection, Depth and Normal integrators
# ------------------------------------------------------------------------------------------
INTERSECTION_RED = """\
if self.scene.any_hit(ray):
    return RED
return BLACK
"""
INTERSECTION_255 = """\
if self.scene.any_hit(ray):
    return RGBColor(255, 0, 0)
else:
    return BLACK
"""
INTERSECTION_ONE = """\
color = BLACK
if self.scene.any_hit(ray):
    color = RGBColor(1, 0, 0)
return color
"""
DEPTH_MAX = """\
hit_data = self.scene.closest_hit(ray)
if hit_data.has_hit:
    c = max(1 - hit_data.hit_distance / self.max_depth, 0)
    return RGBColor(c, c, c)
return BLACK
"""
DEPTH_IF = """\
hit = self.scene.closest_hit(ray)
if not hit.has_hit:
    return BLACK
value = 1.0 - hit.hit_distance / self.max_depth
if value < 0:
    value = 0.0
return RGBColor(value, value, value)
"""
NORMAL_CHANNELS = """\
hit = self.scene.closest_hit(ray)
if hit.has_hit:
    n = hit.normal
    return RGBColor((n.x + 1) / 2, (n.y + 1) / 2, (n.z + 1) / 2)
return BLACK
"""
NORMAL_WITH_HELPER = """\
hit_data = self.scene.closest_hit(ray)
if not hit_data.has_hit:
    return BLACK
return normal_to_color(hit_data.normal)
"""
NORMAL_HELPER = ("PyRT_Integrators.py", """\
# maps a normal, whose components are in [-1, 1], to a colour in [0, 1]
def normal_to_color(n):
    c = (n + Vector3D(1, 1, 1)) / 2
    return RGBColor(c.x, c.y, c.z)
""")

# ------------------------------------------------------------------------------------------
# Phong, one style of shadow ray each
# ------------------------------------------------------------------------------------------
PHONG_SHADOW_RAY_WITH_DISTANCE = """\
hit_data = self.scene.closest_hit(ray)
if not hit_data.has_hit:
    return BLACK
brdf = self.scene.object_list[hit_data.primitive_index].get_BRDF()
color = brdf.kd.multiply(self.scene.i_a)
for light in self.scene.pointLights:
    to_light = light.pos - hit_data.hit_point
    r = Length(to_light)
    wi = Normalize(to_light)
    shadow_ray = Ray(hit_data.hit_point, wi, r)
    if not self.scene.any_hit(shadow_ray):
        value = brdf.get_value(wi, ray.d * -1, hit_data.normal)
        color = color + light.intensity.multiply(value) / (r * r)
return color
"""
PHONG_START_LIFTED_ALONG_NORMAL = """\
hit = self.scene.closest_hit(ray)
if hit.has_hit == False:
    return BLACK
obj = self.scene.object_list[hit.primitive_index]
ambient = obj.BRDF.kd.multiply(self.scene.i_a)
diffuse = RGBColor(0, 0, 0)
for light in self.scene.pointLights:
    light_dir = light.pos - hit.hit_point
    dist = Length(light_dir)
    light_dir = Normalize(light_dir)
    start = hit.hit_point + hit.normal * EPSILON
    if self.scene.any_hit(Ray(start, light_dir, dist)):
        continue
    brdf_value = obj.BRDF.get_value(light_dir, Vector3D(0, 0, 0), hit.normal)
    diffuse = diffuse + light.intensity.multiply(brdf_value) / (dist ** 2)
return ambient + diffuse
"""
PHONG_CLOSEST_HIT_DISTANCE = """\
hit = self.scene.closest_hit(ray)
if not hit.has_hit:
    return BLACK
brdf = self.scene.object_list[hit.primitive_index].get_BRDF()
L = brdf.kd.multiply(self.scene.i_a)
for light in self.scene.pointLights:
    wi = Normalize(light.pos - hit.hit_point)
    r = Length(light.pos - hit.hit_point)
    shadow = self.scene.closest_hit(Ray(hit.hit_point, wi))
    if shadow.has_hit and shadow.hit_distance < r:
        continue  # the light is hidden
    L = L + light.intensity.multiply(brdf.get_value(wi, ray.d, hit.normal)) * (1 / r ** 2)
return L
"""
PHONG_CLOSEST_HIT_INDEX = """\
hit = self.scene.closest_hit(ray)
if hit.has_hit:
    brdf = self.scene.object_list[hit.primitive_index].get_BRDF()
    color = brdf.kd.multiply(self.scene.i_a)
    for light in self.scene.pointLights:
        light_vec = light.pos - hit.hit_point
        d2 = Dot(light_vec, light_vec)
        wi = Normalize(light_vec)
        shadow_hit = self.scene.closest_hit(Ray(hit.hit_point, wi, sqrt(d2)))
        if shadow_hit.has_hit and shadow_hit.primitive_index != hit.primitive_index:
            continue
        color = color + light.intensity.multiply(brdf.get_value(wi, ray.d, hit.normal)) / d2
    return color
else:
    return BLACK
"""
# The shadow-ray styles, by name, for the comparison with the course's own renders
SHADOW_STYLES = {
    "shadow ray with the light's distance": PHONG_SHADOW_RAY_WITH_DISTANCE,
    "start lifted EPSILON along the normal": PHONG_START_LIFTED_ALONG_NORMAL,
    "closest_hit's distance against the light's": PHONG_CLOSEST_HIT_DISTANCE,
    "closest_hit's primitive_index against the object's": PHONG_CLOSEST_HIT_INDEX,
}

# ------------------------------------------------------------------------------------------
# The complete solutions, one or two per edition, and the mistakes made in them
# ------------------------------------------------------------------------------------------
RIGHT_2021 = Answers(render=RENDER_RAY_THEN_O_AND_D, any_hit=ANY_HIT_RETURN_IN_LOOP,
                     intersection=INTERSECTION_255, depth=DEPTH_MAX, normal=NORMAL_CHANNELS,
                     phong=PHONG_CLOSEST_HIT_DISTANCE, app_integrator="PhongIntegrator")
RIGHT_2023 = Answers(render=RENDER_RAY_THEN_O_AND_D, any_hit=ANY_HIT_WHILE,
                     intersection=INTERSECTION_RED, depth=DEPTH_IF, normal=NORMAL_CHANNELS,
                     phong=PHONG_START_LIFTED_ALONG_NORMAL, app_integrator="PhongIntegrator")
RIGHT_2023_HELPERS = Answers(render=RENDER_ORIGIN_AND_DIRECTION, any_hit=ANY_HIT_FLAG_AND_BREAK,
                             intersection=INTERSECTION_ONE, depth=DEPTH_MAX,
                             normal=NORMAL_WITH_HELPER, phong=PHONG_SHADOW_RAY_WITH_DISTANCE,
                             helpers=(NORMAL_HELPER,))
RIGHT_2025 = Answers(render=RENDER_RAY_THEN_D, any_hit=ANY_HIT_RETURN_IN_LOOP,
                     intersection=INTERSECTION_RED, depth=DEPTH_IF, normal=NORMAL_CHANNELS,
                     phong=PHONG_CLOSEST_HIT_INDEX)
# Ray(direction=d) works from 2025-26 on, where Ray's default origin is a Vector3D
RIGHT_2025_DIRECTION_ONLY = Answers(render=RENDER_DIRECTION_ONLY, any_hit=ANY_HIT_WHILE,
                                    intersection=INTERSECTION_ONE, depth=DEPTH_MAX,
                                    normal=NORMAL_CHANNELS,
                                    phong=PHONG_START_LIFTED_ALONG_NORMAL)

UNTOUCHED = {"1.1": "every pixel is GREEN",
             "1.2": "answers False for every ray that hits",
             "1.3": "DepthIntegrator.compute_color returned None",
             "1.4": "PhongIntegrator.compute_color returned None"}
LAZY_LOOP = "still paints the colours of Assignment 1.1"
# A mistake of render() costs the steps whose subject it is, 1.1 and 1.2 (the check of its
# rays); the images of 1.3 and 1.4 show it too, but there compute_color is what counts
RENDER_STEPS = ("1.1", "1.2")

FIXTURES = (
    # Complete and right: full points
    Fixture("right_2021_ray_then_o_and_d", "2021-22",
            ("Ray() then ray.o and ray.d", "RGBColor(255, 0, 0)", "any_hit returns in its loop",
             "closest_hit's distance against the light's"), RIGHT_2021),
    Fixture("right_2023_ray_then_o_and_d", "2023-24",
            ("Ray() then ray.o and ray.d", "RED", "any_hit with a while loop",
             "start lifted EPSILON along the normal"), RIGHT_2023),
    Fixture("right_2023_origin_and_direction", "2023-24",
            ("Ray(Vector3D(0, 0, 0), cam.get_direction(x, y))", "RGBColor(1, 0, 0)",
             "any_hit with a flag and break", "shadow ray with the light's distance",
             "a helper function of its own"), RIGHT_2023_HELPERS),
    Fixture("right_2025_ray_then_d", "2025-26",
            ("Ray() then ray.d", "RED", "any_hit returns in its loop",
             "closest_hit's primitive_index against the object's"), RIGHT_2025),
    Fixture("right_2025_direction_only", "2025-26",
            ("Ray(direction=d)", "RGBColor(1, 0, 0)", "any_hit with a while loop",
             "start lifted EPSILON along the normal"), RIGHT_2025_DIRECTION_ONLY),
    # One common mistake each
    Fixture("untouched_2021", "2021-22", ("the base code as handed out",), Answers(),
            UNTOUCHED),
    Fixture("upside_down_2021", "2021-22", ("set_pixel(color, x, height - 1 - y)",),
            replace(RIGHT_2021, render=changed(RENDER_RAY_THEN_O_AND_D,
                                               "set_pixel(pixel, x, y)",
                                               "set_pixel(pixel, x, cam.height - 1 - y)")),
            dict.fromkeys(RENDER_STEPS, "upside down")),
    Fixture("no_shadows_2021", "2021-22", ("Phong without shadow rays",),
            replace(RIGHT_2021, phong=changed(
                PHONG_CLOSEST_HIT_DISTANCE,
                "    shadow = self.scene.closest_hit(Ray(hit.hit_point, wi))\n"
                "    if shadow.has_hit and shadow.hit_distance < r:\n"
                "        continue  # the light is hidden\n", "")),
            {"1.4": "there are no shadows"}),
    Fixture("lazy_loop_2023", "2023-24", ("render() still paints (x/width, y/height, 0)",),
            replace(RIGHT_2023, render=RENDER_LAZY_COLOURS),
            {"1.2": LAZY_LOOP}),
    Fixture("transposed_2023", "2023-24", ("set_pixel(pixel, y, x)",),
            replace(RIGHT_2023, render=changed(RENDER_RAY_THEN_O_AND_D,
                                               "set_pixel(pixel, x, y)",
                                               "set_pixel(pixel, y, x)")),
            dict.fromkeys(RENDER_STEPS, "transposed")),
    Fixture("any_hit_first_object_2023", "2023-24", ("any_hit tests object_list[0] only",),
            # its Phong finds shadows with closest_hit, so only 1.2 depends on any_hit
            replace(RIGHT_2023, any_hit=ANY_HIT_FIRST_OBJECT_ONLY,
                    phong=PHONG_CLOSEST_HIT_DISTANCE),
            {"1.2": "any_hit is wrong for 2 of 12 rays"}),
    Fixture("no_ambient_2023", "2023-24", ("Phong without its ambient term",),
            replace(RIGHT_2023, phong=changed(PHONG_START_LIFTED_ALONG_NORMAL,
                                              "return ambient + diffuse", "return diffuse")),
            {"1.4": "the ambient term, kd (x) i_a, is missing"}),
    Fixture("untouched_2025", "2025-26", ("the base code as handed out",), Answers(),
            UNTOUCHED),
    Fixture("corner_rays_2025", "2025-26", ("rays through the pixels' top-left corners",),
            replace(RIGHT_2025, render=RENDER_CORNER_RAYS),
            dict.fromkeys(RENDER_STEPS, "top-left corners")),
    Fixture("unclamped_depth_2025", "2025-26", ("depth not clamped at 0",),
            replace(RIGHT_2025, depth=changed(DEPTH_IF, "if value < 0:\n    value = 0.0\n",
                                              "")),
            {"1.3": "not clamped at 0"}),
    Fixture("unmapped_normals_2025", "2025-26", ("normals not mapped to [0, 1]",),
            replace(RIGHT_2025, normal=changed(NORMAL_CHANNELS,
                                               "RGBColor((n.x + 1) / 2, (n.y + 1) / 2, "
                                               "(n.z + 1) / 2)", "RGBColor(n.x, n.y, n.z)")),
            {"1.3": "normals are not mapped to [0, 1]"}),
    Fixture("no_inverse_square_2025", "2025-26", ("Phong without 1/r^2",),
            replace(RIGHT_2025, phong=changed(PHONG_CLOSEST_HIT_INDEX, " / d2\n", "\n")),
            {"1.4": "not divided by r^2"}),
)

# ------------------------------------------------------------------------------------------
# Rendering pixels of the course's figures with a submission's own modules
# ------------------------------------------------------------------------------------------
# Run in a submission's folder with python: `python -c FIGURE_PIXELS_SCRIPT FIGURE PIXELS
# OUT` reads the (y, x) pairs of the .npy file PIXELS and saves into OUT the colour of
# each, compute_color of the camera ray through its centre, rendered at 500 x 500 with
# the scenes of the submission's own AppRenderer.py (its scene functions only: importing
# the older editions' AppRenderer.py would render and open a window). The 2025-26
# edition's AppRenderer.py has no Cornell box, so no Figure 1.
FIGURE_PIXELS_SCRIPT = '''\
import ast
import sys

import numpy as np

import PyRT_Common
import PyRT_Core
import PyRT_Integrators

FIGURES = {"figure1": ("cornell", "PhongIntegrator", ()),
           "figure3": ("sphere", "IntersectionIntegrator", ()),
           "figure4_depth": ("sphere", "DepthIntegrator", (5,)),
           "figure4_normal": ("sphere", "NormalIntegrator", ()),
           "figure5": ("sphere", "PhongIntegrator", ())}
SCENE_CALLS = {"cornell": ("cornell_box_scene", (0.75, 2.0)),
               "sphere_test_scene": ("sphere_test_scene", ()),
               "sphere_scene": ("sphere_scene", ())}

figure, pixels, out = sys.argv[1:]
scope = {}
for module in (PyRT_Common, PyRT_Core, PyRT_Integrators):
    scope.update(vars(module))
source = open("AppRenderer.py", encoding="utf-8").read()
functions = [node for node in ast.parse(source).body if isinstance(node, ast.FunctionDef)]
exec(compile(ast.Module(functions, []), "AppRenderer.py", "exec"), scope)
kind, integrator_name, arguments = FIGURES[figure]
if kind == "sphere":
    kind = "sphere_test_scene" if "sphere_test_scene" in scope else "sphere_scene"
function, scene_arguments = SCENE_CALLS[kind]
scene = scope[function](*scene_arguments)
integrator = getattr(PyRT_Integrators, integrator_name)("unused", *arguments)
integrator.add_scene(scene)
camera = scene.camera
colours = []
for y, x in np.load(pixels):
    ray = PyRT_Common.Ray(PyRT_Common.Vector3D(0.0, 0.0, 0.0),
                          camera.get_direction(int(x), int(y)))
    colour = integrator.compute_color(ray)
    colours.append((colour.r, colour.g, colour.b))
np.save(out, np.array(colours, dtype=float).reshape(-1, 3))
'''
