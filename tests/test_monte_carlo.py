"""The Monte Carlo half of the course's base code (PYRT_SPEC.md): PyRT_Common's pdfs,
integrands, hemisphere sampling and environment map, Lambertian.get_kd, and the
integrators of the later practices, each against the spec's formulas worked out here."""
import math
import random

import cv2
import matplotlib.pyplot as plt
import numpy as np
import pytest

from helpers import TIGHT, as_tuple, global_generator_kept  # noqa: F401
from PyRT_Common import (Constant, CosineLobe, CosinePDF, EnvironmentMap, Function, PDF,
                         RGBColor, UniformPDF, Vector3D, center_around_normal,
                         euclidean_to_disk, oriented_hemi_dir, rotate_around_y,
                         sample_set_hemisphere, visualize_sample_set)
from PyRT_Core import Lambertian
from PyRT_Integrators import BayesianMonteCarloIntegrator, CMCIntegrator, Integrator

PI = math.pi
S3 = 1 / math.sqrt(3)
# u1, u2 in [0, 1), as random() draws them: the ends, quarters, and values in between
UNIT_SQUARE = [(u1, u2) for u1 in (0.0, 0.1, 0.25, 0.5, 0.6, 0.75, 0.99, 1 - 2 ** -53)
               for u2 in (0.0, 0.2, 0.5, 0.64, 0.9, 1 - 2 ** -53)]
COSINE_EXPONENTS = [0, 1, 2, 3, 10, 2.5]


# ------------------------------------------------------------------------------------------
# The spec's formulas, written out on tuples
# ------------------------------------------------------------------------------------------
def uniform_direction(u1, u2):
    """UniformPDF.generate_dir: y = u2, phi = 2 pi u1, x and z on the circle of sqrt(1 - y^2)."""
    phi = 2 * PI * u1
    return (math.sin(phi) * math.sqrt(1 - u2 ** 2), u2, math.cos(phi) * math.sqrt(1 - u2 ** 2))


def cosine_direction(exp, u1, u2):
    """CosinePDF(exp).generate_dir: y = u2^(1/(exp+1)), s = sqrt(1 - u2^(2/(exp+1)))."""
    phi = 2 * PI * u1
    s = math.sqrt(1 - u2 ** (2 / (exp + 1)))
    return (math.sin(phi) * s, u2 ** (1 / (exp + 1)), math.cos(phi) * s)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalized(a):
    length = math.sqrt(a[0] ** 2 + a[1] ** 2 + a[2] ** 2)
    return tuple(c / length for c in a)


def centred(direction, normal):
    """center_around_normal: Normalize(v*x + w*y + u*z) in the jittered-up frame."""
    w = normal
    v = normalized(cross((0.00319, 1.0, 0.0078), w))
    u = cross(v, w)
    x, y, z = direction
    return normalized(tuple(v[i] * x + w[i] * y + u[i] * z for i in range(3)))


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def hemisphere_integral(f, n_theta=32, n_phi=16):
    """The integral of f(direction) over the hemisphere around +y, by quadrature."""
    # The direction at polar angle theta and azimuth phi is (sin theta sin phi, cos theta,
    # sin theta cos phi), and d omega = sin theta d theta d phi. Gauss-Legendre in theta on
    # [0, pi/2]; the midpoint rule in phi, exact for integrands that do not depend on phi.
    # Worked out on cos^exp, the error is below 1e-13 for whole exponents and 1e-10 for 2.5.
    nodes, weights = np.polynomial.legendre.leggauss(n_theta)
    total = 0.0
    for node, weight in zip(nodes, weights):
        theta = (node + 1) * PI / 4
        for k in range(n_phi):
            phi = (k + 0.5) * 2 * PI / n_phi
            direction = Vector3D(math.sin(theta) * math.sin(phi), math.cos(theta),
                                 math.sin(theta) * math.cos(phi))
            total += weight * PI / 4 * 2 * PI / n_phi * f(direction) * math.sin(theta)
    return total


# ------------------------------------------------------------------------------------------
# UniformPDF
# ------------------------------------------------------------------------------------------
def test_uniform_pdf_is_one_over_two_pi_for_every_direction():
    """get_val is 1/(2 pi) exactly, whatever omega is."""
    pdf = UniformPDF()
    assert isinstance(pdf, PDF)
    for omega in [(0.0, 1.0, 0.0), (1.0, 0.0, 0.0), (S3, S3, -S3), (0.0, -1.0, 0.0)]:
        assert pdf.get_val(Vector3D(*omega)) == 1 / (2 * PI)


