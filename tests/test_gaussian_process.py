"""GaussianProcess.py, the course's module of Practices 3 and 4: its kernels, z against closed
forms and an independent high-precision quadrature, the weights worked by hand and against
an independent solve, the posterior variance, the course's own z estimate against the
course-style loop, numerics, bad input, pickling, and students' styles."""
import math
import pickle
import random
import shutil

import mpmath
import numpy as np
import pytest

import GaussianProcess
from GaussianProcess import GP, CovarianceFunction, SECov, SobolevCov
from helpers import REPO, TIGHT, global_generator_kept, run_python  # noqa: F401
from PyRT_Common import (BLACK, Constant, CosineLobe, Dot, Function, Length, Normalize,
                         RGBColor, UniformPDF, Vector3D, sample_set_hemisphere)

S = 1.4
C = 2 ** (2 * S - 1) / S  # k(omega, omega) of the Sobolev kernel
NOISE2 = 0.01 ** 2
POLE, HORIZON = Vector3D(0.0, 1.0, 0.0), Vector3D(1.0, 0.0, 0.0)
# Closed forms of z for the Sobolev kernel (s = 1.4), from the integrals over the polar
# angle: the spec's, and at the horizon for p = cos, C pi - 2 * 4^s B(s + 1/2, 3/2)
Z_POLE_1 = (2 * math.pi / S) * (2 ** (2 * S - 1) - 2 ** (S - 1))
Z_HORIZON_1 = math.pi * 2 ** (2 * S - 1) / S
Z_POLE_COS = math.pi * C - 2 * math.pi * 2 ** (S - 1) / (S * (S + 1))
BETA = math.gamma(S + 0.5) * math.gamma(1.5) / math.gamma(S + 2)
Z_HORIZON_COS = math.pi * C - 2 * 4 ** S * BETA
COURSE_DATA = REPO / "tests" / "data"


def gp_of(positions, p_func=Constant(1), **options):
    gp = GP(SobolevCov(), p_func, **options)
    gp.add_sample_pos(positions)
    return gp


def direction(theta, phi=0.3):
    """The unit direction at polar angle theta from +y and azimuth phi."""
    return Vector3D(math.sin(theta) * math.sin(phi), math.cos(theta),
                    math.sin(theta) * math.cos(phi))


class CosineOfMyOwn(Function):
    """cos(theta) as a student writes it: PyRT cannot tell it is symmetric about +y."""

    def __init__(self):
        super().__init__(math.pi)

    def eval(self, omega_i):
        return Dot(Vector3D(0.0, 1.0, 0.0), omega_i)

    def get_integral(self):
        return math.pi


class SobolevOfMyOwn(CovarianceFunction):
    """The Sobolev kernel as a student writes it, with math on floats (it cannot take
    arrays): PyRT evaluates it through its eval, one pair at a time."""

    def eval(self, omega_i, omega_j):
        r = Length(omega_i - omega_j)
        return (2 ** (2 * S - 1)) / S - math.pow(r, 2 * S - 2)


# ------------------------------------------------------------------------------------------
# The kernels
# ------------------------------------------------------------------------------------------
def test_the_sobolev_kernel_is_the_spec_formula():
    a, b = Vector3D(0.0, 1.0, 0.0), Normalize(Vector3D(1.0, 1.0, 0.0))
    r = math.sqrt(2 - math.sqrt(2))  # |a - b| at 45 degrees
    assert SobolevCov().s == 1.4
    assert SobolevCov().eval(a, b) == pytest.approx(C - r ** 0.8, rel=TIGHT)
    assert SobolevCov().eval(a, a) == pytest.approx(2.487287, abs=5e-7)
    assert SobolevCov(s=1.8).eval(a, b) == pytest.approx(2 ** 2.6 / 1.8 - r ** 1.6, rel=TIGHT)


def test_the_squared_exponential_kernel_constructs_and_is_the_spec_formula():
    kernel = SECov(0.5, 0.01)  # the course's raises TypeError here
    a, b = POLE, HORIZON  # r^2 = 2
    assert (kernel.l, kernel.noise) == (0.5, 0.01)
    assert kernel.eval(a, b) == pytest.approx(math.exp(-2 / (2 * 0.25)), rel=TIGHT)
    assert kernel.eval(a, a) == 1.0


