"""The course kit of Practices 3 and 4: their handouts, the checks' closed forms and
judges, and the grader's verdicts on course-style submissions (tests/
course_bayesian_submissions.py), right, mistaken, untouched and hostile."""
import math
import random
import shutil
import sys

import numpy as np
import pytest

import course_bayesian_submissions as submissions
import course_kit.autograder
import course_kit.grader
import course_kit.handout
import course_kit.isolation
import course_kit.sandbox
from helpers import matrix_on_the_main_python_only

sys.path.insert(0, str(course_kit.handout.CHECKS))
import practice3_checks as checks  # noqa: E402  (found through the line above)
import practice3_render as render  # noqa: E402
import practice3_scenes as scenes  # noqa: E402
from test_course_autograder import autograder_root, run_autograder  # noqa: E402

S = 1.4
K_SAME = 2 ** (2 * S - 1) / S  # k(omega, omega)
SUPPORTED = course_kit.isolation.unsupported() is None


# ------------------------------------------------------------------------------------------
# The handouts
# ------------------------------------------------------------------------------------------
def test_practice3_handout_has_the_three_stubs_and_the_course_set_up_of_z():
    files = course_kit.handout.handout_files(3)
    gp = files["GaussianProcess.py"].decode()
    for solution in ("self.cov_func.eval(self.samples_pos[i], self.samples_pos[j])",
                     "total += self.cov_func.eval", "res = res + self.samples_val[i]"):
        assert solution not in gp
    for given in ("ns_z = 50000", "sample_set_hemisphere(ns_z, UniformPDF())",
                  "z_vec = np.zeros(ns)", "Q = np.zeros((n, n))", "return BLACK",
                  "# ASSIGNMENT 3.1: PUT YOUR CODE HERE"):
        assert given in gp
    assert "FRAMEWORK ONLY" not in gp and "pyrt." not in gp and "BEGIN" not in gp
    integrators = files["PyRT_Integrators.py"].decode()
    assert "# ASSIGNMENT 3.3: PUT YOUR CODE HERE" in integrators
    assert "gp.compute_integral_BMC()" not in integrators
    assert "tests/test_practice3.py" in files and "tests/practice3_scenes.py" in files


def test_practice4_handout_has_practice3_finished_and_its_own_stubs():
    files = course_kit.handout.handout_files(4)
    gp = files["GaussianProcess.py"].decode()
    assert "self.cov_func.eval(self.samples_pos[i], self.samples_pos[j])" in gp
    integrators = files["PyRT_Integrators.py"].decode()
    assert "# ASSIGNMENT 4.1: PUT YOUR CODE HERE" in integrators
    assert "# ASSIGNMENT 4.2: PUT YOUR CODE HERE" in integrators
    assert "experiment_name, pdf=CosinePDF(1))\n" not in integrators
    assert "return l_i.multiply(brdf.kd)" not in integrators
    assert "gp.compute_integral_BMC()" in integrators  # 3.3 finished


@pytest.mark.parametrize("practice", [3, 4])
def test_the_handouts_modules_import_and_their_integrators_construct(practice, tmp_path,
                                                                     monkeypatch):
    folder = course_kit.handout.write_handout(tmp_path / "handout", practice)
    monkeypatch.syspath_prepend(str(folder))
    for name in ("PyRT_Common", "PyRT_Core", "PyRT_Integrators", "GaussianProcess"):
        monkeypatch.delitem(sys.modules, name, raising=False)
    import GaussianProcess
    import PyRT_Integrators
    integrator = PyRT_Integrators.CMCIntegrator(4, "x", pdf=PyRT_Integrators.CosinePDF(1))
    assert integrator.get_filename().endswith("x_MC_cos1_4_samples")
    gp = GaussianProcess.GP(GaussianProcess.SobolevCov(), GaussianProcess.Constant(1))
    assert gp.noise == 0.01 and gp.weights is None
    for name in ("PyRT_Common", "PyRT_Core", "PyRT_Integrators", "GaussianProcess"):
        sys.modules.pop(name, None)