@pytest.mark.parametrize("u1, u2, expected", [
    ((0.0), 0.0, (0.0, 0.0, 1.0)),            # phi = 0, on the horizon
    (0.25, 0.0, (1.0, 0.0, 0.0)),             # phi = pi/2
    (0.5, 0.6, (0.0, 0.6, -0.8)),             # phi = pi, sqrt(1 - 0.36) = 0.8
    (0.75, 0.8, (-0.6, 0.8, 0.0)),            # phi = 3 pi/2, sqrt(1 - 0.64) = 0.6
    (0.125, 0.28, (0.96 / math.sqrt(2), 0.28, 0.96 / math.sqrt(2))),  # phi = pi/4
    (0.3, 0.0, (math.sin(0.6 * PI), 0.0, math.cos(0.6 * PI))),
])
def test_uniform_pdf_generates_the_direction_worked_out_by_hand(u1, u2, expected):
    """generate_dir(u1, u2) for hand-picked u1, u2."""
    direction = UniformPDF().generate_dir(u1, u2)
    assert type(direction) == Vector3D
    assert as_tuple(direction) == pytest.approx(expected, abs=TIGHT)


def test_uniform_pdf_at_zero_zero_is_exactly_straight_ahead_on_the_horizon():
    """generate_dir(0, 0): sin 0 = 0, cos 0 = 1, sqrt(1) = 1, all exact."""
    assert as_tuple(UniformPDF().generate_dir(0.0, 0.0)) == (0.0, 0.0, 1.0)


@pytest.mark.parametrize("u1, u2", UNIT_SQUARE)
def test_uniform_pdf_generates_the_formulas_direction(u1, u2):
    """generate_dir follows y = u2, phi = 2 pi u1 over the unit square."""
    direction = UniformPDF().generate_dir(u1, u2)
    assert as_tuple(direction) == pytest.approx(uniform_direction(u1, u2), abs=TIGHT)


# ------------------------------------------------------------------------------------------
# CosinePDF
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("exp, omega, expected", [
    (1, (0.0, 1.0, 0.0), 1 / PI),               # (1 + 1)/(2 pi) * 1
    (1, (0.6, 0.8, 0.0), 0.8 / PI),             # (2/(2 pi)) * 0.8
    (3, (math.sqrt(0.75), 0.5, 0.0), 0.25 / PI),  # (4/(2 pi)) * 0.125
    (0, (S3, S3, -S3), 1 / (2 * PI)),           # cos^0 = 1: the uniform pdf
    (2, (0.0, 0.0, 1.0), 0.0),                  # on the horizon
    (2.5, (0.0, 0.6, 0.8), 3.5 / (2 * PI) * 0.6 ** 2.5),
])
def test_cosine_pdf_is_exp_plus_one_over_two_pi_times_the_cosine_to_the_exp(exp, omega,
                                                                           expected):
    """get_val(omega) = (exp + 1)/(2 pi) * Dot((0, 1, 0), omega)^exp."""
    pdf = CosinePDF(exp)
    assert isinstance(pdf, PDF)
    assert pdf.exp == exp
    assert pdf.get_val(Vector3D(*omega)) == pytest.approx(expected, rel=TIGHT, abs=TIGHT)


@pytest.mark.parametrize("exp, u1, u2, expected", [
    (1, 0.5, 0.25, (0.0, 0.5, -math.sqrt(0.75))),    # y = sqrt(0.25), s = sqrt(1 - 0.25)
    (3, 0.25, 0.0625, (math.sqrt(0.75), 0.5, 0.0)),  # y = 0.0625^(1/4), s = sqrt(1 - 0.25)
    (1, 0.0, 0.0, (0.0, 0.0, 1.0)),                  # y = 0: on the horizon
    (2, 0.75, 0.512, (-0.6, 0.8, 0.0)),              # y = 0.512^(1/3), s = sqrt(1 - 0.64)
])
def test_cosine_pdf_generates_the_direction_worked_out_by_hand(exp, u1, u2, expected):
    """generate_dir(u1, u2) for hand-picked exponents and u1, u2."""
    direction = CosinePDF(exp).generate_dir(u1, u2)
    assert type(direction) == Vector3D
    assert as_tuple(direction) == pytest.approx(expected, abs=TIGHT)


