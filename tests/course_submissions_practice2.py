"""Submissions of Practice 2, written from the spec's description of what students write
(its "Practice 2" section): right ones in several styles, each listed mistake, the
untouched handout, and hostile ones.

A submission is written on the Practice 2 handout (the finished Practice 1 with the stubs
of 2.1 and 2.3), or on the course's own 2023-24 base code (tests/data/course_base/) with a
right Practice 1 (course_submissions.RIGHT_2023) and a workbench written as the course's
script, whose module-level code the checks must not run. A student's code is the body of
compute_estimate_cmc and of CMCIntegrator.compute_color, without indentation. FIXTURES
holds each with the points a teaching assistant gives it, and for a failed step a
fragment of the reason.
"""
import textwrap
from dataclasses import dataclass, field
from pathlib import Path

import course_submissions
from helpers import write_texts

WORKBENCH_STUB = "    # ASSIGNMENT 2.1: PUT YOUR CODE HERE\n    return 0\n"
CMC_STUB = "        # ASSIGNMENT 2.3: PUT YOUR CODE HERE\n        pass\n"
MODULES = ("PyRT_Common.py", "PyRT_Core.py", "PyRT_Integrators.py", "AppRenderer.py",
           "AppWorkbench.py")

# ------------------------------------------------------------------------------------------
# compute_estimate_cmc
# ------------------------------------------------------------------------------------------
ESTIMATE_LOOP = """\
estimate = 0
for j in range(len(sample_values_)):
    estimate += sample_values_[j].r / sample_prob_[j]
return estimate / len(sample_values_)
"""
ESTIMATE_SUM = """\
n = len(sample_prob_)
return sum(value.r / prob for value, prob in zip(sample_values_, sample_prob_)) / n
"""
ESTIMATE_NO_DENSITY = """\
return sum(value.r for value in sample_values_) / len(sample_values_)
"""
ESTIMATE_N_MINUS_ONE = """\
total = 0.0
for value, prob in zip(sample_values_, sample_prob_):
    total += value.r / prob
return total / (len(sample_values_) - 1)
"""
ESTIMATE_NO_N = """\
total = 0.0
for value, prob in zip(sample_values_, sample_prob_):
    total += value.r / prob
return total
"""

# The course's workbench as a script: the set-up, the loop and the plot at module level,
# and Assignment 2.2's map read there, which the grader's folder does not have
COURSE_WORKBENCH = '''\
from PyRT_Common import *
import random
import matplotlib.pyplot as plt


def collect_samples(function_list, sample_pos_):
    sample_values = []
    for i in range(len(sample_pos_)):
        value = 1
        for f in function_list:
            value *= f.eval(sample_pos_[i])
        sample_values.append(RGBColor(value, 0, 0))
    return sample_values


def compute_estimate_cmc(sample_prob_, sample_values_):
{body}

env_map = EnvironmentMap('env_maps/arch_nozero.hdr')
l_i = Constant(1)
kd = 1
brdf = Constant(kd)
cosine_term = CosineLobe(1)
integrand = [l_i, brdf, cosine_term]
ground_truth = cosine_term.get_integral() * l_i.get_integral() * kd / (2 * pi)
ns_min, ns_max, ns_step = 20, 101, 20
n_estimates = 1000
ns_vector = np.arange(start=ns_min, stop=ns_max, step=ns_step)
methods_label = [('MC', 'o')]
results = np.zeros((len(ns_vector), len(methods_label)))
for k, ns in enumerate(ns_vector):
    errors = []
    for _ in range(n_estimates):
        sample_set, sample_prob = sample_set_hemisphere(ns, UniformPDF())
        values = collect_samples(integrand, sample_set)
        errors.append(abs(compute_estimate_cmc(sample_prob, values) - ground_truth))
    results[k, 0] = np.mean(errors)
plt.plot(ns_vector, results[:, 0], marker='o')
plt.show()
'''

