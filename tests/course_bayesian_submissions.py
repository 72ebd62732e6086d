"""Submissions of Practices 3 and 4 as students hand them in, written from the spec's "What
students write": the course's base code (tests/data/course_base/2023-24) with Practice 1's
answers (course_submissions.RIGHT_2023), the classic Monte Carlo integrator of 2.3, the
Bayesian Monte Carlo integrator of 3.3 and 3.3.2, importance sampling for Practice 4, and a
course-style GaussianProcess.py (tests/data/course_practice3/, with its three methods of
3.1 filled in). Each variant changes
the right code in one place, as a student's style or mistake does; FIXTURES gives the
verdict a teaching assistant gives each, step by step.
"""
import textwrap
from dataclasses import dataclass, field
from pathlib import Path

import course_hostile
import course_kit.handout
import course_submissions
import course_submissions_practice2

GP_FILE = Path(__file__).resolve().parent / "data" / "course_practice3" / "GaussianProcess.py"
CMC_STUB = "        # ASSIGNMENT 2.3: PUT YOUR CODE HERE\n        pass\n"
BMC_STUB = "        # ASSIGNMENT 3: PUT YOUR CODE HERE\n        pass\n"
CMC_INIT = ("    def __init__(self, n, filename_, experiment_name=''):\n"
            "        filename_mc = filename_ + '_MC_' + str(n) + '_samples' + experiment_name\n"
            "        super().__init__(filename_mc)\n"
            "        self.n_samples = n\n")

LIGHT = '''\
    def light(self, origin, wi):
        h = self.scene.closest_hit(Ray(origin, wi))
        if h.has_hit:
            return self.scene.object_list[h.primitive_index].emission
        if self.scene.env_map is not None:
            return self.scene.env_map.getValue(wi)
        return BLACK

'''
CMC = '''\
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            if self.scene.env_map is None:
                return BLACK
            return self.scene.env_map.getValue(ray.d)
        brdf = self.scene.object_list[hit.primitive_index].get_BRDF()
        samples, probs = sample_set_hemisphere(self.n_samples, self.pdf)
        total = BLACK
        for omega, prob in zip(samples, probs):
            wi = center_around_normal(omega, hit.normal)
            total = total + self.light(hit.hit_point, wi).multiply(
                brdf.get_value(wi, Vector3D(0, 0, 0), hit.normal)) / prob
        return total / self.n_samples
'''
BMC = '''\
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            if self.scene.env_map is None:
                return BLACK
            return self.scene.env_map.getValue(ray.d)
        if isinstance(self.myGP, list):
            gp = self.myGP[int(random() * len(self.myGP))]
        else:
            gp = self.myGP
        alpha = 2 * pi * random()
        brdf = self.scene.object_list[hit.primitive_index].get_BRDF()
        values = []
        for omega in gp.samples_pos:
            wi = center_around_normal(rotate_around_y(alpha, omega), hit.normal)
            values.append(self.value(hit, brdf, wi))
        gp.add_sample_val(values)
        return gp.compute_integral_BMC()

    def value(self, hit, brdf, wi):
        return self.light(hit.hit_point, wi).multiply(
            brdf.get_value(wi, Vector3D(0, 0, 0), hit.normal))
'''
BMCIS = '''

class BMCISIntegrator(BayesianMonteCarloIntegrator):
    def __init__(self, n, myGP, filename_, experiment_name=''):
        super().__init__(n, myGP, filename_, '_IS' + experiment_name)

    def value(self, hit, brdf, wi):
        return self.light(hit.hit_point, wi).multiply(brdf.kd)
'''
CMCIS = '''

class CMCISIntegrator(CMCIntegrator):
    def __init__(self, n, filename_, experiment_name=''):
        super().__init__(n, filename_, '_IS' + experiment_name)
        self.pdf = CosinePDF(1)
'''