@pytest.mark.parametrize("exp", COSINE_EXPONENTS)
def test_cosine_pdf_generates_the_formulas_direction(exp):
    """generate_dir follows y = u2^(1/(exp+1)), s = sqrt(1 - u2^(2/(exp+1))) everywhere."""
    pdf = CosinePDF(exp)
    for u1, u2 in UNIT_SQUARE:
        assert as_tuple(pdf.generate_dir(u1, u2)) == pytest.approx(
            cosine_direction(exp, u1, u2), abs=TIGHT), (u1, u2)


def test_cosine_pdf_of_exponent_zero_is_the_uniform_pdf():
    """With exp = 0 both formulas agree: y = u2 and density 1/(2 pi)."""
    for u1, u2 in UNIT_SQUARE:
        assert as_tuple(CosinePDF(0).generate_dir(u1, u2)) == pytest.approx(
            as_tuple(UniformPDF().generate_dir(u1, u2)), abs=TIGHT)
    assert CosinePDF(0).get_val(Vector3D(S3, S3, S3)) == pytest.approx(1 / (2 * PI), rel=TIGHT)


# ------------------------------------------------------------------------------------------
# Both pdfs: densities over the hemisphere, and the directions they make
# ------------------------------------------------------------------------------------------
PDFS = [("uniform", UniformPDF)] + [(f"cosine^{exp}", lambda exp=exp: CosinePDF(exp))
                                     for exp in COSINE_EXPONENTS]


@pytest.mark.parametrize("name, make", PDFS, ids=[name for name, _ in PDFS])
def test_each_pdf_integrates_to_one_over_the_hemisphere(name, make):
    """A density: its integral over the hemisphere around +y is 1 (by quadrature)."""
    pdf = make()
    assert hemisphere_integral(pdf.get_val) == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("name, make", PDFS, ids=[name for name, _ in PDFS])
def test_each_pdf_generates_unit_directions_above_the_horizon(name, make):
    """Every generated direction is of unit length and has y >= 0."""
    pdf = make()
    for u1, u2 in UNIT_SQUARE:
        x, y, z = as_tuple(pdf.generate_dir(u1, u2))
        assert math.sqrt(x * x + y * y + z * z) == pytest.approx(1.0, abs=TIGHT), (u1, u2)
        assert y >= 0.0, (u1, u2)


# ------------------------------------------------------------------------------------------
# Function, Constant, CosineLobe
# ------------------------------------------------------------------------------------------
class Tilted(Function):
    """A student's integrand: Function's constructor with an integral of its own."""

    def eval(self, omega_i):
        return omega_i.x

    def get_integral(self):
        return 0.0


def test_function_keeps_its_integral_value_as_the_ground_truth():
    """Function(integral_value) sets ground_truth = integral_value."""
    assert Tilted(3.25).ground_truth == 3.25
    assert Tilted(integral_value=-1.5).ground_truth == -1.5


@pytest.mark.parametrize("c", [1.0, 0.5, 0.8 / PI, 3])
def test_constant_is_its_value_everywhere_and_integrates_to_two_pi_times_it(c):
    """Constant(c): eval = c, get_integral = 2 pi c = ground_truth."""
    constant = Constant(c)
    assert isinstance(constant, Function)
    assert constant.const_value == c
    for omega in [(0.0, 1.0, 0.0), (1.0, 0.0, 0.0), (S3, S3, -S3)]:
        assert constant.eval(Vector3D(*omega)) == c
    assert constant.get_integral() == pytest.approx(2 * PI * c, rel=TIGHT)
    assert constant.ground_truth == constant.get_integral()


@pytest.mark.parametrize("exp, omega, expected", [
    (1, (0.0, 1.0, 0.0), 1.0),
    (3, (math.sqrt(0.75), 0.5, 0.0), 0.125),
    (2, (0.6, 0.8, 0.0), 0.64),
    (0, (1.0, 0.0, 0.0), 1.0),     # x^0 = 1, also for a cosine of 0
    (4, (0.0, 0.0, 1.0), 0.0),
])
def test_cosine_lobe_is_the_cosine_to_the_exp(exp, omega, expected):
    """CosineLobe(exp).eval(omega) = Dot((0, 1, 0), omega)^exp."""
    lobe = CosineLobe(exp)
    assert isinstance(lobe, Function)
    assert lobe.exp == exp
    assert lobe.eval(Vector3D(*omega)) == pytest.approx(expected, abs=TIGHT)