# ------------------------------------------------------------------------------------------
# CMCIntegrator.compute_color
# ------------------------------------------------------------------------------------------
CMC_COURSE_STYLE = """\
hit = self.scene.closest_hit(ray)
if not hit.has_hit:
    if self.scene.env_map is not None:
        return self.scene.env_map.getValue(ray.d)
    return BLACK
brdf = self.scene.object_list[hit.primitive_index].get_BRDF()
sample_set, sample_prob = sample_set_hemisphere(self.n_samples, UniformPDF())
result = RGBColor(0, 0, 0)
for j in range(self.n_samples):
    omega = center_around_normal(sample_set[j], hit.normal)
    sample_hit = self.scene.closest_hit(Ray(hit.hit_point, omega))
    if sample_hit.has_hit:
        l_i = self.scene.object_list[sample_hit.primitive_index].emission
    elif self.scene.env_map is not None:
        l_i = self.scene.env_map.getValue(omega)
    else:
        l_i = BLACK
    result = result + l_i.multiply(brdf.get_value(omega, Vector3D(0, 0, 0), hit.normal)) / sample_prob[j]
return result / self.n_samples
"""
# Channels as floats, the sample ray started EPSILON along the normal, 1/p as a product
CMC_FLOATS_LIFTED = """\
scene = self.scene
hit = scene.closest_hit(ray)
if not hit.has_hit:
    return BLACK if scene.env_map is None else scene.env_map.getValue(ray.d)
brdf = scene.object_list[hit.primitive_index].get_BRDF()
directions, densities = sample_set_hemisphere(self.n_samples, UniformPDF())
r = g = b = 0.0
start = hit.hit_point + hit.normal * EPSILON
for direction, density in zip(directions, densities):
    wi = center_around_normal(direction, hit.normal)
    found = scene.closest_hit(Ray(start, wi))
    if found.has_hit:
        light = scene.object_list[found.primitive_index].emission
    elif scene.env_map is not None:
        light = scene.env_map.getValue(wi)
    else:
        continue
    f = brdf.get_value(wi, Vector3D(0.0, 0.0, 0.0), hit.normal)
    weight = 1.0 / density
    r += light.r * f.r * weight
    g += light.g * f.g * weight
    b += light.b * f.b * weight
n = self.n_samples
return RGBColor(r / n, g / n, b / n)
"""
# A list of the samples' contributions, added up at the end
CMC_LIST = """\
hit = self.scene.closest_hit(ray)
if hit.has_hit == False:
    if self.scene.env_map == None:
        return BLACK
    return self.scene.env_map.getValue(ray.d)
obj = self.scene.object_list[hit.primitive_index]
samples, probs = sample_set_hemisphere(self.n_samples, UniformPDF())
contributions = []
for k in range(len(samples)):
    wi = center_around_normal(samples[k], hit.normal)
    h = self.scene.closest_hit(Ray(hit.hit_point, wi))
    if h.has_hit:
        li = self.scene.object_list[h.primitive_index].emission
    elif self.scene.env_map != None:
        li = self.scene.env_map.getValue(wi)
    else:
        li = RGBColor(0, 0, 0)
    contributions.append(li.multiply(obj.get_BRDF().get_value(wi, ray.d, hit.normal)) / probs[k])
total = RGBColor(0, 0, 0)
for c in contributions:
    total = total + c
return total / len(contributions)
"""


def cmc_mistake(old, new):
    """CMC_COURSE_STYLE with one line changed."""
    assert CMC_COURSE_STYLE.count(old) == 1, old
    return CMC_COURSE_STYLE.replace(old, new)


ACCUMULATE = ("    result = result + l_i.multiply(brdf.get_value(omega, Vector3D(0, 0, 0), "
              "hit.normal)) / sample_prob[j]\n")
CMC_DOUBLE_COSINE = cmc_mistake(ACCUMULATE, ACCUMULATE.replace(
    ") / sample_prob[j]", ") * Dot(hit.normal, omega) / sample_prob[j]"))
CMC_NO_DENSITY = cmc_mistake(ACCUMULATE, ACCUMULATE.replace(" / sample_prob[j]", ""))
CMC_NO_N = cmc_mistake("return result / self.n_samples\n", "return result\n")
CMC_MISS_BLACK = cmc_mistake("""\
    if self.scene.env_map is not None:
        return self.scene.env_map.getValue(ray.d)
    return BLACK
""", "    return BLACK\n")
CMC_NO_EMISSION = cmc_mistake(
    "        l_i = self.scene.object_list[sample_hit.primitive_index].emission\n",
    "        l_i = BLACK\n")