# The workbench as the course's script (Practice 2's, with Assignment 3.2's BMC and
# Practice 4's MC IS and BMC IS at module level): no function computes an estimate
COURSE_WORKBENCH = course_submissions_practice2.COURSE_WORKBENCH.format(
    body=textwrap.indent(course_submissions_practice2.ESTIMATE_LOOP, "    ")).replace(
    "from PyRT_Common import *\n", "from PyRT_Common import *\nfrom GaussianProcess import *\n"
) + '''
bmc_errors = np.zeros(len(ns_vector))
for k, ns in enumerate(ns_vector):
    errors = []
    for _ in range(10):
        sample_set, sample_prob = sample_set_hemisphere(ns, UniformPDF())
        myGP = GP(SobolevCov(), Constant(1))
        myGP.add_sample_pos(sample_set)
        myGP.add_sample_val(collect_samples(integrand, sample_set))
        errors.append(abs(myGP.compute_integral_BMC().r - ground_truth))
    bmc_errors[k] = np.mean(errors)
plt.plot(ns_vector, bmc_errors, marker='x', label='BMC')

f_part = [CosineLobe(3)]
ground_truth_4 = CosineLobe(4).get_integral()
for k, ns in enumerate(ns_vector):
    sample_set, sample_prob = sample_set_hemisphere(ns, CosinePDF(1))
    mc_is = compute_estimate_cmc(sample_prob, collect_samples(f_part + [CosineLobe(1)],
                                                              sample_set))
    gp_is = GP(SobolevCov(), CosineLobe(1))
    gp_is.add_sample_pos(sample_set)
    gp_is.add_sample_val(collect_samples(f_part, sample_set))
    bmc_is = gp_is.compute_integral_BMC().r
plt.show()
'''
# The workbench of the handouts, finished: its functions are called
HANDOUT_WORKBENCH = (course_kit.handout.REPO / "AppWorkbench.py").read_text(encoding="utf-8")
WORKBENCH = "AppWorkbench.py"


@dataclass(frozen=True)
class Variant:
    """Changes of the right submission: (module, old, new) replacements, each of a text
    that the module holds once."""

    changes: tuple = ()


@dataclass(frozen=True)
class Fixture:
    """A submission: its name, the styles or mistake it shows, its changes, and per
    failed step a fragment of the reason expected (a step left out passes)."""

    name: str
    styles: tuple
    variant: Variant
    fails: dict = field(default_factory=dict)


def right_files():
    """{module: text} of the right submission."""
    texts = course_submissions.submission_files("2023-24", course_submissions.RIGHT_2023)
    integrators = texts["PyRT_Integrators.py"]
    integrators = integrators.replace(CMC_INIT, CMC_INIT.replace(
        "experiment_name=''):", "experiment_name='', pdf=UniformPDF()):") +
        "        self.pdf = pdf\n")
    integrators = integrators.replace(CMC_STUB, CMC + "\n" + LIGHT.rstrip("\n") + "\n")
    # the BMC integrator's own light, its hit named otherwise
    integrators = integrators.replace(BMC_STUB, BMC + "\n" + LIGHT.replace(
        "h = ", "found = ").replace("h.", "found.").rstrip("\n") + "\n")
    texts["PyRT_Integrators.py"] = integrators + BMCIS + CMCIS
    texts["GaussianProcess.py"] = GP_FILE.read_text(encoding="utf-8")
    texts[WORKBENCH] = COURSE_WORKBENCH
    return texts


def files(variant):
    """{module: text} of a variant of the right submission."""
    texts = right_files()
    for module, old, new in variant.changes:
        assert texts[module].count(old) == 1, (module, old)
        texts[module] = texts[module].replace(old, new)
    return texts


def write(folder, variant):
    folder = Path(folder)
    folder.mkdir(parents=True)
    for module, text in files(variant).items():
        (folder / module).write_text(text, encoding="utf-8")
    return folder