# ------------------------------------------------------------------------------------------
# The checks' closed forms
# ------------------------------------------------------------------------------------------
def test_exact_z_has_the_closed_forms_at_the_pole_and_the_horizon():
    pole, horizon = (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)
    z = scenes.exact_z([pole, horizon], 0)
    assert z[0] == pytest.approx(2 * math.pi / S * (2 ** (2 * S - 1) - 2 ** (S - 1)),
                                 rel=1e-10)
    assert z[1] == pytest.approx(math.pi * 2 ** (2 * S - 1) / S, rel=1e-10)
    # p = cos at the pole: 2 pi (K_SAME / 2 - the integral of (2 - 2u)^(s-1) u du), by hand
    # with v = 1 - u: 2^(s-1) (1/(s) - 1/(s+1))
    by_hand = 2 * math.pi * (K_SAME / 2 - 2 ** (S - 1) * (1 / S - 1 / (S + 1)))
    assert scenes.exact_z([pole], 1)[0] == pytest.approx(by_hand, rel=1e-10)
    assert by_hand == pytest.approx(5.34657, abs=5e-6)  # the spec's rounded figure


def test_one_sample_at_the_pole_has_the_specs_weight():
    weight = scenes.weights([(0.0, 1.0, 0.0)], 0)[0]
    pole = 2 * math.pi / S * (2 ** (2 * S - 1) - 2 ** (S - 1))
    assert weight == pytest.approx(pole / (K_SAME + 1e-4), rel=1e-10)
    assert weight == pytest.approx(3.90214, abs=1e-5)


def test_the_kits_weights_are_the_framework_gps():
    import GaussianProcess
    draws = random.Random(3)
    for p_exponent, p_func in ((0, GaussianProcess.Constant(1)),
                               (1, GaussianProcess.CosineLobe(1))):
        positions = [scenes._direction(draws, bool(p_exponent)) for _ in range(15)]
        gp = GaussianProcess.GP(GaussianProcess.SobolevCov(), p_func)
        gp.add_sample_pos([GaussianProcess.Vector3D(*p) for p in positions])
        assert np.allclose(scenes.weights(positions, p_exponent), gp.weights,
                           rtol=1e-7, atol=1e-9)


def test_course_z_is_the_courses_loop_after_the_seed():
    position = (0.6, 0.8, 0.0)
    draws = random.Random(11)
    total = 0.0
    for _ in range(scenes.COURSE_NS_Z):
        u1, u2 = draws.random(), draws.random()
        s = math.sqrt(1 - u2 * u2)
        x = (math.sin(2 * math.pi * u1) * s, u2, math.cos(2 * math.pi * u1) * s)
        r = math.sqrt(sum((a - b) ** 2 for a, b in zip(position, x)))
        total += (K_SAME - r ** (2 * S - 2)) * u2 / (1 / (2 * math.pi))
    assert scenes.course_z(11, [position], 1)[0] == pytest.approx(
        total / scenes.COURSE_NS_Z, rel=1e-12)


# ------------------------------------------------------------------------------------------
# The judges, on data
# ------------------------------------------------------------------------------------------
def _z_rendered(z_one, z_cos):
    rendered = render.Rendered("z")
    rendered.arrays.update(z_one=np.asarray(z_one), z_cos=np.asarray(z_cos))
    return rendered


def test_a_z_of_other_directions_passes_and_one_without_p_fails():
    draw = scenes.PUBLISHED
    other = _z_rendered(scenes.course_z(draw.seed + 5, draw.positions, 0),
                        scenes.course_z(draw.seed + 6, draw.positions, 1))
    assert checks.judge_rendered(other, draw, None).passed
    without_p = _z_rendered(scenes.course_z(draw.seed, draw.positions, 0),
                            scenes.course_z(draw.seed + 1, draw.positions, 0))
    check = checks.judge_rendered(without_p, draw, None)
    assert not check.passed and "leaves out p" in check.reason


def _pool_rendered(draw, chosen, angles):
    rendered = render.Rendered("bmc_pool")
    directions, picked = scenes.turned_sets(draw, chosen, angles)
    rendered.arrays.update(directions=directions, chosen=picked,
                           image=np.zeros((draw.size, draw.size, 3)))
    return rendered


def test_the_pool_check_wants_every_gp_and_a_rotation_per_hit():
    draw = scenes.PUBLISHED
    count = int(scenes.floor_pixels(draw).sum())
    draws = random.Random(5)
    chosen = [draws.randrange(scenes.POOL) for _ in range(count)]
    angles = [draws.random() * 2 * math.pi for _ in range(count)]
    assert checks.judge_rendered(_pool_rendered(draw, chosen, angles), draw, None).passed
    one_angle = checks.judge_rendered(_pool_rendered(draw, chosen, [0.3] * count), draw,
                                      None)
    assert not one_angle.passed and "same sample set" in one_angle.reason
    no_pool = checks.judge_rendered(_pool_rendered(draw, [0] * count, angles), draw, None)
    assert not no_pool.passed and "never used" in no_pool.reason