@pytest.mark.parametrize("exp", COSINE_EXPONENTS)
def test_cosine_lobe_integrates_to_two_pi_over_exp_plus_one(exp):
    """get_integral = 2 pi/(exp + 1) = ground_truth, and eval integrates to it."""
    lobe = CosineLobe(exp)
    assert lobe.get_integral() == pytest.approx(2 * PI / (exp + 1), rel=TIGHT)
    assert lobe.ground_truth == lobe.get_integral()
    assert hemisphere_integral(lobe.eval) == pytest.approx(lobe.get_integral(), abs=1e-9)


def test_constant_integrates_to_its_integral_by_quadrature():
    """Constant(c).eval integrates over the hemisphere to get_integral()."""
    constant = Constant(0.7)
    assert hemisphere_integral(constant.eval) == pytest.approx(constant.get_integral(),
                                                               abs=1e-9)


# ------------------------------------------------------------------------------------------
# sample_set_hemisphere: u1 = random(), then u2 = random(), per sample
# ------------------------------------------------------------------------------------------
SAMPLING_PDFS = [("uniform", UniformPDF, uniform_direction),
                 ("cosine^1", lambda: CosinePDF(1), lambda u1, u2: cosine_direction(1, u1, u2)),
                 ("cosine^4", lambda: CosinePDF(4), lambda u1, u2: cosine_direction(4, u1, u2))]


@pytest.mark.parametrize("name, make, formula", SAMPLING_PDFS,
                         ids=[name for name, _, _ in SAMPLING_PDFS])
@pytest.mark.parametrize("seed", [0, 1, 2024])
def test_sample_set_draws_u1_then_u2_from_the_global_generator(name, make, formula, seed):
    """Sample k is generate_dir(draw 2k, draw 2k+1) of random.seed(seed)'s draws: no more."""
    n = 25
    random.seed(seed)
    draws = [random.random() for _ in range(2 * n + 1)]
    pdf = make()
    random.seed(seed)
    directions, probabilities = sample_set_hemisphere(n, pdf)
    assert random.random() == draws[2 * n]  # it drew exactly 2n numbers
    assert isinstance(directions, list) and isinstance(probabilities, list)
    assert len(directions) == len(probabilities) == n
    for k, (direction, probability) in enumerate(zip(directions, probabilities)):
        u1, u2 = draws[2 * k], draws[2 * k + 1]
        assert type(direction) == Vector3D
        assert as_tuple(direction) == as_tuple(pdf.generate_dir(u1, u2)), k
        assert as_tuple(direction) == pytest.approx(formula(u1, u2), abs=TIGHT), k
        assert probability == pdf.get_val(direction), k


@pytest.mark.parametrize("name, make, formula", SAMPLING_PDFS,
                         ids=[name for name, _, _ in SAMPLING_PDFS])
def test_sample_set_is_the_same_for_the_same_seed(name, make, formula):
    """Two runs after random.seed(s) give equal lists, number for number."""
    random.seed(11)
    first_directions, first_probabilities = sample_set_hemisphere(40, make())
    random.seed(11)
    directions, probabilities = sample_set_hemisphere(40, make())
    assert [as_tuple(d) for d in directions] == [as_tuple(d) for d in first_directions]
    assert probabilities == first_probabilities


def test_sample_set_of_the_uniform_pdf_carries_its_constant_density():
    """Every probability of a uniform sample set is 1/(2 pi)."""
    random.seed(5)
    _, probabilities = sample_set_hemisphere(10, UniformPDF())
    assert probabilities == [1 / (2 * PI)] * 10


# ------------------------------------------------------------------------------------------
# center_around_normal, oriented_hemi_dir, rotate_around_y
# ------------------------------------------------------------------------------------------
NORMALS = [(0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0), (0.0, -1.0, 0.0),
           (1 / 3, 2 / 3, -2 / 3), (-S3, S3, S3), (0.0, 0.6, -0.8)]
