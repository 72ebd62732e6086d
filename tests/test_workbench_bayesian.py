"""AppWorkbench.py for Practices 3 and 4: the BMC estimate, BMC's error below MC's on the
workbench's integrals (seeded, with margins a correct GP cannot miss), the GP's belief, the
plot and the command line of --practice 3 and 4, and the handout's stubs of the workbench.

Margins: at N = 40 the course's figures read MC 0.19 against BMC 0.05 (Practice 3), and MC
0.25, MC IS 0.11, BMC 0.03, BMC IS 0.014 (Practice 4): a correct BMC's error lies well
below half of MC's; a GP with wrong weights (z off by a few per cent, or the weights of
another sample set) gives errors near or above MC's."""
import math
import random

import matplotlib.pyplot as plt
import numpy as np
import pytest

import AppWorkbench
from AppWorkbench import (INTEGRANDS, PRACTICE4_INTEGRAND, Method, absolute_errors,
                          bmc_absolute_errors, collect_samples, compute_estimate_bmc,
                          plot_errors, practice3_methods, practice4_methods)
from GaussianProcess import GP, SobolevCov
from helpers import REPO, TIGHT, global_generator_kept, run_python  # noqa: F401
from PyRT_Common import Constant, CosineLobe, UniformPDF, Vector3D, sample_set_hemisphere

SCRIPT = REPO / "AppWorkbench.py"
# A small run of the script: N = 10, 20, 30, 50 MC and 5 BMC estimates each
SMALL = ["--ns-min", "10", "--ns-max", "31", "--ns-step", "10", "--estimates", "50",
         "--bmc-estimates", "5"]


def mean_error(integrand, method, ns, estimates):
    if method.is_bmc:
        return np.mean(bmc_absolute_errors(integrand, method, ns, estimates).errors)
    return np.mean(absolute_errors(integrand, method.pdf, ns, estimates))


# ------------------------------------------------------------------------------------------
# The BMC estimate and its errors
# ------------------------------------------------------------------------------------------
def test_the_bmc_estimate_is_the_gps_weighted_sum_of_the_red_channel():
    positions = [Vector3D(0.0, 1.0, 0.0), Vector3D(1.0, 0.0, 0.0)]
    values = collect_samples([Constant(1), CosineLobe(1)], positions)  # cos: 1 and 0
    gp = GP(SobolevCov(), Constant(1))
    estimate = compute_estimate_bmc(gp, positions, values)
    assert gp.samples_pos is positions and gp.samples_val is values
    assert estimate == pytest.approx(gp.weights[0], rel=TIGHT)


def test_the_methods_of_each_practice_are_the_courses():
    three = practice3_methods("uniform")
    assert [(m.label, m.marker, m.is_bmc) for m in three] == [("MC", "o", False),
                                                            ("BMC", "x", True)]
    four = practice4_methods()
    assert [(m.label, m.marker, m.pdf_name) for m in four] == [
        ("MC", "o", "uniform"), ("MC IS", "v", "cos"), ("BMC", "x", "uniform"),
        ("BMC IS", "1", "cos")]
    bmc_is = four[3]
    assert isinstance(bmc_is.p_func, CosineLobe) and bmc_is.p_func.exp == 1
    assert [f.exp for f in bmc_is.value_functions] == [3]  # the GP models cos^3 alone
    assert PRACTICE4_INTEGRAND.ground_truth == pytest.approx(2 * math.pi / 5, rel=TIGHT)


def test_bmc_beats_mc_on_the_integral_of_cos():
    random.seed(2026)
    mc, bmc = practice3_methods("uniform")
    assert mean_error(INTEGRANDS["cos"], bmc, 40, 20) < 0.5 * mean_error(
        INTEGRANDS["cos"], mc, 40, 200)


def test_bmc_beats_mc_and_bmc_is_beats_mc_is_on_practice_4s_integral():
    random.seed(2027)
    mc, mc_is, bmc, bmc_is = (mean_error(PRACTICE4_INTEGRAND, method, 40,
                                         20 if method.is_bmc else 200)
                              for method in practice4_methods())
    assert max(bmc, bmc_is) < 0.5 * mc and bmc_is < 0.5 * mc_is and mc_is < mc