def _method_rendered(name, pdf, p, f, defines=True):
    rendered = render.Rendered(name)
    script = np.zeros(len(render.SCRIPT_CALLS))
    script[-1] = defines
    rendered.arrays.update(pdf=pdf, p=p, f=f, script=script)
    return rendered


def test_the_workbenchs_bmc_is_must_model_cos3_alone():
    draw = scenes.PUBLISHED
    y = np.asarray(draw.pool[0].positions)[:, 1]
    assert checks.judge_rendered(_method_rendered("workbench_bmc_is", y / math.pi, y, y ** 3),
                                 draw, None).passed
    check = checks.judge_rendered(_method_rendered("workbench_bmc_is", y / math.pi, y,
                                                   y ** 4), draw, None)  # the cosine kept
    assert not check.passed and "keep the cosine" in check.reason
    check = checks.judge_rendered(_method_rendered(
        "workbench_mc_is", np.full_like(y, 1 / (2 * math.pi)), y * np.nan, y * np.nan), draw,
        None)
    assert not check.passed and "MC IS does not sample from the cosine" in check.reason


def test_a_script_workbench_is_judged_on_the_courses_calls():
    draw = scenes.PUBLISHED
    nothing = np.full(len(draw.pool[0].positions), np.nan)
    rendered = _method_rendered("workbench_bmc_is", nothing, nothing, nothing, defines=False)
    calls = dict.fromkeys(render.SCRIPT_CALLS, 1.0)
    calls["the handout's function"] = 0.0
    rendered.arrays["script"] = np.array(list(calls.values()))
    check = checks.judge_rendered(rendered, draw, None)
    assert check.passed and "a script with no practice4_methods()" in check.note
    calls["GP with p = CosineLobe"] = 0.0  # BMC IS's GP of p = 1
    rendered.arrays["script"] = np.array(list(calls.values()))
    check = checks.judge_rendered(rendered, draw, None)
    assert not check.passed and "never calls GP with p = CosineLobe" in check.reason


def test_a_step_may_not_open_the_frameworks_gaussian_process(tmp_path):
    hook = course_kit.isolation.guard(tmp_path, refused := [])
    framework = course_kit.handout.REPO / "GaussianProcess.py"
    with pytest.raises(PermissionError):
        hook("open", (str(framework), "r", 0))
    with pytest.raises(PermissionError):
        hook("open", (str(course_kit.handout.REPO / "pyrt" / "gp_integrals.py"), "rb", 0))
    hook("open", (str(tmp_path / "GaussianProcess.py"), "r", 0))  # the student's own
    assert len(refused) == 2 and "framework's answers" in refused[0]


# ------------------------------------------------------------------------------------------
# The grader
# ------------------------------------------------------------------------------------------
def write_untouched_and_hostile(root, folder):
    """The untouched handouts of Practices 3 and 4 and the hostile submissions (on the
    first), in folder; their handouts in root."""
    for practice, name in ((3, "untouched"), (4, "untouched4")):
        handout = course_kit.handout.write_handout(root / f"handout{practice}", practice)
        (folder / name).mkdir(parents=True)
        for module in course_kit.handout.PRACTICES[practice].modules:
            shutil.copyfile(handout / module, folder / name / module)
    for hostile in submissions.HOSTILE:
        submissions.write_hostile(folder / hostile.name, hostile, root / "handout3")


def grade_both(root, folder, isolation, seed):
    """{practice: {submission: record}} of the submissions of folder graded for Practices 3
    and 4 in isolation, on inputs drawn with seed + the practice; results in root."""
    return {practice: {record["submission"]: record for record in
                       course_kit.grader.grade_folder(
                           folder, root / f"results{practice}",
                           course_kit.grader.load_config(practice=practice), jobs=2,
                           progress=False, isolation=isolation,
                           draws=random.Random(seed + practice))}
            for practice in (3, 4)}


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """{practice: {submission: record}} of FIXTURES, the untouched handouts of Practices 3
    and 4 and the hostile submissions, graded in processes of their own on inputs drawn
    with a seed."""
    if not SUPPORTED:
        pytest.skip(str(course_kit.isolation.unsupported()))
    matrix_on_the_main_python_only()
    root = tmp_path_factory.mktemp("bayesian")
    folder = root / "submissions"
    for fixture in submissions.FIXTURES:
        submissions.write(folder / fixture.name, fixture.variant)
    write_untouched_and_hostile(root, folder)
    return grade_both(root, folder, "process", 40)