DIRECTIONS = [uniform_direction(u1, u2) for u1, u2 in UNIT_SQUARE[::5]]


@pytest.mark.parametrize("normal", NORMALS)
def test_center_around_normal_follows_the_jittered_up_frame(normal):
    """The result is Normalize(v*x + w*y + u*z) of the spec's frame (v, w, u)."""
    n = Vector3D(*normal)
    for direction in DIRECTIONS:
        result = center_around_normal(Vector3D(*direction), n)
        assert type(result) == Vector3D
        assert as_tuple(result) == pytest.approx(centred(direction, normal), abs=TIGHT)


@pytest.mark.parametrize("normal", NORMALS)
def test_center_around_normal_maps_up_to_the_normal(normal):
    """(0, 1, 0), the pole of the hemisphere, goes to the normal itself."""
    result = center_around_normal(Vector3D(0.0, 1.0, 0.0), Vector3D(*normal))
    assert as_tuple(result) == pytest.approx(normal, abs=TIGHT)


@pytest.mark.parametrize("normal", NORMALS)
def test_center_around_normal_uses_an_orthonormal_right_handed_frame(normal):
    """The images v, w = n, u of the axes are unit, orthogonal, and u = v x w."""
    n = Vector3D(*normal)
    v, w, u = (as_tuple(center_around_normal(Vector3D(*axis), n))
               for axis in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)))
    for a, b in ((v, w), (w, u), (u, v)):
        assert dot(a, b) == pytest.approx(0.0, abs=TIGHT)
    for a in (v, w, u):
        assert dot(a, a) == pytest.approx(1.0, abs=TIGHT)
    assert cross(v, w) == pytest.approx(u, abs=TIGHT)


@pytest.mark.parametrize("normal", NORMALS)
def test_center_around_normal_keeps_the_angle_to_the_pole(normal):
    """Unit results in the hemisphere around n, at the angle to n they had to +y."""
    n = Vector3D(*normal)
    for direction in DIRECTIONS:
        result = as_tuple(center_around_normal(Vector3D(*direction), n))
        assert dot(result, result) == pytest.approx(1.0, abs=TIGHT)
        assert dot(result, normal) == pytest.approx(direction[1], abs=TIGHT)
        assert dot(result, normal) >= -TIGHT


@pytest.mark.parametrize("normal", NORMALS[:4])
@pytest.mark.parametrize("pdf", [UniformPDF(), CosinePDF(1), CosinePDF(5)],
                         ids=["uniform", "cosine^1", "cosine^5"])
def test_oriented_hemi_dir_is_the_generated_direction_centred_around_the_normal(pdf, normal):
    """oriented_hemi_dir(pdf, u1, u2, n) = center_around_normal(pdf.generate_dir(u1, u2), n)."""
    n = Vector3D(*normal)
    for u1, u2 in UNIT_SQUARE[::3]:
        result = oriented_hemi_dir(pdf, u1, u2, n)
        assert type(result) == Vector3D
        assert as_tuple(result) == as_tuple(center_around_normal(pdf.generate_dir(u1, u2), n))
        assert as_tuple(result) == pytest.approx(
            centred(as_tuple(pdf.generate_dir(u1, u2)), normal), abs=TIGHT)


@pytest.mark.parametrize("alpha, direction, expected", [
    (PI / 2, (1.0, 0.0, 0.0), (0.0, 0.0, -1.0)),   # x' = cos, z' = -sin
    (PI / 2, (0.0, 0.0, 1.0), (1.0, 0.0, 0.0)),    # x' = sin, z' = cos
    (PI, (1.0, 2.0, 3.0), (-1.0, 2.0, -3.0)),
    (PI / 4, (1.0, 0.5, 1.0), (math.sqrt(2), 0.5, 0.0)),
    (-PI / 2, (0.0, -0.7, 2.0), (-2.0, -0.7, 0.0)),
])
def test_rotate_around_y_by_hand(alpha, direction, expected):
    """x' = x cos a + z sin a, y' = y, z' = -x sin a + z cos a, for hand-picked angles."""
    result = rotate_around_y(alpha, Vector3D(*direction))
    assert type(result) == Vector3D
    assert as_tuple(result) == pytest.approx(expected, abs=TIGHT)
    assert result.y == direction[1]