def test_each_bmc_estimate_has_its_own_samples_and_the_gps_belief():
    random.seed(7)
    method = practice3_methods("uniform")[1]
    errors = bmc_absolute_errors(INTEGRANDS["cos"], method, 10, 3)
    random.seed(7)
    for error, believed in zip(errors.errors, errors.believed):
        positions, _ = sample_set_hemisphere(10, UniformPDF())
        gp = GP(SobolevCov(), Constant(1))
        estimate = compute_estimate_bmc(gp, positions,
                                        collect_samples(INTEGRANDS["cos"].functions, positions))
        assert error == pytest.approx(abs(estimate - math.pi), rel=TIGHT)
        assert believed == pytest.approx(
            math.sqrt(2 / math.pi) * math.sqrt(gp.compute_variance_BMC()), rel=TIGHT)
    assert len(set(errors.errors)) == 3  # three sample sets, three errors


# ------------------------------------------------------------------------------------------
# The plot and the command line
# ------------------------------------------------------------------------------------------
def test_the_plot_draws_the_bmc_curve_and_its_belief_dashed():
    ns_vector = np.array([20, 40])
    methods = practice3_methods("uniform")
    results = np.array([[0.3, 0.1], [0.2, 0.05]])
    believed = np.array([[0.0, 0.8], [0.0, 0.5]])
    figure = plot_errors(ns_vector, results, methods, [1.8, None], INTEGRANDS["cos"], 1000,
                         believed, 100)
    axes = figure.axes[0]
    by_label = {line.get_label(): line for line in axes.lines}
    assert list(by_label["BMC"].get_ydata()) == [0.1, 0.05]
    assert by_label["BMC"].get_marker() == "x"
    belief = next(line for label, line in by_label.items() if label.startswith("BMC belief"))
    assert belief.get_linestyle() == "--" and list(belief.get_ydata()) == [0.8, 0.5]
    assert "not a bound" in belief.get_label()
    assert "1000 MC and 100 BMC estimates" in axes.get_title()
    plt.close(figure)


@pytest.mark.parametrize("practice, labels", [(3, ["MC", "BMC"]),
                                              (4, ["MC", "MC IS", "BMC", "BMC IS"])])
def test_each_practice_runs_headless_with_its_methods_and_beliefs(practice, labels, tmp_path):
    result = run_python([SCRIPT, "--practice", str(practice), *SMALL, "--weights", "--out",
                         "plots"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    columns = "".join(f"{label:>10}{'belief' if label.startswith('BMC') else 'theory':>10}"
                      for label in labels)
    assert f"{'N':>5}{columns}" in result.stdout.splitlines()
    assert "50 MC and 5 BMC estimates per number of samples in " in result.stdout
    assert "a belief, not a bound" in result.stdout
    for name in (f"workbench_error_practice{practice}.png",
                 f"workbench_weights_practice{practice}.png"):
        assert plt.imread(tmp_path / "plots" / name).ndim == 3


@pytest.mark.parametrize("argv, message", [
    (["--practice", "4", "--integrand", "cos4"], "leave out --integrand and --pdf"),
    (["--weights"], "the weights are a GP's; use --practice 3 or 4"),
    (["--practice", "5"], "invalid choice: 5"),
    (["--bmc-estimates", "0"], "--bmc-estimates: must be a whole number of 1 or more"),
])
def test_bad_practice_options_are_a_one_line_message(argv, message, capsys):
    with pytest.raises(SystemExit) as exited:
        AppWorkbench.main(argv)
    assert exited.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("AppWorkbench.py: error: ") and err.count("\n") == 1
    assert message in err


def test_the_handout_of_the_workbench_has_the_stubs_of_3_2_4_1_and_4_2():
    import course_kit.handout
    source = SCRIPT.read_text(encoding="utf-8")
    handout = course_kit.handout.strip_solution(source, "AppWorkbench.py")
    compile(handout, "AppWorkbench.py", "exec")
    for step, count in (("3.2", 2), ("4.1", 1), ("4.2", 1)):
        assert handout.count(f"# ASSIGNMENT {step}: PUT YOUR CODE HERE") == count
    assert "OPENBLAS_NUM_THREADS" not in handout  # PyRT's own, left out


def test_a_method_without_p_is_classic_monte_carlo():
    assert not Method("MC", "o", UniformPDF(), "uniform").is_bmc
    assert Method("BMC", "x", UniformPDF(), "uniform", p_func=1).is_bmc