@pytest.mark.parametrize("practice", [3, 4])
@pytest.mark.parametrize("fixture", submissions.FIXTURES, ids=lambda f: f.name)
def test_each_submission_gets_the_verdict_it_deserves(graded, practice, fixture):
    record = graded[practice][fixture.name]
    for step in record["steps"]:
        expected = fixture.fails.get(step["step"])
        if expected is None:
            assert step["passed"], (step["step"], step["reason"])
        else:
            assert not step["passed"] and expected in step["reason"], step["reason"]


@pytest.mark.parametrize("practice", [3, 4])
def test_the_untouched_handout_gets_nothing(graded, practice):
    record = graded[practice]["untouched"]
    assert record["total"] == 0
    assert all("stub" in step["reason"] or "not drawn from the cosine" in step["reason"]
               for step in record["steps"]), [step["reason"] for step in record["steps"]]


def test_practice4s_handout_gets_nothing_for_practice_4_and_all_of_practice_3(graded):
    assert graded[4]["untouched4"]["total"] == 0
    record = graded[3]["untouched4"]  # Practice 3 finished, course-style, FRAMEWORK ONLY cut
    assert record["total"] == record["max_total"], [step["reason"] for step in record["steps"]]


@pytest.mark.parametrize("practice", [3, 4])
def test_reading_the_frameworks_answers_costs_every_step(graded, practice):
    record = graded[practice]["hostile_reads_framework_gp"]
    assert record["total"] == 0
    for step in record["steps"]:
        assert "refused: read the framework's answers" in step["reason"]
        assert "no step of a submission that reads the framework's answers" in step["reason"]


@pytest.mark.parametrize("practice", [3, 4])
@pytest.mark.parametrize("hostile", submissions.HOSTILE, ids=lambda h: h.name)
def test_a_hostile_submission_gets_what_the_untouched_handout_gets(graded, practice, hostile):
    steps = graded[practice][hostile.name]["steps"]
    untouched = graded[practice]["untouched"]["steps"]
    assert [s["points"] for s in steps] == [s["points"] for s in untouched], [
        s["reason"] for s in steps]
    assert [s["points"] for s in untouched] == [0] * len(untouched)


@pytest.fixture(scope="module")
def graded_in_bubblewrap(tmp_path_factory):
    """{practice: {submission: record}} of the untouched handouts, the hostile submissions
    and the right one, graded in bubblewrap's sandbox."""
    matrix_on_the_main_python_only()
    if course_kit.sandbox.why_no_bubblewrap():
        pytest.skip("needs bubblewrap's sandbox: " + course_kit.sandbox.why_no_bubblewrap())
    root = tmp_path_factory.mktemp("bayesian_bwrap")
    folder = root / "submissions"
    submissions.write(folder / "right", submissions.FIXTURES[0].variant)
    write_untouched_and_hostile(root, folder)
    return grade_both(root, folder, "bubblewrap", 50)


@pytest.mark.parametrize("practice", [3, 4])
def test_in_bubblewrap_the_hostile_get_what_the_untouched_handout_gets(graded_in_bubblewrap,
                                                                       practice):
    records = graded_in_bubblewrap[practice]
    assert records["right"]["total"] == records["right"]["max_total"] == 100
    untouched = [s["points"] for s in records["untouched"]["steps"]]
    for hostile in submissions.HOSTILE:
        assert [s["points"] for s in records[hostile.name]["steps"]] == untouched, hostile


@pytest.mark.parametrize("practice", [3, 4])
def test_the_autograder_grades_the_workbench_too(practice, tmp_path):
    if not SUPPORTED:
        pytest.skip(str(course_kit.isolation.unsupported()))
    archive = course_kit.autograder.write_zip(tmp_path / "ag.zip", practice=practice)
    root = autograder_root(archive, tmp_path / "root")
    for name, text in submissions.files(submissions.FIXTURES[0].variant).items():
        (root / "submission" / name).write_text(text)
    results, ran = run_autograder(root, isolation="process")
    assert results["score"] == 100, ran.stdout[-2000:]
    assert [test["number"] for test in results["tests"]] == {
        3: ["3.1", "3.2", "3.3", "3.3.2"], 4: ["4.1", "4.2"]}[practice]
