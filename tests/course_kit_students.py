"""Submissions of Practice 1 for the tests of the course kit, made as students make them:
the handout with its stubs filled in.

A student's answers are a dict from a stub (STUB_PLACES) to the code that replaces it,
written without indentation: "render" is the whole render() method of Integrator, the
others the bodies of Scene.any_hit and of the compute_color methods. RIGHT holds the
answers of a correct solution in the course's style; each of VARIANTS changes some of
them: the common mistakes, a second correct solution in another style, and hostile code.
"""
import re
from pathlib import Path

import course_kit.handout

# stub -> (module, the class whose stub it is, the stub's first line)
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

RENDER = """\
def render(self):
    cam = self.scene.camera
    for x in range(cam.width):
        for y in range(cam.height):
            ray = Ray(Vector3D(0, 0, 0), cam.get_direction(x, y))
            pixel = self.compute_color(ray)
            self.scene.set_pixel(pixel, x, y)
        print(str(100 * (x + 1) / cam.width) + '%')
    self.scene.save_image(self.get_filename())
"""

RIGHT = {
    "render": RENDER,
    "any_hit": """\
for obj in self.object_list:
    hit_data = obj.intersect(ray)
    if hit_data.has_hit:
        return True
return False
""",
    "intersection": """\
if self.scene.any_hit(ray):
    return RED
return BLACK
""",
    "depth": """\
hit_data = self.scene.closest_hit(ray)
if hit_data.has_hit:
    c = max(1 - hit_data.hit_distance / self.max_depth, 0)
    return RGBColor(c, c, c)
return BLACK
""",
    "normal": """\
hit_data = self.scene.closest_hit(ray)
if not hit_data.has_hit:
    return BLACK
n = hit_data.normal
c = (n + Vector3D(1, 1, 1)) / 2
return RGBColor(c.x, c.y, c.z)
""",
    "phong": """\
hit_data = self.scene.closest_hit(ray)
if not hit_data.has_hit:
    return BLACK
brdf = self.scene.object_list[hit_data.primitive_index].get_BRDF()
color = brdf.kd.multiply(self.scene.i_a)
for light in self.scene.pointLights:
    light_vector = light.pos - hit_data.hit_point
    distance = Length(light_vector)
    wi = Normalize(light_vector)
    shadow_ray = Ray(hit_data.hit_point, wi, distance)
    if not self.scene.any_hit(shadow_ray):
        diffuse = light.intensity.multiply(brdf.get_value(wi, ray.d * -1, hit_data.normal))
        color = color + diffuse / (distance ** 2)
return color
""",
}


def _loop(body):
    """A render() whose loop over the pixels runs `body` (indented for the inner loop)."""
    return ("def render(self):\n    cam = self.scene.camera\n    for x in range(cam.width):\n"
            "        for y in range(cam.height):\n"
            + "".join(f"            {line}\n" for line in body.splitlines())
            + "    self.scene.save_image(self.get_filename())\n")