def test_the_star_import_gives_the_course_modules_names_and_exp():
    names = {}
    exec("from GaussianProcess import *", names)
    for name in ("GP", "SobolevCov", "SECov", "CovarianceFunction", "exp", "np", "Vector3D",
                 "sample_set_hemisphere", "UniformPDF", "CosineLobe", "random", "BLACK"):
        assert name in names, name
    assert names["exp"] is math.exp


# ------------------------------------------------------------------------------------------
# z, exact: closed forms, an independent quadrature, 2-D quadrature for any p
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("p_func, pole, horizon", [
    (Constant(1), Z_POLE_1, Z_HORIZON_1), (1, Z_POLE_1, Z_HORIZON_1),
    (Constant(2.5), 2.5 * Z_POLE_1, 2.5 * Z_HORIZON_1),
    (CosineLobe(1), Z_POLE_COS, Z_HORIZON_COS)])
def test_z_at_the_pole_and_the_horizon_is_the_closed_form(p_func, pole, horizon):
    z = gp_of([POLE, HORIZON], p_func).z
    assert z[0] == pytest.approx(pole, rel=TIGHT)
    assert z[1] == pytest.approx(horizon, rel=TIGHT)
    # the spec's rounded decimals
    assert gp_of([POLE]).z[0] == pytest.approx(9.70615, abs=5e-6)


def test_z_of_the_squared_exponential_kernel_is_its_closed_form():
    l = 0.5
    a = 1 / l ** 2  # k = exp(-(1 - cos(gamma)) / l^2)
    z1 = GP(SECov(l, 0.0), 1)
    z1.add_sample_pos([POLE, HORIZON])
    assert z1.z[0] == pytest.approx(2 * math.pi * l ** 2 * (1 - math.exp(-a)), rel=TIGHT)
    assert z1.z[1] == pytest.approx(math.pi * l ** 2 * (1 - math.exp(-2 * a)), rel=TIGHT)
    cos = GP(SECov(l, 0.0), CosineLobe(1))
    cos.add_sample_pos([POLE])
    assert cos.z[0] == pytest.approx(2 * math.pi * (1 / a - (1 - math.exp(-a)) / a ** 2),
                                     rel=TIGHT)


def reference_z(theta, exponent, kernel=lambda r: C - r ** (2 * S - 2)):
    """z at polar angle theta for p = cos^exponent (0 or 1), by mpmath at 30 digits over
    the angle gamma from the sample (the ring wholly in the hemisphere up to pi/2 - theta,
    an arc of half-angle acos(-cot(theta) cot(gamma)) up to pi/2 + theta)."""
    mpmath.mp.dps = 30
    theta = mpmath.mpf(theta)

    def ring(gamma):
        a, b = mpmath.cos(theta) * mpmath.cos(gamma), mpmath.sin(theta) * mpmath.sin(gamma)
        if gamma <= mpmath.pi / 2 - theta:
            psi0, whole = mpmath.pi, True
        else:
            psi0, whole = mpmath.acos(max(-1, min(1, -a / b))), False
        if exponent == 0:
            return 2 * psi0
        return 2 * mpmath.pi * a if whole else 2 * (a * psi0 + b * mpmath.sin(psi0))

    def integrand(gamma):
        return kernel(2 * mpmath.sin(gamma / 2)) * mpmath.sin(gamma) * ring(gamma)
    ends = [0, mpmath.pi / 2 - theta, mpmath.pi / 2 + theta]
    return float(mpmath.quad(integrand, [e for e in ends if e >= 0 and e <= mpmath.pi]))


@pytest.mark.parametrize("theta", [0.05, 0.4, 1.0, 1.45, math.pi / 2 - 1e-6])
@pytest.mark.parametrize("exponent", [0, 1])
def test_z_between_pole_and_horizon_is_the_high_precision_quadratures(theta, exponent):
    p_func = Constant(1) if exponent == 0 else CosineLobe(1)
    assert gp_of([direction(theta)], p_func).z[0] == pytest.approx(
        reference_z(theta, exponent), rel=TIGHT)