def test_rotate_around_y_follows_the_formula():
    """The closed form for angles and directions that are not special."""
    for alpha in (0.0, 0.3, -1.1, 2.5, 7.0):
        x, y, z = 0.2, -0.5, 0.7
        expected = (x * math.cos(alpha) + z * math.sin(alpha), y,
                    -x * math.sin(alpha) + z * math.cos(alpha))
        assert as_tuple(rotate_around_y(alpha, Vector3D(x, y, z))) == pytest.approx(
            expected, abs=TIGHT)


# ------------------------------------------------------------------------------------------
# euclidean_to_disk and visualize_sample_set
# ------------------------------------------------------------------------------------------
# (direction, r = acos(y), phi = atan2(x, z)), worked out by hand
DISK = [((0.0, 1.0, 0.0), 0.0, 0.0),
        ((1.0, 0.0, 0.0), PI / 2, PI / 2),
        ((0.0, 0.0, 1.0), PI / 2, 0.0),
        ((0.0, 0.0, -1.0), PI / 2, PI),
        ((-1.0, 0.0, 0.0), PI / 2, -PI / 2),
        ((0.6, 0.8, 0.0), math.acos(0.8), PI / 2),
        ((0.0, 0.5, -math.sqrt(0.75)), PI / 3, PI),
        ((S3, S3, S3), math.acos(S3), PI / 4)]


def test_euclidean_to_disk_gives_the_polar_angle_and_the_azimuth():
    """Two numpy arrays: r_i = acos(Dot((0, 1, 0), d_i)) and phi_i = atan2(d_i.x, d_i.z)."""
    r, phi = euclidean_to_disk([Vector3D(*d) for d, _, _ in DISK])
    assert isinstance(r, np.ndarray) and isinstance(phi, np.ndarray)
    assert r.tolist() == pytest.approx([r_i for _, r_i, _ in DISK], abs=TIGHT)
    assert phi.tolist() == pytest.approx([phi_i for _, _, phi_i in DISK], abs=TIGHT)


@pytest.fixture
def shown(monkeypatch):
    """The figures visualize_sample_set shows, with plt.show replaced (nothing opens)."""
    figures = []
    before = set(plt.get_fignums())
    monkeypatch.setattr(plt, "show", lambda *args, **kwargs: figures.append(plt.gcf()))
    yield figures
    for number in set(plt.get_fignums()) - before:
        plt.close(number)


# The points (phi, r) of DISK, one after the other
SCATTERED = [value for _, r_i, phi_i in DISK for value in (phi_i, r_i)]


def polar_scatter(figure):
    """The one polar axes of figure and its one scatter plot."""
    polar = [axes for axes in figure.axes if axes.name == "polar"]
    assert len(polar) == 1, [axes.name for axes in figure.axes]
    assert len(polar[0].collections) == 1
    return polar[0], polar[0].collections[0]


def test_visualize_sample_set_scatters_phi_and_r_on_polar_axes(shown):
    """One polar scatter of (phi, r) on [0, 2 pi] x [0, pi/2], shown with plt.show()."""
    visualize_sample_set([Vector3D(*d) for d, _, _ in DISK])
    assert len(shown) == 1
    axes, points = polar_scatter(shown[0])
    assert np.ravel(points.get_offsets()).tolist() == pytest.approx(SCATTERED, abs=TIGHT)
    assert axes.get_xlim() == pytest.approx((0.0, 2 * PI), abs=TIGHT)
    assert axes.get_ylim() == pytest.approx((0.0, PI / 2), abs=TIGHT)
    assert points.get_array() is None  # one colour: no weights
    assert len(shown[0].axes) == 1  # and no colour bar


def test_visualize_sample_set_colours_the_points_by_weight(shown):
    """With weights: colormap jet from 1/n - 0.3/n to 1/n + 0.3/n, with a colour bar."""
    directions = [Vector3D(*d) for d, _, _ in DISK]
    n = len(directions)
    weights = [0.1, 0.15, 0.1, 0.2, 0.05, 0.12, 0.18, 0.1]
    visualize_sample_set(directions, weights=weights)
    assert len(shown) == 1
    axes, points = polar_scatter(shown[0])
    assert np.ravel(points.get_offsets()).tolist() == pytest.approx(SCATTERED, abs=TIGHT)
    assert np.asarray(points.get_array()).tolist() == pytest.approx(weights, abs=TIGHT)
    assert points.get_cmap().name == "jet"
    assert points.get_clim() == pytest.approx((1 / n - 0.3 / n, 1 / n + 0.3 / n), abs=TIGHT)
    assert points.colorbar is not None
    assert axes.get_ylim() == pytest.approx((0.0, PI / 2), abs=TIGHT)


