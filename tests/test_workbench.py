"""AppWorkbench.py, the Monte Carlo workbench of Practice 2, Part I: the course's functions
on inputs worked out by hand, the average errors against theory's closed forms, the plot,
and the script run as a student runs it, headless; and a student's workbench in the
course's style, run unchanged.

The theory: for f = cos and uniform sampling, p = 1/(2 pi), each term f/p = 2 pi cos with
cos = u2 uniform on [0, 1), so f/p is uniform on [0, 2 pi): mean pi, standard deviation
sigma = 2 pi / sqrt(12). The mean of N terms is close to normal with standard deviation
sigma / sqrt(N), whose average distance from its mean is sqrt(2/pi) sigma / sqrt(N):
0.32360 for N = 20."""
import math
import random
import shutil

import matplotlib.pyplot as plt
import numpy as np
import pytest

import AppWorkbench
from AppWorkbench import (INTEGRANDS, Method, absolute_errors, average_errors,
                          collect_samples, compute_estimate_cmc, expected_error, plot_errors,
                          standard_deviation)
from helpers import REPO, TIGHT, rgb, run_python
from PyRT_Common import Constant, CosineLobe, CosinePDF, RGBColor, UniformPDF, Vector3D

SCRIPT = REPO / "AppWorkbench.py"
SIGMA_COS_UNIFORM = 2 * math.pi / math.sqrt(12)  # f/p uniform on [0, 2 pi)
UNIFORM = Method("MC", "o", UniformPDF(), "uniform")
COSINE = Method("MC IS", "v", CosinePDF(1), "cos")
# A small run of the script: N = 10, 20, 30, 50 estimates each
SMALL = ["--ns-min", "10", "--ns-max", "31", "--ns-step", "10", "--estimates", "50"]


# ------------------------------------------------------------------------------------------
# The course's functions, on inputs worked out by hand
# ------------------------------------------------------------------------------------------
def test_collect_samples_gives_the_product_of_the_functions_in_the_red_channel():
    functions = [Constant(0.5), Constant(3), CosineLobe(2)]
    directions = [Vector3D(0.0, 1.0, 0.0), Vector3D(0.6, 0.8, 0.0), Vector3D(1.0, 0.0, 0.0)]
    values = collect_samples(functions, directions)
    # 0.5 * 3 * cos^2: cos = 1, 0.8, 0
    assert [rgb(value) for value in values] == [
        pytest.approx((1.5, 0, 0), abs=TIGHT), pytest.approx((0.96, 0, 0), abs=TIGHT),
        pytest.approx((0, 0, 0), abs=TIGHT)]
    assert all(isinstance(value, RGBColor) for value in values)
    assert collect_samples(functions, []) == []


def test_compute_estimate_cmc_is_the_mean_of_f_over_p_in_the_red_channel():
    probs = [0.5, 2.0, 4.0]
    # green and blue are not the integrand's: an estimate that read them would differ
    values = [RGBColor(1.0, 5.0, 5.0), RGBColor(4.0, 9.0, 9.0), RGBColor(2.0, 7.0, 7.0)]
    assert compute_estimate_cmc(probs, values) == pytest.approx((2 + 2 + 0.5) / 3, abs=TIGHT)
    # one sample of f = 1/2 at the uniform density 1/(2 pi): (1/2) 2 pi = pi
    assert compute_estimate_cmc([1 / (2 * math.pi)], [RGBColor(0.5, 0, 0)]) == pytest.approx(
        math.pi, abs=TIGHT)


def test_the_integrands_ground_truths_are_their_integrals():
    assert INTEGRANDS["cos"].ground_truth == pytest.approx(math.pi, abs=TIGHT)
    assert INTEGRANDS["cos4"].ground_truth == pytest.approx(2 * math.pi / 5, abs=TIGHT)
    assert INTEGRANDS["constant"].ground_truth == pytest.approx(2 * math.pi, abs=TIGHT)


# ------------------------------------------------------------------------------------------
# Theory
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("integrand, pdf, sigma", [
    ("cos", UniformPDF(), SIGMA_COS_UNIFORM),
    # f/p = 2 pi u^4 for u uniform: E = 2 pi / 5, E[(f/p)^2] = 4 pi^2 / 9
    ("cos4", UniformPDF(), 2 * math.pi * math.sqrt(1 / 9 - 1 / 25)),
    # f/p = pi cos^3 with cos = sqrt(u): pi u^1.5, E = 2 pi / 5, E[(f/p)^2] = pi^2 / 4
    ("cos4", CosinePDF(1), math.pi * math.sqrt(1 / 4 - 4 / 25)),
])
def test_the_quadrature_sigma_of_f_over_p_is_the_closed_forms(integrand, pdf, sigma):
    # the midpoint rule on 128 x 128 points is within about 1e-4 of it, far within the
    # width of a line of the plot
    assert standard_deviation(INTEGRANDS[integrand].functions, pdf) == pytest.approx(
        sigma, rel=1e-3)