def test_z_of_a_cosine_lobe_of_another_exponent_is_the_integral_of_cos_to_that_power():
    # p = cos^3 at the pole: C * 2 pi / 4 - 2 pi * integral of u^3 (2 - 2u)^(s-1), the
    # latter 2^(s-1) B(4, s) = 2^(s-1) * 6 / (s (s+1) (s+2) (s+3))
    expected = C * math.pi / 2 - 2 * math.pi * 2 ** (S - 1) * 6 / (
        S * (S + 1) * (S + 2) * (S + 3))
    assert gp_of([POLE], CosineLobe(3)).z[0] == pytest.approx(expected, rel=TIGHT)


def test_a_p_of_ones_own_takes_a_two_dimensional_quadrature_with_the_same_z():
    positions = [POLE, HORIZON, direction(0.7, 1.1)]
    own = gp_of(positions, CosineOfMyOwn()).z
    assert own[0] == pytest.approx(Z_POLE_COS, rel=TIGHT)
    assert own[1] == pytest.approx(Z_HORIZON_COS, rel=TIGHT)
    assert own[2] == pytest.approx(reference_z(0.7, 1), rel=TIGHT)


def test_a_p_that_is_not_symmetric_about_y_gets_its_own_z():
    class Tilted(Function):  # p = 1 + x: z gains the integral of k x
        def __init__(self):
            super().__init__(2 * math.pi)

        def eval(self, omega_i):
            return 1 + omega_i.x

        def get_integral(self):
            return 2 * math.pi
    z = gp_of([POLE, HORIZON], Tilted()).z
    # at the pole the x of the hemisphere cancels; at the horizon (1, 0, 0) x = cos(gamma)
    # on each ring, half of which lies in the hemisphere
    mpmath.mp.dps = 30
    half_rings = mpmath.pi * mpmath.quad(
        lambda g: (C - (2 * mpmath.sin(g / 2)) ** 0.8) * mpmath.cos(g) * mpmath.sin(g),
        [0, mpmath.pi])
    assert z[0] == pytest.approx(Z_POLE_1, rel=TIGHT)
    assert z[1] == pytest.approx(Z_HORIZON_1 + float(half_rings), rel=TIGHT)


def test_a_kernel_of_ones_own_runs_as_written_and_gives_the_same_z():
    gp = GP(SobolevOfMyOwn(), Constant(1))
    gp.add_sample_pos([POLE, HORIZON])
    assert gp.z[0] == pytest.approx(Z_POLE_1, rel=TIGHT)
    assert gp.z[1] == pytest.approx(Z_HORIZON_1, rel=TIGHT)
    assert gp.invQ[0, 0] == pytest.approx(gp_of([POLE, HORIZON]).invQ[0, 0], rel=TIGHT)


def test_the_exact_z_draws_nothing_from_random():
    random.seed(5)
    state = random.getstate()
    gp_of([POLE, direction(0.5)])
    assert random.getstate() == state


# ------------------------------------------------------------------------------------------
# The weights, the integral, the variance
# ------------------------------------------------------------------------------------------
def test_one_sample_at_the_pole_has_the_spec_weight():
    gp = gp_of([POLE])
    assert gp.weights[0] == pytest.approx(Z_POLE_1 / (C + NOISE2), rel=TIGHT)
    assert gp.weights[0] == pytest.approx(3.90214, abs=1e-5)  # the spec's, cut at 5 places
    assert gp.invQ[0, 0] == pytest.approx(1 / (C + NOISE2), rel=TIGHT)


def test_two_samples_have_the_weights_of_the_two_by_two_solve():
    gp = gp_of([POLE, HORIZON])
    diagonal, k12 = C + NOISE2, C - math.sqrt(2) ** 0.8  # |pole - horizon| = sqrt 2
    det = diagonal ** 2 - k12 ** 2
    assert gp.weights[0] == pytest.approx((Z_POLE_1 * diagonal - Z_HORIZON_1 * k12) / det,
                                          rel=TIGHT)
    assert gp.weights[1] == pytest.approx((Z_HORIZON_1 * diagonal - Z_POLE_1 * k12) / det,
                                          rel=TIGHT)


def test_the_integral_is_the_weighted_sum_of_colours_or_of_numbers():
    gp = gp_of([POLE, HORIZON])
    w = gp.weights
    gp.add_sample_val([RGBColor(1.0, 2.0, 0.0), RGBColor(3.0, 0.0, 1.0)])
    colour = gp.compute_integral_BMC()
    assert type(colour) is RGBColor
    assert (colour.r, colour.g, colour.b) == pytest.approx(
        (w[0] + 3 * w[1], 2 * w[0], w[1]), rel=TIGHT)
    gp.add_sample_val([1.0, 3.0])
    assert gp.compute_integral_BMC() == pytest.approx(w[0] + 3 * w[1], rel=TIGHT)