CMC_DIVIDED_BY_HITS = cmc_mistake("""\
    else:
        l_i = BLACK
    result = result""", """\
    else:
        continue
    found += 1
    result = result""").replace("result = RGBColor(0, 0, 0)\n",
                                "result = RGBColor(0, 0, 0)\nfound = 0\n").replace(
    "return result / self.n_samples", "return result / max(found, 1)")

# ------------------------------------------------------------------------------------------
# Hostile code, a student's who has read the checks
# ------------------------------------------------------------------------------------------
# Tries to make every comparison pass in its own process, then hands back the stub's 0
HOSTILE_PATCHES = """\
import numpy, json, sys
numpy.all = lambda *a, **k: True
numpy.isclose = lambda *a, **k: True
json.dump = lambda *a, **k: None
for name in ("practice2_checks", "monte_carlo_check"):
    module = sys.modules.get(name)
    if module is not None:
        module.judge_rendered = lambda *a, **k: None
return 0
"""
# Writes a result of its own choosing into the file the step hands back, then ends
HOSTILE_FORGES = """\
import os, io, json, zipfile
import numpy
for fd in range(3, 64):
    try:
        if os.readlink(f"/proc/self/fd/{fd}").endswith(".result"):
            with zipfile.ZipFile(os.fdopen(fd, "wb"), "w") as archive:
                for name, key, shape in (("estimate", "estimates", (6,)),
                                         ("curve", "curve", (5,))):
                    buffer = io.BytesIO()
                    numpy.save(buffer, numpy.full(shape, 3.14159))
                    archive.writestr(f"{name}/{key}.npy", buffer.getvalue())
                archive.writestr("meta.json", json.dumps({"checks": {
                    name: {"error": None, "first_color": None, "not_bool": None}
                    for name in ("estimate", "curve")}, "passed": True}))
            os._exit(0)
    except OSError:
        pass
return 0
"""
# Hands back the published checks' answers: the estimates, one per call, in order
HOSTILE_PUBLISHED_ESTIMATES = """\
global _calls
import practice2_scenes
published = practice2_scenes.estimates(practice2_scenes.PUBLISHED)
_calls = globals().get("_calls", -1) + 1
return float(published[_calls % len(published)])
"""
# Hands back the published curve: each estimate pi plus the published average error
HOSTILE_PUBLISHED_CURVE = """\
import math
import practice2_scenes
curve = practice2_scenes.curve(practice2_scenes.PUBLISHED.seed)
if len(sample_prob_) in practice2_scenes.CURVE_NS:
    return math.pi + float(curve[practice2_scenes.CURVE_NS.index(len(sample_prob_))])
return 0
"""
# Hands back the published furnace's expected pixels, one per call, in reading order
HOSTILE_PUBLISHED_IMAGE = """\
import practice2_scenes
expected = practice2_scenes.furnace_expected(practice2_scenes.PUBLISHED).value
count = getattr(type(self), "_calls", 0)
type(self)._calls = count + 1
y, x = divmod(count % expected.size // 3, expected.shape[1])
return RGBColor(*expected[y, x])
"""


@dataclass(frozen=True)
class Fixture:
    """A submission: its name, its base ("handout" or "course 2023-24"), its styles, the
    bodies of compute_estimate_cmc and compute_color (None: the stub), the points it
    deserves per step and a fragment of each failed step's reason."""

    name: str
    base: str
    styles: tuple
    estimate: str = None
    cmc: str = None
    points: dict = field(default_factory=lambda: {"2.1": 50, "2.3": 50})
    reasons: dict = field(default_factory=dict)