# ------------------------------------------------------------------------------------------
# EnvironmentMap: the course reads the map in grey
# ------------------------------------------------------------------------------------------
MAP_WIDTH, MAP_HEIGHT = 9, 5


def texel_rgb(x, y):
    """The linear colour written at texel (x, y): red counts columns, green rows."""
    # every value is exact in RGBE (8-bit mantissas sharing the exponent of the largest)
    return (x + 1.0, y + 1.0, 0.5)


@pytest.fixture
def map_path(tmp_path):
    """A 9 x 5 latitude-longitude .hdr holding texel_rgb, written by OpenCV (BGR order)."""
    image = np.array([[texel_rgb(x, y)[::-1] for x in range(MAP_WIDTH)]
                      for y in range(MAP_HEIGHT)], dtype=np.float32)
    path = tmp_path / "map.hdr"
    assert cv2.imwrite(str(path), image)
    return str(path)


def course_reading(path):
    """The map as the course reads it: in grey, the grey copied to three channels."""
    return cv2.cvtColor(cv2.imread(path, flags=cv2.IMREAD_ANYDEPTH), cv2.COLOR_RGB2BGR)


def test_environment_map_holds_the_courses_grey_float32_array(map_path):
    """env_map_hdr is OpenCV's grey reading, float32, r = g = b; width and height."""
    env_map = EnvironmentMap(env_map_path=map_path)
    expected = course_reading(map_path)
    assert expected.shape == (MAP_HEIGHT, MAP_WIDTH, 3) and expected.dtype == np.float32
    assert env_map.env_map_hdr.dtype == np.float32
    assert np.array_equal(env_map.env_map_hdr, expected)
    assert (env_map.width, env_map.height) == (MAP_WIDTH, MAP_HEIGHT)


def test_environment_map_grey_is_the_weighted_sum_of_the_written_colour(map_path):
    """Each texel is 0.299 R + 0.587 G + 0.114 B of what was written, in all channels."""
    grey = EnvironmentMap(map_path).env_map_hdr
    for y in range(MAP_HEIGHT):
        for x in range(MAP_WIDTH):
            r, g, b = texel_rgb(x, y)
            # RGBE keeps 8 bits of each channel's mantissa against the largest channel
            tolerance = max(r, g, b) / 128
            assert grey[y, x, 0] == grey[y, x, 1] == grey[y, x, 2]
            assert grey[y, x, 0] == pytest.approx(0.299 * r + 0.587 * g + 0.114 * b,
                                                  abs=tolerance), (x, y)