VARIANTS = {
    # A correct solution in another style: Ray() then o and d, its own camera formula, the
    # Lazy image kept in the loop of 1.2, a shadow ray lifted along the normal.
    "right_other_style": {
        "render": _loop("""\
if isinstance(self, LazyIntegrator):
    self.scene.set_pixel(RGBColor(x / cam.width, y / cam.height, 0), x, y)
    continue
x_s = 2 * (x + 0.5) / cam.width - 1
y_s = 1 - 2 * (y + 0.5) / cam.height
scale = tan(cam.vertical_fov / 2)
ray = Ray()
ray.o = Vector3D(0, 0, 0)
ray.d = Normalize(Vector3D(x_s * scale * cam.aspect_ratio, y_s * scale, -1))
self.scene.set_pixel(self.compute_color(ray), x, y)"""),
        "any_hit": """\
for index, primitive in enumerate(self.object_list):
    if primitive.intersect(ray).has_hit == True:
        return True
return False
""",
        "depth": """\
hit = self.scene.closest_hit(ray)
if hit.has_hit == False:
    return BLACK
depth = 1 - hit.hit_distance / self.max_depth
if depth < 0:
    depth = 0
return RGBColor(depth, depth, depth)
""",
        "phong": """\
hit = self.scene.closest_hit(ray)
if not hit.has_hit:
    return BLACK
kd = self.scene.object_list[hit.primitive_index].BRDF.kd
result = RGBColor(kd.r * self.scene.i_a.r, kd.g * self.scene.i_a.g, kd.b * self.scene.i_a.b)
for light in self.scene.pointLights:
    to_light = light.pos - hit.hit_point
    r = sqrt(Dot(to_light, to_light))
    wi = to_light / r
    start = hit.hit_point + hit.normal * EPSILON
    if self.scene.any_hit(Ray(start, wi, r)):
        continue
    value = self.scene.object_list[hit.primitive_index].BRDF.get_value(wi, -1 * ray.d, hit.normal)
    result = result + light.intensity.multiply(value) / (r * r)
return result
""",
    },
    "upside_down": {"render": RENDER.replace("set_pixel(pixel, x, y)",
                                             "set_pixel(pixel, x, cam.height - 1 - y)")},
    "transposed": {"render": RENDER.replace("set_pixel(pixel, x, y)", "set_pixel(pixel, y, x)")},
    "corner_rays": {"render": _loop("""\
x_s = 2 * x / cam.width - 1
y_s = 1 - 2 * y / cam.height
scale = tan(cam.vertical_fov / 2)
d = Normalize(Vector3D(x_s * scale * cam.aspect_ratio, y_s * scale, -1))
self.scene.set_pixel(self.compute_color(Ray(Vector3D(0, 0, 0), d)), x, y)""")},
    "any_hit_first_object_only": {"any_hit": """\
for obj in self.object_list:
    return obj.intersect(ray).has_hit
return False
"""},
    "unclamped_depth_and_no_ambient": {
        "depth": RIGHT["depth"].replace("max(1 - hit_data.hit_distance / self.max_depth, 0)",
                                        "1 - hit_data.hit_distance / self.max_depth"),
        "phong": RIGHT["phong"].replace("brdf.kd.multiply(self.scene.i_a)", "RGBColor(0, 0, 0)"),
    },
    "unmapped_normals_and_no_shadows": {
        "normal": RIGHT["normal"].replace("(n + Vector3D(1, 1, 1)) / 2", "n"),
        "phong": RIGHT["phong"].replace("if not self.scene.any_hit(shadow_ray):", "if True:"),
    },
    "no_inverse_square": {"phong": RIGHT["phong"].replace(" / (distance ** 2)", "")},
    "inverse_distance": {"phong": RIGHT["phong"].replace(" / (distance ** 2)", " / distance")},
    # the grey of every ray, a miss's included, whose hit_distance is HUGEVALUE
    "depth_of_misses_too": {"depth": "hit_data = self.scene.closest_hit(ray)\n"
                                     "c = 1 - hit_data.hit_distance / self.max_depth\n"
                                     "return RGBColor(c, c, c)\n"},
    # Hostile code, each in one step. The allocation takes memory that the system hands
    # out zeroed without touching it, so that it meets the memory limit long before the
    # limit of processor time, however loaded the machine.
    "raises": {"intersection": "return RED / 0\n"},
    "calls_sys_exit": {"normal": "import sys\nsys.exit(3)\n"},
    "calls_os_exit": {"depth": "import os\nos._exit(7)\n"},
    "hangs": {"phong": "while True:\n    pass\n"},
    "prints_without_end": {"phong": "while True:\n    print('x' * 1000)\n"},
    "allocates_without_bound": {"depth": "chunks = []\nwhile True:\n"
                                         "    chunks.append(bytes(100_000_000))\n"},
    "starts_a_process": {"normal": "import os\nos.system('true')\n" + RIGHT["normal"]},
}
# Variants whose code needs a path from the test: {OUTSIDE} is replaced by it; and one
# that writes into the checks' expected images, next to the student's modules
WRITES_INTO_THE_CHECKS = {"depth": "try:\n    open('tests/expected/practice1.npz', 'wb')\n"
                                   "except OSError:\n    pass\n" + RIGHT["depth"]}
WRITES_OUTSIDE = {"normal": "try:\n    open({OUTSIDE!r}, 'w').write('x')\nexcept OSError:\n"
                            "    pass\n" + RIGHT["normal"]}
SYNTAX_ERROR_LINE = "    def compute_color(self, ray)\n"  # no colon


def fill(handout_text, stub, answer):
    """handout_text with the stub STUB_PLACES[stub] replaced by answer."""
    _, owner, first_line = STUB_PLACES[stub]
    start = re.search(rf"^class {owner}\b", handout_text, re.MULTILINE).start()
    at = handout_text.index(first_line, start)
    line_start = handout_text.rindex("\n", 0, at) + 1
    indent = handout_text[line_start:at]
    if stub == "render":
        stub_lines = course_kit.handout.RENDER_STUB.count("\n")
    else:
        stub_lines = 2
    end = line_start
    for _ in range(stub_lines):
        end = handout_text.index("\n", end) + 1
    filled = "".join(indent + line if line.strip() else line
                     for line in answer.splitlines(keepends=True))
    return handout_text[:line_start] + filled + handout_text[end:]


def submission_files(handout, answers):
    """The course modules of a submission whose answers are RIGHT updated by answers:
    {module name: text}, from the handout in the folder `handout`."""
    texts = {}
    for stub, answer in {**RIGHT, **answers}.items():
        module = STUB_PLACES[stub][0]
        text = texts.get(module) or (Path(handout) / module).read_text(encoding="utf-8")
        texts[module] = fill(text, stub, answer)
    if "tan" in answers.get("render", ""):
        texts["PyRT_Integrators.py"] = texts["PyRT_Integrators.py"].replace(
            "from PyRT_Common import *\n", "from PyRT_Common import *\nfrom math import tan\n", 1)
    return texts


def write_submission(folder, handout, answers):
    folder = Path(folder)
    folder.mkdir(parents=True)
    for name, text in submission_files(handout, answers).items():
        (folder / name).write_text(text, encoding="utf-8")
    return folder