@pytest.mark.parametrize("integrand, pdf", [
    ("cos", CosinePDF(1)),  # f/p = cos / (cos / pi) = pi
    ("cos4", CosinePDF(4)),  # f/p = cos^4 / (5 cos^4 / (2 pi)) = 2 pi / 5
    ("constant", UniformPDF()),  # f/p = 1 / (1 / (2 pi)) = 2 pi
])
def test_an_f_over_p_that_is_constant_has_zero_variance(integrand, pdf):
    assert standard_deviation(INTEGRANDS[integrand].functions, pdf) == 0.0


def test_a_constant_sampled_by_the_cosine_has_infinite_variance():
    # f/p = pi / cos: E[(f/p)^2] = pi^2 integral of 1/u over [0, 1), infinite
    assert standard_deviation(INTEGRANDS["constant"].functions, CosinePDF(1)) == math.inf


def test_the_expected_error_is_sqrt_2_over_pi_sigma_over_sqrt_n():
    assert expected_error(SIGMA_COS_UNIFORM, 20) == pytest.approx(0.32360, abs=1e-5)
    # four times the samples, half the error
    assert expected_error(1.0, 80) == pytest.approx(expected_error(1.0, 20) / 2, abs=TIGHT)


def test_the_average_error_of_uniform_sampling_at_20_samples_matches_theory():
    random.seed(2025)  # the draws, and so the test's outcome, are the same on every run
    errors = absolute_errors(INTEGRANDS["cos"], UniformPDF(), 20, 1000)
    standard_error = np.std(errors, ddof=1) / math.sqrt(len(errors))
    theory = math.sqrt(2 / math.pi) * SIGMA_COS_UNIFORM / math.sqrt(20)
    assert 0.0 < standard_error < 0.02
    assert abs(np.mean(errors) - theory) <= 4 * standard_error


def test_cosine_sampling_of_cos_is_exact_at_every_n():
    random.seed(0)
    results = average_errors(INTEGRANDS["cos"], [UNIFORM, COSINE], [1, 5, 20, 100], 50,
                             progress=False)
    assert results.shape == (4, 2)  # sample counts x methods
    assert np.all(results[:, 1] <= 1e-12)
    assert np.all(results[:, 0] > 0.01)  # uniform sampling has an error


# ------------------------------------------------------------------------------------------
# The plot
# ------------------------------------------------------------------------------------------
def test_the_plot_draws_each_method_with_its_marker_and_theory_dashed_on_log_axes():
    ns_vector = np.array([20, 40, 60])
    results = np.array([[0.3, 1e-16], [0.2, 1e-16], [0.15, 1e-16]])
    figure = plot_errors(ns_vector, results, [UNIFORM, COSINE], [SIGMA_COS_UNIFORM, 0.0],
                         INTEGRANDS["cos"], 1000)
    axes = figure.axes[0]
    measured, theory, exact = axes.lines
    assert (axes.get_xscale(), axes.get_yscale()) == ("log", "log")
    assert measured.get_label() == "MC"
    assert measured.get_marker() == "o" and measured.get_linestyle() == "-"
    assert list(measured.get_ydata()) == [0.3, 0.2, 0.15]
    assert theory.get_label().startswith("MC theory") and theory.get_linestyle() == "--"
    assert list(theory.get_ydata()) == pytest.approx(
        [math.sqrt(2 / math.pi) * SIGMA_COS_UNIFORM / math.sqrt(n) for n in ns_vector])
    # zero variance: named with its marker, nothing drawn on the log scale
    assert exact.get_label().startswith("MC IS: zero variance")
    assert exact.get_marker() == "v" and len(exact.get_xdata()) == 0
    assert [text.get_text() for text in axes.get_legend().get_texts()] == [
        line.get_label() for line in axes.lines]
    plt.close(figure)


@pytest.mark.parametrize("backend, platform, display, screen", [
    ("agg", "linux", ":0", False),  # a backend that draws into files only
    ("TkAgg", "linux", None, False),  # on Linux, no DISPLAY: no screen
    ("TkAgg", "linux", ":0", True),
    ("TkAgg", "win32", None, True),
])
def test_the_plot_is_shown_only_with_an_interactive_backend_and_a_display(
        monkeypatch, backend, platform, display, screen):
    monkeypatch.setattr(AppWorkbench.matplotlib, "get_backend", lambda: backend)
    monkeypatch.setattr(AppWorkbench.sys, "platform", platform)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    if display is None:
        monkeypatch.delenv("DISPLAY", raising=False)
    else:
        monkeypatch.setenv("DISPLAY", display)
    assert AppWorkbench.has_screen() is screen