# The last two tell the course's (1/PI) * ... from a division by PI: for (-0.6, 0, 0.8) u,
# for (0.48, -0.8, 0.36) v, differ in the last bit.
LAT_LONG_DIRECTIONS = [(0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (0.0, 0.0, 1.0),
                       (S3, S3, -S3), (0.6, 0.8, 0.0), (0.36, -0.48, 0.8), (0.0, 1.0, 0.0),
                       (0.0, -1.0, 0.0), (-0.48, 0.6, -0.64), (0.1, -0.995, 0.0),
                       (-0.6, 0.0, 0.8), (0.48, -0.8, 0.36)]


def lat_long(direction):
    """u = (1 + (1/PI) * atan2(x, -z)) / 2 and v = (1/PI) * acos(y), the course's way."""
    x, y, z = direction
    return (1 + (1 / PI) * math.atan2(x, -z)) / 2, (1 / PI) * math.acos(y)


@pytest.mark.parametrize("direction", LAT_LONG_DIRECTIONS)
def test_euclidean_to_lat_long_is_the_courses_arithmetic(map_path, direction):
    """(u, v) to the last bit, the operations in the spec's order."""
    u, v = EnvironmentMap(map_path).euclideanToLatLong(Vector3D(*direction))
    assert (u, v) == lat_long(direction)


@pytest.mark.parametrize("direction, column, row", [
    ((0.0, 0.0, -1.0), 4, 2),   # u = v = 0.5: floor(0.5 * 8), floor(0.5 * 4)
    ((1.0, 0.0, 0.0), 6, 2),    # atan2(1, 0) = pi/2: u = 0.75
    ((-1.0, 0.0, 0.0), 2, 2),   # u = 0.25
    ((0.0, 0.0, 1.0), 8, 2),    # atan2(0, -1) = pi: u = 1
    ((S3, S3, -S3), 5, 1),      # u = 0.625, v = acos(0.577)/pi = 0.304
    ((0.0, 1.0, 0.0), 8, 0),    # v = 0; -z = -0.0, atan2(0, -0) = pi: u = 1
    ((0.0, -1.0, 0.0), 8, 4),   # v = 1
])
def test_get_value_reads_the_texel_worked_out_by_hand(map_path, direction, column, row):
    """getValue(d) is the texel (floor(u*(width-1)), floor(v*(height-1)))."""
    env_map = EnvironmentMap(map_path)
    value = env_map.getValue(Vector3D(*direction))
    assert type(value) == RGBColor
    expected = course_reading(map_path)[row, column]
    assert (value.r, value.g, value.b) == tuple(expected)


@pytest.mark.parametrize("direction", LAT_LONG_DIRECTIONS)
def test_get_value_gives_numpy_float32_channels_of_the_formulas_texel(map_path, direction):
    """The channels are the float32 values of env_map_hdr, at the formula's index."""
    env_map = EnvironmentMap(map_path)
    value = env_map.getValue(Vector3D(*direction))
    u, v = lat_long(direction)
    column, row = math.floor(u * (MAP_WIDTH - 1)), math.floor(v * (MAP_HEIGHT - 1))
    assert all(type(channel) is np.float32 for channel in (value.r, value.g, value.b))
    assert (value.r, value.g, value.b) == tuple(course_reading(map_path)[row, column])
    assert value.r == value.g == value.b


# ------------------------------------------------------------------------------------------
# Lambertian.get_kd, and the integrators of the later practices
# ------------------------------------------------------------------------------------------
def test_lambertian_get_kd_is_kd_the_diffuse_colour_over_pi():
    """get_kd() returns kd, which already holds the 1/pi."""
    brdf = Lambertian(RGBColor(0.5, 1.0, PI))
    kd = brdf.get_kd()
    assert type(kd) == RGBColor
    assert (kd.r, kd.g, kd.b) == (0.5 / PI, 1.0 / PI, PI / PI)
    assert (kd.r, kd.g, kd.b) == (brdf.kd.r, brdf.kd.g, brdf.kd.b)


class GaussianProcess:
    """Stands for the Gaussian process of Practice 3."""


@pytest.mark.parametrize("make, filename", [
    (lambda: CMCIntegrator(8, "out/x", "_e"), "out/x_MC_8_samples_e"),
    (lambda: CMCIntegrator(40, "out/rendered_image"), "out/rendered_image_MC_40_samples"),
    (lambda: CMCIntegrator(n=1, filename_="img", experiment_name="_uniform"),
     "img_MC_1_samples_uniform"),
])
def test_cmc_integrator_names_its_file_after_its_samples(make, filename):
    """filename_ + '_MC_' + str(n) + '_samples' + experiment_name, and n_samples = n."""
    integrator = make()
    assert isinstance(integrator, Integrator)
    assert integrator.get_filename() == filename
    assert integrator.n_samples == int(filename.split("_MC_")[1].split("_")[0])


@pytest.mark.parametrize("experiment_name, filename", [
    (None, "out/x_BMC_8_samples"), ("_e", "out/x_BMC_8_samples_e")])
def test_bayesian_integrator_names_its_file_and_keeps_its_gaussian_process(experiment_name,
                                                                           filename):
    """filename_ + '_BMC_' + str(n) + '_samples' + experiment_name; myGP is the one given."""
    gp = GaussianProcess()
    if experiment_name is None:
        integrator = BayesianMonteCarloIntegrator(8, gp, "out/x")
    else:
        integrator = BayesianMonteCarloIntegrator(8, gp, "out/x", experiment_name)
    assert isinstance(integrator, Integrator)
    assert integrator.get_filename() == filename
    assert integrator.n_samples == 8
    assert integrator.myGP is gp