def test_k_bar_is_the_double_integral_of_the_kernel_over_the_hemisphere():
    # For p = 1, two directions gamma apart lie in one hemisphere of a random orientation
    # with probability (pi - gamma) / (2 pi): k-bar = 4 pi * integral over gamma in [0, pi]
    # of k(gamma) sin(gamma) (pi - gamma)
    mpmath.mp.dps = 30
    expected = 4 * mpmath.pi * mpmath.quad(
        lambda g: (C - (2 * mpmath.sin(g / 2)) ** 0.8) * mpmath.sin(g) * (mpmath.pi - g),
        [0, mpmath.pi])
    gp = gp_of([POLE])
    k_bar = gp.compute_variance_BMC() + gp.weights @ gp.z
    assert k_bar == pytest.approx(float(expected), rel=1e-11)


def test_k_bar_with_the_cosine_matches_a_seeded_monte_carlo_of_a_million_pairs():
    rng = np.random.default_rng(2026)
    u = rng.random((4, 1_000_000))
    def directions(u1, u2):
        s = np.sqrt(1 - u2 ** 2)
        return np.stack([np.sin(2 * np.pi * u1) * s, u2, np.cos(2 * np.pi * u1) * s])
    a, b = directions(u[0], u[1]), directions(u[2], u[3])
    values = (C - np.sum((a - b) ** 2, axis=0) ** 0.4) * a[1] * b[1] * (2 * np.pi) ** 2
    gp = gp_of([POLE], CosineLobe(1))
    k_bar = gp.compute_variance_BMC() + gp.weights @ gp.z
    assert abs(k_bar - values.mean()) < 6 * values.std() / 1000  # six standard errors


def test_the_variance_falls_as_samples_are_added_and_never_goes_negative():
    random.seed(3)
    positions, _ = sample_set_hemisphere(200, UniformPDF())
    variances = [gp_of(positions[:n]).compute_variance_BMC() for n in (1, 10, 50, 200)]
    assert all(a > b for a, b in zip(variances, variances[1:]))
    assert variances[-1] >= 0.0


def test_the_variance_with_a_p_of_ones_own_is_that_of_the_same_p_known_to_pyrt():
    positions = [POLE, direction(0.8, 0.4)]
    own = gp_of(positions, CosineOfMyOwn()).compute_variance_BMC()
    assert own == pytest.approx(gp_of(positions, CosineLobe(1)).compute_variance_BMC(),
                                rel=1e-7)


def test_the_variance_with_the_course_z_comes_from_the_exact_z():
    random.seed(4)
    positions, _ = sample_set_hemisphere(5, UniformPDF())
    exact = gp_of(positions).compute_variance_BMC()
    assert gp_of(positions, z_estimate="course").compute_variance_BMC() == pytest.approx(
        exact, rel=1e-9)


# ------------------------------------------------------------------------------------------
# The course's own z estimate
# ------------------------------------------------------------------------------------------
def test_the_course_estimate_draws_exactly_100000_numbers_and_is_near_the_exact_z():
    random.seed(11)
    gp = gp_of([POLE, HORIZON], z_estimate="course")
    after = random.random()
    random.seed(11)
    for _ in range(100_000):
        random.random()
    assert after == random.random()
    # within five standard errors of the closed forms: k spreads its values over about
    # 0.4, so the estimate's standard error is near 2 pi 0.4 / sqrt(50000) = 0.011
    assert gp.z == pytest.approx([Z_POLE_1, Z_HORIZON_1], abs=5 * 0.011)


def test_the_course_estimate_of_a_kernel_of_ones_own_is_the_modules_loop_with_its_draws():
    positions = [POLE, direction(0.9, 2.0)]
    random.seed(12)
    vectorised = gp_of(positions, z_estimate="course").z
    random.seed(12)
    loop = GP(SobolevOfMyOwn(), Constant(1), z_estimate="course")  # the loop as written
    loop.add_sample_pos(positions)
    assert loop.z == pytest.approx(vectorised, rel=TIGHT)