UNTOUCHED = {"2.1": "the handout's stub", "2.3": "the handout's pass returns None"}
FIXTURES = (
    Fixture("right_handout_loop", "handout", ("an index loop", "course-style integrator"),
            ESTIMATE_LOOP, CMC_COURSE_STYLE),
    Fixture("right_handout_floats", "handout",
            ("a generator sum", "floats per channel", "sample rays lifted EPSILON"),
            ESTIMATE_SUM, CMC_FLOATS_LIFTED),
    Fixture("right_course_2023_script", "course 2023-24",
            ("the course's base code", "the workbench as a script", "a list of samples"),
            ESTIMATE_LOOP, CMC_LIST),
    Fixture("untouched", "handout", ("the handout as it is",),
            points={"2.1": 0, "2.3": 0}, reasons=UNTOUCHED),
    Fixture("mistake_estimate_no_density", "handout", (), ESTIMATE_NO_DENSITY,
            CMC_COURSE_STYLE, {"2.1": 0, "2.3": 50},
            {"2.1": "does not divide by the density"}),
    Fixture("mistake_estimate_n_minus_one", "handout", (), ESTIMATE_N_MINUS_ONE,
            CMC_COURSE_STYLE, {"2.1": 0, "2.3": 50}, {"2.1": "divides by N - 1"}),
    Fixture("mistake_estimate_no_n", "course 2023-24", (), ESTIMATE_NO_N, CMC_LIST,
            {"2.1": 0, "2.3": 50}, {"2.1": "does not divide by the number of samples"}),
    Fixture("mistake_double_cosine", "handout", (), ESTIMATE_LOOP, CMC_DOUBLE_COSINE,
            {"2.1": 50, "2.3": 0}, {"2.3": "the cosine is counted twice"}),
    Fixture("mistake_no_density", "handout", (), ESTIMATE_LOOP, CMC_NO_DENSITY,
            {"2.1": 50, "2.3": 0}, {"2.3": "does not divide by the density"}),
    Fixture("mistake_no_n", "handout", (), ESTIMATE_LOOP, CMC_NO_N,
            {"2.1": 50, "2.3": 0}, {"2.3": "not divided by their number"}),
    Fixture("mistake_divided_by_hits", "handout", (), ESTIMATE_LOOP, CMC_DIVIDED_BY_HITS,
            {"2.1": 50, "2.3": 0}, {"2.3": "divided by the sample rays that found light"}),
    Fixture("mistake_miss_black", "handout", (), ESTIMATE_LOOP, CMC_MISS_BLACK,
            {"2.1": 50, "2.3": 0}, {"2.3": "not the environment map"}),
    Fixture("mistake_no_emission", "handout", (), ESTIMATE_LOOP, CMC_NO_EMISSION,
            {"2.1": 50, "2.3": 0}, {"2.3": "no light from the emitter"}),
)
# Hostile submissions: each gets what the untouched handout gets
HOSTILE = (
    Fixture("hostile_patches_the_checks", "handout", (), HOSTILE_PATCHES),
    Fixture("hostile_forges_the_result", "handout", (), HOSTILE_FORGES),
    Fixture("hostile_published_estimates", "handout", (), HOSTILE_PUBLISHED_ESTIMATES),
    Fixture("hostile_published_curve", "handout", (), HOSTILE_PUBLISHED_CURVE),
    Fixture("hostile_published_image", "handout", (), None, HOSTILE_PUBLISHED_IMAGE),
)


def _filled(text, stub, body, indent):
    """text with the last occurrence of stub answered by body: the handout's integrators
    also have Integrator.incoming_light's stub of 2.3, before CMCIntegrator's, which the
    fixtures leave as it is (their compute_color finds L_i itself)."""
    assert stub in text, stub
    before, _, after = text.rpartition(stub)
    return before + stub.splitlines(keepends=True)[0] + textwrap.indent(body, indent) + after


def submission_files(fixture, handout):
    """{module: text} of the fixture's submission; handout: the Practice 2 handout's
    folder."""
    if fixture.base == "handout":
        texts = {name: (Path(handout) / name).read_text(encoding="utf-8") for name in MODULES}
        if fixture.estimate is not None:
            texts["AppWorkbench.py"] = _filled(texts["AppWorkbench.py"], WORKBENCH_STUB,
                                               fixture.estimate, "    ")
    else:
        texts = course_submissions.submission_files("2023-24", course_submissions.RIGHT_2023)
        texts["AppWorkbench.py"] = COURSE_WORKBENCH.format(
            body=textwrap.indent(fixture.estimate or "return 0\n", "    "))
    if fixture.cmc is not None:
        texts["PyRT_Integrators.py"] = _filled(texts["PyRT_Integrators.py"], CMC_STUB,
                                               fixture.cmc, "        ")
    return texts


def write_submission(folder, fixture, handout):
    """Writes the fixture's submission into the new folder; returns the folder."""
    return write_texts(folder, submission_files(fixture, handout))