GP, INTEGRATORS = "GaussianProcess.py", "PyRT_Integrators.py"
HOSTILE_READ = '''

try:  # the framework's GaussianProcess.py, found above the kit's modules, run here
    import pathlib as _pathlib, sys as _sys
    _found = [_parent for _module in list(_sys.modules.values())
              if "course_kit" in (getattr(_module, "__file__", None) or "")
              for _parent in _pathlib.Path(_module.__file__).resolve().parents
              if (_parent / "GaussianProcess.py").is_file()
              and (_parent / "course_kit").is_dir()]
    _sys.path.insert(0, str(_found[0]))
    exec(compile(open(_found[0] / "GaussianProcess.py").read(), "GP", "exec"), globals())
except Exception as _error:
    print("could not read the framework's GaussianProcess.py:", repr(_error))
'''
FIXTURES = (
    Fixture("right", ("p through p_func.eval", "one GP or a list", "pdf= on CMCIntegrator",
                      "the workbench as the course's script"), Variant()),
    Fixture("right_p_number", ("p as a number, multiplied in", "a rotation per sample",
                               "the handout's workbench"),
            Variant(((WORKBENCH, COURSE_WORKBENCH, HANDOUT_WORKBENCH),
                     (GP, "* self.p_func.eval(omega_j) /",
                      "* (self.p_func.eval(omega_j) if isinstance(self.p_func, Function) "
                      "else self.p_func) /"),
                     (INTEGRATORS, "rotate_around_y(alpha, omega)",
                      "rotate_around_y(2 * pi * np.random.rand(), omega)")))),
    Fixture("q_without_noise", ("Q without the noise",),
            Variant(((GP, "        Q = Q + np.identity(n) * (self.noise ** 2)\n", ""),)),
            {"3.1": "no noise"}),
    Fixture("z_without_p", ("z without p",),
            Variant(((GP, "* self.p_func.eval(omega_j) / probab[j]", "/ probab[j]"),)),
            {"3.1": "leaves out p"}),
    Fixture("z_wrong_density", ("z by the wrong density",),
            Variant(((GP, "/ probab[j]", "* probab[j]"),)),
            {"3.1": "multiplies by the density"}),
    Fixture("double_cosine", ("a double cosine in BMC",),
            Variant(((INTEGRATORS,
                      "            brdf.get_value(wi, Vector3D(0, 0, 0), hit.normal))\n",
                      "            brdf.get_value(wi, Vector3D(0, 0, 0), hit.normal)) * "
                      "Dot(hit.normal, wi)\n"),)),
            {"3.3": "counted twice"}),
    Fixture("bmc_emission_forgotten", ("L_i of a sample ray's hit forgotten in BMC",),
            Variant(((INTEGRATORS, "return self.scene.object_list[found.primitive_index]"
                                   ".emission", "return BLACK"),)),
            {"3.3": "no light from the walls"}),
    Fixture("one_rotation_no_pool", ("one rotation for every pixel without a pool",),
            Variant(((INTEGRATORS, "gp = self.myGP[int(random() * len(self.myGP))]",
                      "gp = self.myGP[0]"),
                     (INTEGRATORS, "alpha = 2 * pi * random()", "alpha = 0.0"))),
            {"3.3.2": "never used"}),
    Fixture("bmcis_keeps_cosine", ("values that keep the cosine in BMC IS",),
            Variant(((INTEGRATORS, "return self.light(hit.hit_point, wi).multiply(brdf.kd)",
                      "return self.light(hit.hit_point, wi).multiply(brdf.get_value(wi, "
                      "Vector3D(0, 0, 0), hit.normal))"),)),
            {"4.2": "keep the cosine"}),
    Fixture("mc_is_without_1_over_p", ("MC IS without the 1/p",),
            Variant(((INTEGRATORS, "hit.normal)) / prob", "hit.normal))"),)),
            {"4.1": "does not divide by the density"}),
    Fixture("workbench_bmc_stub", ("the handout's workbench, its BMC estimate the stub's",),
            Variant(((WORKBENCH, COURSE_WORKBENCH, HANDOUT_WORKBENCH.replace(
                "    gp.add_sample_pos(sample_pos_)\n    gp.add_sample_val(sample_values_)\n"
                "    return gp.compute_integral_BMC().r\n", "    return 0\n")),)),
            {"3.2": "the handout's stub"}),
    Fixture("workbench_script_without_bmc", ("the course's script without 3.2's BMC",),
            Variant(((WORKBENCH, COURSE_WORKBENCH, COURSE_WORKBENCH.replace(
                COURSE_WORKBENCH[COURSE_WORKBENCH.index("bmc_errors = "):
                                 COURSE_WORKBENCH.index("f_part = ")], "")),)),
            {"3.2": "never calls GP with p = 1"}),
    Fixture("workbench_mc_is_uniform", ("the handout's workbench, MC IS sampling uniformly",),
            Variant(((WORKBENCH, COURSE_WORKBENCH, HANDOUT_WORKBENCH.replace(
                'Method("MC IS", "v", CosinePDF(1), "cos")',
                'Method("MC IS", "v", UniformPDF(), "uniform")')),)),
            {"4.1": "does not sample from the cosine"}),
    Fixture("workbench_bmcis_keeps_cosine", ("the handout's workbench, BMC IS's values "
                                             "keeping the cosine",),
            Variant(((WORKBENCH, COURSE_WORKBENCH, HANDOUT_WORKBENCH.replace(
                "value_functions=[CosineLobe(3)]",
                "value_functions=[CosineLobe(3), CosineLobe(1)]")),)),
            {"4.2": "keep the cosine"}),
    Fixture("hostile_reads_framework_gp", ("the handout's stubs, and the framework's "
                                           "GaussianProcess.py read and run",),
            Variant(((GP, "        return res\n", "        return res\n" + HOSTILE_READ),
                     (GP, "        res = BLACK\n", "        return BLACK\n"),
                     (GP, "                Q[i, j] = self.cov_func.eval(self.samples_pos[i], "
                          "self.samples_pos[j])\n", "                pass\n"),
                     (GP, "            z_vec[i] = z / ns_z\n", ""))),
            {step: "refused: read the framework's answers"
             for step in ("3.1", "3.2", "3.3", "3.3.2", "4.1", "4.2")}),
)