# ------------------------------------------------------------------------------------------
# The script
# ------------------------------------------------------------------------------------------
def test_importing_the_workbench_runs_and_writes_nothing(tmp_path):
    out = REPO / "out"
    before = {path.name: path.stat().st_mtime_ns for path in out.iterdir()}
    result = run_python(["-c", "import AppWorkbench"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert (result.stdout, result.stderr) == ("", "")
    assert list(tmp_path.iterdir()) == []
    assert {path.name: path.stat().st_mtime_ns for path in out.iterdir()} == before


def test_the_defaults_are_the_courses_set_up():
    args = AppWorkbench.parse_args([])
    assert (args.integrand, args.pdf) == ("cos", "uniform")
    assert (args.ns_min, args.ns_max, args.ns_step, args.estimates) == (20, 101, 20, 1000)
    assert args.out == REPO / "out" and not args.no_window


def test_the_script_runs_headless_from_a_folder_outside_the_repository(tmp_path):
    result = run_python([SCRIPT, *SMALL, "--out", "plots"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "Traceback" not in result.stderr
    assert plt.imread(tmp_path / "plots" / "workbench_error.png").ndim == 3
    lines = result.stdout.splitlines()
    assert lines[0] == "Ground truth: 3.141592653589793"
    assert "MC IS: zero variance, every estimate is exact" in result.stdout
    assert "No screen: the plot is saved, not shown." in lines
    # the table: N, then MC and its theory, MC IS and its theory
    rows = [line.split() for line in lines if line.split()[:1] in (["10"], ["20"], ["30"])]
    assert [row[0] for row in rows] == ["10", "20", "30"]
    assert [float(row[2]) for row in rows] == pytest.approx(
        [math.sqrt(2 / math.pi) * SIGMA_COS_UNIFORM / math.sqrt(n) for n in (10, 20, 30)],
        abs=1e-4)
    assert [float(row[3]) for row in rows] == [0.0, 0.0, 0.0]


def test_the_same_seed_gives_the_same_errors_and_another_seed_others(tmp_path, capsys):
    def table(seed):
        argv = [*SMALL, "--seed", str(seed), "--out", str(tmp_path), "--no-window"]
        assert AppWorkbench.main(argv) == 0
        return [line for line in capsys.readouterr().out.splitlines()
                if line.split()[:1] == ["10"]]

    assert table(7) == table(7) != table(8)


def test_help_lists_the_options(tmp_path):
    result = run_python([SCRIPT, "--help"], cwd=tmp_path)
    assert result.returncode == 0
    for option in ("--practice", "--integrand", "--pdf", "--ns-min", "--ns-max", "--ns-step",
                   "--estimates", "--bmc-estimates", "--weights", "--seed", "--out",
                   "--no-window"):
        assert option in result.stdout
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("argv, named", [
    (["--estimates", "0"], "--estimates"),
    (["--ns-step", "-5"], "--ns-step"),
    (["--integrand", "sin"], "--integrand"),
    (["--pdf", "gauss"], "--pdf"),
    (["--seed", "one"], "--seed"),
    (["--ns-min", "50", "--ns-max", "50"], "--ns-max"),
    (["--samples", "20"], "--samples"),
])
def test_bad_input_is_a_one_line_message(argv, named, capsys):
    with pytest.raises(SystemExit) as exited:
        AppWorkbench.main(argv)
    assert exited.value.code == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.startswith("AppWorkbench.py: error: ") and err.count("\n") == 1
    assert named in err


def test_a_bad_option_stops_the_script_with_one_line_and_no_traceback(tmp_path):
    result = run_python([SCRIPT, "--estimates", "many"], cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.splitlines() == [
        "AppWorkbench.py: error: argument --estimates: must be a whole number of 1 or more, "
        "got 'many' (see --help)"]
    assert list(tmp_path.iterdir()) == []


def test_an_out_folder_that_cannot_be_made_is_one_line_before_any_estimate(tmp_path, capsys):
    (tmp_path / "taken").write_text("a file, not a folder")
    assert AppWorkbench.main(["--out", str(tmp_path / "taken")]) == 1
    out, err = capsys.readouterr()
    assert out == ""
    assert err.startswith("AppWorkbench.py: error: cannot make the folder ")
    assert err.count("\n") == 1


# ------------------------------------------------------------------------------------------
# A student's workbench in the course's style
# ------------------------------------------------------------------------------------------
def test_a_2025_26_student_workbench_runs_unchanged(tmp_path):
    # tests/student/workbench_2025_26.py: the star import, UniformPDF, sample_set_hemisphere,
    # its own loop of estimates seeded with random.seed, results = np.zeros, a plot saved.
    shutil.copy(REPO / "tests" / "student" / "workbench_2025_26.py", tmp_path)
    result = run_python(["workbench_2025_26.py"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "Traceback" not in result.stderr
    assert result.stdout.splitlines()[0] == "Ground truth: 3.141592653589793"
    assert plt.imread(tmp_path / "workbench.png").ndim == 3
    errors = [float(line.rsplit(": ", 1)[1]) for line in result.stdout.splitlines()
              if line.startswith("Average error with ")]
    assert len(errors) == 5
    # Its 200 estimates each: the standard error of an average |error| is
    # sqrt(1 - 2/pi) / sqrt(2/pi) = 0.756 of it over sqrt(200); the seed fixes the draws
    for n, error in zip((20, 40, 60, 80, 100), errors):
        theory = math.sqrt(2 / math.pi) * SIGMA_COS_UNIFORM / math.sqrt(n)
        assert abs(error - theory) <= 4 * 0.756 / math.sqrt(200) * theory