def test_the_course_estimate_is_the_course_style_loop_on_the_courses_base_code(tmp_path):
    # tests/data/course_practice3/GaussianProcess.py on the course's base code, in a
    # process of its own (its modules have PyRT's names), from the same seed
    for module in (COURSE_DATA / "course_base" / "2023-24").glob("*.py"):
        shutil.copy(module, tmp_path)
    shutil.copy(COURSE_DATA / "course_practice3" / "GaussianProcess.py", tmp_path)
    script = ("from GaussianProcess import *\nimport random\nrandom.seed(13)\n"
              "positions, _ = sample_set_hemisphere(2, UniformPDF())\n"
              "gp = GP(SobolevCov(), CosineLobe(1))\ngp.add_sample_pos(positions)\n"
              "print(repr(list(gp.z)), repr(list(gp.weights)))\n"
              "try:\n    SECov(0.5, 0.01)\nexcept TypeError:\n    print('TypeError')\n")
    result = run_python(["-c", script], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    z_line, error_line = result.stdout.splitlines()
    course_z, course_weights = (eval(part + "]") for part in z_line[:-1].split("] "))
    assert error_line == "TypeError"  # the course's SECov, as the spec says
    random.seed(13)
    positions, _ = sample_set_hemisphere(2, UniformPDF())
    gp = gp_of(positions, CosineLobe(1), z_estimate="course")
    assert list(gp.z) == pytest.approx(course_z, rel=TIGHT)
    assert list(gp.weights) == pytest.approx(course_weights, rel=TIGHT)


# ------------------------------------------------------------------------------------------
# Numerics
# ------------------------------------------------------------------------------------------
def independent_weights(gp):
    """w solving Q w = z by mpmath at 40 digits, from the GP's own Q and z."""
    mpmath.mp.dps = 40
    Q = mpmath.matrix(gp.Q.tolist())
    return [float(w) for w in mpmath.lu_solve(Q, mpmath.matrix(list(gp.z)))]


def test_the_weights_of_two_almost_equal_samples_are_those_of_an_independent_solve():
    random.seed(21)
    positions, _ = sample_set_hemisphere(30, UniformPDF())
    near = positions[0] + Vector3D(1e-9, 0.0, 0.0)
    positions.append(Normalize(near))
    gp = gp_of(positions)
    assert np.allclose(gp.weights, independent_weights(gp), rtol=1e-12, atol=1e-13)


def test_hundreds_of_samples_solve_to_rounding():
    random.seed(22)
    positions, _ = sample_set_hemisphere(400, UniformPDF())
    gp = gp_of(positions)
    residual = gp.Q.astype(np.longdouble) @ gp.weights - gp.z
    assert np.max(np.abs(residual.astype(float))) < 1e-12 * np.max(np.abs(gp.z))
    assert sum(gp.weights) == pytest.approx(2 * math.pi, rel=1e-3)  # the integral of 1


@pytest.mark.parametrize("kernel, offset, said", [
    (SobolevCov(), 0.0, "the same direction"),
    # the squared exponential's 1 - k grows as r^2: 1e-8 apart, Q's condition is 1e16
    (SECov(0.5, 0.0), 1e-8, "1e-08 apart")])
def test_noise_0_with_a_repeated_sample_says_to_add_noise_or_remove_it(kernel, offset, said):
    again = Normalize(Vector3D(offset, 1.0, 0.0))
    with pytest.raises(ValueError, match=rf"sample positions 0 and 2 are {said} and noise_ "
                                         r"is 0; pass a noise_ above 0 .* or remove the "
                                         r"duplicate sample"):
        GP(kernel, 1, noise_=0.0).add_sample_pos([POLE, HORIZON, again])


def test_a_kernel_that_is_not_a_covariance_is_named_as_the_reason():
    class Negative(CovarianceFunction):
        def eval(self, omega_i, omega_j):
            return -1.0
    with pytest.raises(ValueError, match=r"^GP: Q = K \+ noise\^2 I is not positive "
                                         r"definite .* not a covariance function"):
        GP(Negative(), 1).add_sample_pos([POLE, HORIZON])


# ------------------------------------------------------------------------------------------
# Bad input: a message that says what to fix
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("positions, exception, message", [
    ([], ValueError, r"^GP\.add_sample_pos: the sample set is empty"),
    ([Vector3D(0.0, 2.0, 0.0)], ValueError, r"position 0 is not a unit direction .*Normalize"),
    ([POLE, Vector3D(0.0, -1.0, 0.0)], ValueError, r"position 1 lies below the hemisphere"),
    ([Vector3D(math.nan, 1.0, 0.0)], ValueError, r"position 0 is not finite"),
    (([POLE], [0.15]), TypeError, r"not the pair"),
    (42, TypeError, r"must be a list of Vector3D directions"),
])
def test_bad_positions_are_refused_with_what_to_fix(positions, exception, message):
    with pytest.raises(exception, match=message):
        GP(SobolevCov(), 1).add_sample_pos(positions)


@pytest.mark.parametrize("values, exception, message", [
    ([1.0], ValueError, r"^GP\.add_sample_val: 1 values for 2 sample positions"),
    ([1.0, math.nan], ValueError, r"value 1 is not finite"),
    ([RGBColor(1, 1, 1), RGBColor(1, math.inf, 1)], ValueError, r"value 1 is not finite"),
    ([1.0, "two"], TypeError, r"value 1 must be an RGBColor of numbers or a number"),
    ([RGBColor(1, 1, 1), 2.0], TypeError, r"value 1 is a number where value 0 is an "
                                          r"RGBColor"),
])
def test_bad_values_are_refused_with_what_to_fix(values, exception, message):
    gp = gp_of([POLE, HORIZON])
    with pytest.raises(exception, match=message):
        gp.add_sample_val(values)


def test_values_before_positions_and_an_integral_before_both_say_the_order():
    gp = GP(SobolevCov(), 1)
    with pytest.raises(ValueError, match=r"call add_sample_pos\(positions\) first"):
        gp.add_sample_val([1.0])
    with pytest.raises(ValueError, match=r"call add_sample_pos\(positions\), then "
                                         r"add_sample_val\(values\)"):
        gp.compute_integral_BMC()


@pytest.mark.parametrize("arguments, exception, message", [
    ((SobolevCov(), UniformPDF()), TypeError, r"not the pdf UniformPDF; .*CosineLobe\(1\)"),
    ((SobolevCov(), "one"), TypeError, r"p_func must be a Function .* or a number"),
    ((SobolevCov(), math.inf), ValueError, r"p_func must be a finite number"),
    (("sobolev", 1), TypeError, r"cov_func must be a CovarianceFunction"),
    ((SobolevCov(), 1, -0.1), ValueError, r"noise_ must be a finite number of 0 or more"),
])
def test_bad_gp_arguments_are_refused_with_what_to_pass(arguments, exception, message):
    with pytest.raises(exception, match=message):
        GP(*arguments)


def test_bad_kernel_parameters_and_z_estimates_are_refused():
    with pytest.raises(ValueError, match=r"^SobolevCov: s must be a finite number larger "
                                         r"than 1"):
        SobolevCov(s=0.5)
    with pytest.raises(ValueError, match=r"^SECov: l must be a finite number larger"):
        SECov(0.0, 0.01)
    with pytest.raises(ValueError, match=r"z_estimate must be 'exact' .* or 'course'"):
        GP(SobolevCov(), 1, z_estimate="mc")


def test_a_z_estimate_set_as_an_attribute_is_checked_when_z_is_computed():
    gp = GP(SobolevCov(), 1)
    gp.z_estimate = "Course"
    with pytest.raises(ValueError, match=r"z_estimate must be 'exact' .* got 'Course'"):
        gp.add_sample_pos([POLE])


# ------------------------------------------------------------------------------------------
# Pickling, and what students write
# ------------------------------------------------------------------------------------------
def test_a_gp_pickles_with_its_weights_and_values():
    gp = gp_of([POLE, direction(1.0)], CosineLobe(1))
    gp.add_sample_val([RGBColor(1.0, 0.5, 0.0), RGBColor(0.2, 0.1, 0.0)])
    again = pickle.loads(pickle.dumps(gp))
    assert np.array_equal(again.weights, gp.weights)
    assert again.compute_integral_BMC() == gp.compute_integral_BMC()
    assert again.compute_variance_BMC() == gp.compute_variance_BMC()


def test_students_styles_of_p_give_the_integral_of_cos():
    # GP(SobolevCov(), Constant(1)) and GP(SobolevCov(), 1) model the whole integrand cos;
    # GP(SobolevCov(), CosineLobe(1)) takes the cosine into z and models f = 1
    random.seed(31)
    positions, _ = sample_set_hemisphere(40, UniformPDF())
    cosines = [RGBColor(Dot(POLE, omega), 0.0, 0.0) for omega in positions]
    for p_func, values in ((Constant(1), cosines), (1, cosines),
                           (CosineLobe(1), [RGBColor(1.0, 0.0, 0.0)] * 40)):
        gp = GP(SobolevCov(), p_func)
        gp.add_sample_pos(positions)
        gp.add_sample_val(values)
        assert gp.compute_integral_BMC().r == pytest.approx(math.pi, abs=0.05)
    assert gp.compute_integral_BMC().r == pytest.approx(sum(gp.weights), rel=TIGHT)


def test_a_compute_inv_q_of_ones_own_gives_the_weights_z_times_its_inverse():
    class MyGP(GP):  # the course's loop and np.linalg.inv, keeping no Q
        def compute_inv_Q(self):
            n = len(self.samples_pos)
            Q = np.zeros((n, n))
            for i in range(n):
                for j in range(n):
                    Q[i, j] = self.cov_func.eval(self.samples_pos[i], self.samples_pos[j])
            return np.linalg.inv(Q + np.identity(n) * self.noise ** 2)
    gp = MyGP(SobolevCov(), 1)
    gp.add_sample_pos([POLE, HORIZON])
    assert list(gp.weights) == pytest.approx(list(gp_of([POLE, HORIZON]).weights), rel=1e-12)
    assert gp.compute_variance_BMC() == pytest.approx(
        gp_of([POLE, HORIZON]).compute_variance_BMC(), rel=1e-9)


def test_the_course_style_bmc_integrator_lights_a_white_floor_under_a_white_sky():
    # tests/data/course_practice3/bmc_integrator.py on PyRT, with one GP and with a list
    # of GPs: a floor of albedo 0.8 inside an emissive sphere reflects 0.8 (the integral
    # of L_i kd cos with L_i = 1, kd = 0.8 / pi)
    namespace = {}
    exec((COURSE_DATA / "course_practice3" / "bmc_integrator.py").read_text(), namespace)
    from PyRT_Common import Ray, WHITE
    from PyRT_Core import Lambertian, Parallelogram, Scene, Sphere
    scene = Scene()
    floor = Parallelogram(Vector3D(-1.0, -1.0, 1.0), Vector3D(2.0, 0.0, 0.0),
                          Vector3D(0.0, 0.0, -2.0))
    floor.set_BRDF(Lambertian(RGBColor(0.8, 0.8, 0.8)))
    sky = Sphere(Vector3D(0.0, 0.0, 0.0), 100.0, emission=WHITE)
    sky.set_BRDF(Lambertian(BLACK))
    scene.add_object(floor)
    scene.add_object(sky)
    random.seed(41)
    pool = [gp_of(sample_set_hemisphere(40, UniformPDF())[0]) for _ in range(3)]
    for my_gp in (pool[0], pool):
        integrator = namespace["BayesianMonteCarloIntegrator"](40, my_gp, "unused")
        integrator.add_scene(scene)
        colour = integrator.compute_color(Ray(Vector3D(0.0, 0.5, 0.0),
                                              Vector3D(0.0, -1.0, 0.0)))
        assert colour.r == pytest.approx(0.8, abs=0.03)


def test_the_handout_of_the_module_is_the_courses_with_its_three_stubs():
    import course_kit.handout
    source = (REPO / "GaussianProcess.py").read_text(encoding="utf-8")
    handout = course_kit.handout.strip_solution(source, "GaussianProcess.py")
    compile(handout, "GaussianProcess.py", "exec")
    assert handout.count("# ASSIGNMENT 3.1: PUT YOUR CODE HERE") == 3
    assert "pyrt" not in handout and "FRAMEWORK" not in handout
    assert "sample_set_hemisphere(ns_z, UniformPDF())" in handout  # compute_z's set-up
    assert GaussianProcess.__all__[-5:] == ["exp", "CovarianceFunction", "SobolevCov",
                                            "SECov", "GP"]
