"""Submissions of Practices 3 and 4 as students hand them in, written from the spec's "What
students write": the course's base code (tests/data/course_base/2023-24) with Practice 1's
answers (course_submissions.RIGHT_2023), the classic Monte Carlo integrator of 2.3, the
Bayesian Monte Carlo integrator of 3.3 and 3.3.2, importance sampling for Practice 4, and a
course-style GaussianProcess.py (tests/data/course_practice3/, with its three methods of
3.1 filled in). Each variant changes
the right code in one place, as a student's style or mistake does; FIXTURES gives the
verdict a teaching assistant gives each, step by step.
"""
from dataclasses import dataclass, field
from pathlib import Path

import course_submissions

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
    Fixture("right", ("p through p_func.eval", "one GP or a list", "pdf= on CMCIntegrator"),
            Variant()),
    Fixture("right_p_number", ("p as a number, multiplied in", "a rotation per sample"),
            Variant(((GP, "* self.p_func.eval(omega_j) /",
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
    Fixture("hostile_reads_framework_gp", ("the handout's stubs, and the framework's "
                                           "GaussianProcess.py read and run",),
            Variant(((GP, "        return res\n", "        return res\n" + HOSTILE_READ),
                     (GP, "        res = BLACK\n", "        return BLACK\n"),
                     (GP, "                Q[i, j] = self.cov_func.eval(self.samples_pos[i], "
                          "self.samples_pos[j])\n", "                pass\n"),
                     (GP, "            z_vec[i] = z / ns_z\n", ""))),
            {"3.1": ""}),
)