# ------------------------------------------------------------------------------------------
# Hostile code, a student's who has read the checks, on the untouched Practice 3 handout:
# each gets what the untouched handout gets (nothing), in every step of Practices 3 and 4
# ------------------------------------------------------------------------------------------
# Makes every comparison pass and the checks judge nothing, in the step's own process
HOSTILE_PATCHES = '''
import json as _json, sys as _sys
import numpy as _numpy
for _name in ("practice3_checks", "practice2_checks", "practice1_checks",
              "monte_carlo_check", "handback"):
    _module = _sys.modules.get(_name)
    if _module is not None:
        for _function in ("judge_rendered", "run_check", "read"):
            setattr(_module, _function, lambda *a, **k: None)
_numpy.all = _numpy.allclose = _numpy.array_equal = lambda *a, **k: True
_json.dump = lambda *a, **k: None
'''
# Hands back, as its own, the published draw's answers: Q^-1, the seeded z, the sums and
# the furnace's pixels, in the order the published checks ask for them
HOSTILE_PUBLISHED_GP = '''
import itertools as _itertools
import practice3_scenes as _scenes
_published = _scenes.PUBLISHED
_sums = _itertools.cycle([_scenes.bmc_sum(case) for case in _published.sums])


def _published_inv_Q(self):
    return _scenes.inverse_q(_published.positions, _published.noise)


def _published_z(self):
    cosine = isinstance(self.p_func, CosineLobe)
    return _scenes.course_z(_published.seed + cosine, _published.positions, int(cosine))


GP.compute_inv_Q = _published_inv_Q
GP.compute_z = _published_z
GP.compute_integral_BMC = lambda self: RGBColor(*next(_sums))
'''
HOSTILE_PUBLISHED_IMAGE = '''
import practice3_scenes as _scenes
_furnace = _scenes.furnace_expected(_scenes.PUBLISHED,
                                    _scenes.cos_sum(_scenes.PUBLISHED.pool[0]) / pi).value


def _published_pixel(self, ray):
    count = getattr(type(self), "_calls", 0)
    type(self)._calls = count + 1
    y, x = divmod(count % (_furnace.size // 3), _furnace.shape[1])
    return RGBColor(*_furnace[y, x])


for _class in (BayesianMonteCarloIntegrator, BMCISIntegrator, CMCIntegrator):
    _class.compute_color = _published_pixel
'''


@dataclass(frozen=True)
class Hostile:
    """A hostile submission: its name, and per module the code added at its end."""

    name: str
    added: dict


HOSTILE = (
    Hostile("hostile_patches_the_checks", {GP: HOSTILE_PATCHES, INTEGRATORS: HOSTILE_PATCHES}),
    Hostile("hostile_forges_the_result", {INTEGRATORS: course_hostile.FORGES_THE_RESULT}),
    Hostile("hostile_hands_back_its_own_data", {
        INTEGRATORS: course_hostile.HANDS_BACK_ITS_OWN_DATA.replace(
            "{FILL}", "numpy.zeros((_size, _size, 3))")}),
    Hostile("hostile_published_answers", {GP: HOSTILE_PUBLISHED_GP,
                                          INTEGRATORS: HOSTILE_PUBLISHED_IMAGE}),
)


def write_hostile(folder, hostile, handout):
    """The hostile submission in the new folder: the modules of the untouched handout
    (its folder), each of hostile.added ending with the code added."""
    folder = Path(folder)
    folder.mkdir(parents=True)
    for module in (*course_submissions.MODULES, GP, "AppWorkbench.py"):
        text = (Path(handout) / module).read_text(encoding="utf-8")
        (folder / module).write_text(text + "\n" + hostile.added.get(module, ""),
                                     encoding="utf-8")
    return folder
