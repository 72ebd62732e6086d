"""Unit tests for PyRT_Common: vectors, colours, rays, hit records and the environment map."""
import abc
import math

import cv2
import matplotlib.pyplot
import numpy as np
import pytest

import PyRT_Common
from helpers import as_tuple, rgb
from PyRT_Common import (BLACK, EPSILON, GREEN, HUGEVALUE, RED, WHITE, Cross, Dot,
                         EnvironmentMap, HitData, Length, Normalize, Ray, RGBColor, Vector3D,
                         check_constants, orient_normal)


# ------------------------------------------------------------------------------------------
# The star-import surface and the constants
# ------------------------------------------------------------------------------------------
def star_import():
    namespace = {}
    exec("from PyRT_Common import *", namespace)
    return namespace


@pytest.mark.parametrize("name, expected", [
    ("np", np), ("cv2", cv2), ("plt", matplotlib.pyplot),
    ("ABC", abc.ABC), ("abstractmethod", abc.abstractmethod),
    ("sqrt", math.sqrt), ("acos", math.acos), ("cos", math.cos), ("sin", math.sin),
    ("atan2", math.atan2), ("floor", math.floor), ("pi", math.pi),
])
def test_star_import_provides_libraries_and_math_names(name, expected):
    assert star_import()[name] is expected


@pytest.mark.parametrize("name", [
    "Vector3D", "Dot", "Cross", "Length", "Normalize", "orient_normal", "RGBColor",
    "BLACK", "WHITE", "GREEN", "RED", "Ray", "HitData", "EnvironmentMap", "random", "PDF",
    "UniformPDF", "CosinePDF", "Function", "Constant", "CosineLobe", "sample_set_hemisphere",
    "center_around_normal", "oriented_hemi_dir", "rotate_around_y", "euclidean_to_disk",
    "visualize_sample_set",
])
def test_star_import_provides_the_course_classes_and_functions(name):
    assert star_import()[name] is getattr(PyRT_Common, name)


def test_constants_have_the_course_values():
    namespace = star_import()
    assert namespace["EPSILON"] == 0.0001
    assert namespace["HUGEVALUE"] == 1e6
    assert namespace["PI"] == math.pi
    assert namespace["TWO_PI"] == pytest.approx(2 * math.pi, rel=1e-15)
    assert namespace["INVERTED_PI"] == pytest.approx(1 / math.pi, rel=1e-15)


# ------------------------------------------------------------------------------------------
# Vector3D
# ------------------------------------------------------------------------------------------
def test_vector_attributes_are_assignable():
    v = Vector3D(1.0, 2.0, 3.0)
    v.x, v.y, v.z = 4.0, 5.0, 6.0
    assert as_tuple(v) == (4.0, 5.0, 6.0)


def test_vector_addition_and_subtraction_work_per_component():
    a, b = Vector3D(1.0, 2.0, 3.0), Vector3D(0.5, -1.0, 4.0)
    assert as_tuple(a + b) == (1.5, 1.0, 7.0)
    assert as_tuple(a - b) == (0.5, 3.0, -1.0)


def test_vector_negation_flips_every_component():
    v = Vector3D(1.0, -2.0, 3.0)
    negated = -v
    assert type(negated) == Vector3D and negated is not v
    assert as_tuple(negated) == (-1.0, 2.0, -3.0)
    assert as_tuple(v) == (1.0, -2.0, 3.0)


def test_vector_operators_leave_their_operands_unchanged():
    a, b = Vector3D(1.0, 2.0, 3.0), Vector3D(0.5, -1.0, 4.0)
    _ = a + b, a - b, a * 2.0, a / 2.0, a.multiply(b)
    assert as_tuple(a) == (1.0, 2.0, 3.0)
    assert as_tuple(b) == (0.5, -1.0, 4.0)


def test_vector_scales_by_a_scalar_on_either_side_and_divides():
    v = Vector3D(1.0, -2.0, 3.0)
    assert as_tuple(v * 2.0) == (2.0, -4.0, 6.0)
    assert as_tuple(2.0 * v) == (2.0, -4.0, 6.0)
    assert as_tuple(v * 3) == (3.0, -6.0, 9.0)
    assert as_tuple(v / 4.0) == (0.25, -0.5, 0.75)


def test_vector_multiply_is_elementwise():
    # (1*4, 2*5, 3*6) = (4, 10, 18)
    assert as_tuple(Vector3D(1.0, 2.0, 3.0).multiply(Vector3D(4.0, 5.0, 6.0))) == (4.0, 10.0, 18.0)


def test_vector_repr_shows_floats():
    assert repr(Vector3D(1.0, 2.0, 3.0)) == "Vector3D(1.0, 2.0, 3.0)"
    assert repr(Vector3D(1, 2, 3)) == "Vector3D(1.0, 2.0, 3.0)"


@pytest.mark.parametrize("make", [Vector3D, RGBColor])
def test_vectors_and_colours_with_the_same_components_are_equal(make):
    assert make(1.0, -2.0, 3.5) == make(1.0, -2.0, 3.5)
    assert not make(1.0, -2.0, 3.5) != make(1.0, -2.0, 3.5)


@pytest.mark.parametrize("make", [Vector3D, RGBColor])
@pytest.mark.parametrize("other", [(9.0, -2.0, 3.5), (1.0, 9.0, 3.5), (1.0, -2.0, 9.0)],
                         ids=["first", "second", "third"])
def test_vectors_and_colours_differing_in_one_component_are_unequal(make, other):
    # x, y, z of a vector and r, g, b of a colour all count
    assert make(1.0, -2.0, 3.5) != make(*other)
    assert not make(1.0, -2.0, 3.5) == make(*other)


@pytest.mark.parametrize("make", [Vector3D, RGBColor])
def test_star_between_two_vectors_or_colours_is_a_clear_type_error(make):
    a, b = make(1.0, 2.0, 3.0), make(4.0, 5.0, 6.0)
    with pytest.raises(TypeError, match="multiply"):
        a * b


@pytest.mark.parametrize("make", [Vector3D, RGBColor])
def test_the_star_error_names_the_class_and_the_method_to_use(make):
    name = make.__name__
    with pytest.raises(TypeError) as error:
        make(1.0, 2.0, 3.0) * make(4.0, 5.0, 6.0)
    assert str(error.value) == (f"multiply a {name} by a number only; for the element-wise "
                                f"product of two {name} objects use a.multiply(b)")


@pytest.mark.parametrize("make", [Vector3D, RGBColor])
def test_the_division_error_names_the_class(make):
    with pytest.raises(TypeError, match=rf"^divide a {make.__name__} by a number only; "
                                        rf"for the element-wise product of two "
                                        rf"{make.__name__} objects"):
        make(1.0, 2.0, 3.0) / make(4.0, 5.0, 6.0)


@pytest.mark.parametrize("make", [Vector3D, RGBColor])
def test_dividing_by_a_vector_or_colour_is_a_type_error(make):
    with pytest.raises(TypeError):
        make(1.0, 2.0, 3.0) / make(4.0, 5.0, 6.0)


def test_dot_product():
    # 1*4 + 2*5 + 3*6 = 32
    assert Dot(Vector3D(1.0, 2.0, 3.0), Vector3D(4.0, 5.0, 6.0)) == 32.0


def test_cross_product():
    # (2*6 - 3*5, 3*4 - 1*6, 1*5 - 2*4) = (-3, 6, -3)
    assert as_tuple(Cross(Vector3D(1.0, 2.0, 3.0), Vector3D(4.0, 5.0, 6.0))) == (-3.0, 6.0, -3.0)


def test_cross_product_is_right_handed():
    assert as_tuple(Cross(Vector3D(1.0, 0.0, 0.0), Vector3D(0.0, 1.0, 0.0))) == (0.0, 0.0, 1.0)


def test_length():
    # sqrt(9 + 16 + 144) = 13
    assert Length(Vector3D(3.0, 4.0, 12.0)) == 13.0


def test_normalize_divides_by_the_length():
    # (3, 4, 12) / 13
    n = Normalize(Vector3D(3.0, 4.0, 12.0))
    assert as_tuple(n) == pytest.approx((3 / 13, 4 / 13, 12 / 13), rel=1e-15)
    assert Length(n) == pytest.approx(1.0, rel=1e-15)


def test_normalize_of_the_zero_vector_raises_value_error():
    with pytest.raises(ValueError) as error:
        Normalize(Vector3D(0.0, 0.0, 0.0))
    assert str(error.value) == ("Normalize: cannot normalise the zero vector "
                                "Vector3D(0.0, 0.0, 0.0), it has no direction; check how the "
                                "vector was computed")


@pytest.mark.parametrize("direction, expected", [
    ((0.0, 0.0, -1.0), (0.0, 0.0, -1.0)),  # n.d = -1 < 0: flipped
    ((0.0, 0.0, 1.0), (0.0, 0.0, 1.0)),    # n.d = 1: kept
    ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),    # n.d = 0 is not < 0: kept
    ((3.0, 1.0, -0.5), (0.0, 0.0, -1.0)),  # n.d = -0.5: flipped
])
def test_orient_normal_flips_only_when_dot_is_negative(direction, expected):
    normal = Vector3D(0.0, 0.0, 1.0)
    assert as_tuple(orient_normal(normal, Vector3D(*direction))) == expected


def test_orient_normal_flips_every_component():
    # n.d = (1, -2, 3).(0, 0, -1) = -3 < 0: the normal becomes -n = (-1, 2, -3)
    flipped = orient_normal(Vector3D(1.0, -2.0, 3.0), Vector3D(0.0, 0.0, -1.0))
    assert type(flipped) == Vector3D
    assert as_tuple(flipped) == (-1.0, 2.0, -3.0)


# ------------------------------------------------------------------------------------------
# RGBColor
# ------------------------------------------------------------------------------------------
def test_colour_arithmetic():
    c, d = RGBColor(0.5, 1.0, 2.0), RGBColor(0.25, 0.5, 4.0)
    assert rgb(c + d) == (0.75, 1.5, 6.0)
    assert rgb(c - d) == (0.25, 0.5, -2.0)
    assert rgb(c * 2.0) == (1.0, 2.0, 4.0)
    assert rgb(c / 2.0) == (0.25, 0.5, 1.0)
    assert rgb(c.multiply(d)) == (0.125, 0.5, 8.0)


def test_colour_repr():
    assert repr(RGBColor(0.5, 1.0, 2.0)) == "RGBColor(0.5, 1.0, 2.0)"


def test_clamp_works_in_place():
    c = RGBColor(-1.0, 0.5, 2.0)
    c.clamp(0.0, 1.0)
    assert rgb(c) == (0.0, 0.5, 1.0)


COLOUR_CONSTANTS = [("BLACK", BLACK, (0.0, 0.0, 0.0)), ("WHITE", WHITE, (1.0, 1.0, 1.0)),
                    ("GREEN", GREEN, (0.0, 1.0, 0.0)), ("RED", RED, (1.0, 0.0, 0.0))]


@pytest.mark.parametrize("name, constant, expected", COLOUR_CONSTANTS)
def test_colour_constants_are_plain_course_colours_with_their_values(name, constant, expected):
    # Student code checks `type(c) == RGBColor` and compares with `==`.
    assert type(constant) == RGBColor
    assert rgb(constant) == expected
    assert constant == RGBColor(*expected)


def test_intact_constants_pass_the_check():
    check_constants("here")  # raises nothing
    assert [rgb(c) for _, c, _ in COLOUR_CONSTANTS] == [e for _, _, e in COLOUR_CONSTANTS]


@pytest.mark.parametrize("name, constant, expected", COLOUR_CONSTANTS)
@pytest.mark.parametrize("channel", ["r", "g", "b"])
def test_a_constant_changed_in_place_is_reported_with_the_fix_and_restored(
        name, constant, expected, channel):
    color = constant  # what a student writes before `color.r += 0.5`
    setattr(color, channel, getattr(color, channel) + 0.5)
    with pytest.raises(RuntimeError) as error:
        check_constants("Scene.save_image")
    message = str(error.value)
    assert message.startswith("Scene.save_image: ")
    assert f"shared colour {name} was changed" in message
    changed = [value + 0.5 if c == channel else value for c, value in zip("rgb", expected)]
    assert f"changed in place to RGBColor({changed[0]}, {changed[1]}, {changed[2]})," in message
    assert f"color = RGBColor{expected}" in message  # what to write instead
    assert rgb(constant) == expected


def test_clamping_black_to_the_unit_range_changes_nothing():
    BLACK.clamp(0, 1)
    assert rgb(BLACK) == (0.0, 0.0, 0.0)
    check_constants("here")


def test_clamping_a_constant_in_place_is_reported():
    WHITE.clamp(0.0, 0.5)  # WHITE becomes (0.5, 0.5, 0.5) ...
    with pytest.raises(RuntimeError, match="WHITE"):
        check_constants("here")
    assert rgb(WHITE) == (1.0, 1.0, 1.0)  # ... and gets its value back


def test_arithmetic_on_a_constant_gives_a_mutable_colour():
    c = BLACK + RGBColor(0.5, 0.5, 0.5)
    c.r = 1.0
    assert rgb(c) == (1.0, 0.5, 0.5)
    assert rgb(BLACK) == (0.0, 0.0, 0.0)


# ------------------------------------------------------------------------------------------
# Ray and HitData
# ------------------------------------------------------------------------------------------
def test_ray_defaults():
    ray = Ray()
    assert as_tuple(ray.o) == (0.0, 0.0, 0.0)
    assert as_tuple(ray.d) == (0.0, 0.0, 0.0)
    assert ray.t_max == HUGEVALUE
    assert ray.t_min == EPSILON


def test_ray_default_vectors_are_fresh_and_not_shared():
    first, second = Ray(), Ray()
    assert first.o is not second.o and first.d is not second.d and first.o is not first.d
    first.o.x = 5.0
    first.d.y = 7.0
    assert as_tuple(second.o) == (0.0, 0.0, 0.0)
    assert as_tuple(second.d) == (0.0, 0.0, 0.0)
    assert as_tuple(Ray().o) == (0.0, 0.0, 0.0)


def test_ray_positional_arguments():
    o, d = Vector3D(1.0, 2.0, 3.0), Vector3D(0.0, 0.0, -1.0)
    ray = Ray(o, d, 25.0)
    assert (ray.o, ray.d, ray.t_max, ray.t_min) == (o, d, 25.0, EPSILON)


def test_ray_with_direction_keyword_starts_at_the_origin():
    ray = Ray(direction=Vector3D(0.0, 1.0, 0.0))
    assert as_tuple(ray.o) == (0.0, 0.0, 0.0)
    assert as_tuple(ray.d) == (0.0, 1.0, 0.0)
    assert ray.t_max == HUGEVALUE


def test_ray_built_empty_then_assigned():
    ray = Ray()
    ray.o = Vector3D(1.0, 1.0, 1.0)
    ray.d = Vector3D(0.0, 0.0, -1.0)
    # o + d*2.5 = (1, 1, 1 - 2.5)
    assert as_tuple(ray.get_hitpoint(2.5)) == (1.0, 1.0, -1.5)


def test_get_hitpoint_is_origin_plus_direction_times_t():
    ray = Ray(Vector3D(1.0, 2.0, 3.0), Vector3D(0.5, -1.0, 2.0))
    # (1 + 0.5*4, 2 - 1*4, 3 + 2*4) = (3, -2, 11)
    assert as_tuple(ray.get_hitpoint(4.0)) == (3.0, -2.0, 11.0)


def test_hitdata_defaults():
    hit = HitData()
    assert hit.has_hit is False
    assert type(hit.hit_point) == Vector3D and type(hit.normal) == Vector3D
    assert as_tuple(hit.hit_point) == (0.0, 0.0, 0.0)
    assert as_tuple(hit.normal) == (0.0, 0.0, 0.0)
    assert hit.hit_distance == HUGEVALUE
    assert hit.primitive_index == -1


def test_changing_one_hitdata_default_vector_never_leaks_into_another():
    first, second = HitData(), HitData()
    first.hit_point.x = 1.0
    first.normal.z = 3.0
    assert as_tuple(first.hit_point) == (1.0, 0.0, 0.0)
    assert as_tuple(first.normal) == (0.0, 0.0, 3.0)
    assert as_tuple(second.hit_point) == (0.0, 0.0, 0.0)
    assert as_tuple(second.normal) == (0.0, 0.0, 0.0)
    assert as_tuple(HitData().hit_point) == (0.0, 0.0, 0.0)
    assert first.hit_point is not first.normal


def test_hitdata_keeps_its_arguments():
    p, n = Vector3D(1.0, 2.0, 3.0), Vector3D(0.0, 1.0, 0.0)
    hit = HitData(True, p, n, 4.5, 2)
    assert (hit.has_hit, hit.hit_point, hit.normal, hit.hit_distance,
            hit.primitive_index) == (True, p, n, 4.5, 2)


def test_hitdata_repr_of_a_miss_says_only_that():
    assert repr(HitData()) == "HitData(has_hit=False)"


def test_hitdata_repr_of_a_hit_shows_every_field():
    hit = HitData(True, Vector3D(1.0, 2.0, 3.0), Vector3D(0.0, 1.0, 0.0), 4.5, 2)
    assert repr(hit) == ("HitData(has_hit=True, hit_point=Vector3D(1.0, 2.0, 3.0), "
                         "normal=Vector3D(0.0, 1.0, 0.0), hit_distance=4.5, primitive_index=2)")


# ------------------------------------------------------------------------------------------
# EnvironmentMap
# ------------------------------------------------------------------------------------------
ENV_WIDTH, ENV_HEIGHT = 9, 5


@pytest.fixture
def env_map(tmp_path):
    """A 9 x 5 map whose texel (x, y) holds RGB (x + 1, y + 1, 0.5): the red channel names
    the column and the green channel the row. The values survive RGBE exactly."""
    ys, xs = np.mgrid[0:ENV_HEIGHT, 0:ENV_WIDTH]
    image_rgb = np.stack([xs + 1.0, ys + 1.0, np.full(xs.shape, 0.5)], axis=2)
    path = tmp_path / "map.hdr"
    assert cv2.imwrite(str(path), image_rgb[:, :, ::-1].astype(np.float32))  # OpenCV: BGR
    return EnvironmentMap(str(path), colour=True)


def test_environment_map_missing_file_names_the_path(tmp_path):
    path = tmp_path / "no_such_map.hdr"
    with pytest.raises(FileNotFoundError) as error:
        EnvironmentMap(str(path))
    assert str(error.value) == (f"EnvironmentMap: no image file at {str(path)!r}; give the "
                                "path of a latitude-longitude .hdr image")


def test_environment_map_that_is_no_image_names_the_file_and_the_formats(tmp_path):
    path = tmp_path / "notes.hdr"
    path.write_text("not an image")
    with pytest.raises(ValueError) as error:
        EnvironmentMap(path)
    assert str(error.value) == (f"EnvironmentMap: OpenCV cannot read {str(path)!r}; give it "
                                "an .hdr (Radiance) or .exr latitude-longitude image")


def test_environment_map_read_in_colour_is_stored_as_rgb(env_map):
    assert env_map.env_map_hdr.shape == (ENV_HEIGHT, ENV_WIDTH, 3)
    assert env_map.env_map_hdr.dtype == np.float32
    assert (env_map.width, env_map.height) == (ENV_WIDTH, ENV_HEIGHT)
    # texel (x=2, y=3) was written as RGB (3, 4, 0.5)
    assert tuple(env_map.env_map_hdr[3, 2]) == pytest.approx((3.0, 4.0, 0.5), rel=1e-2)


def test_environment_map_is_read_in_grey_as_the_course_reads_it(env_map, tmp_path):
    # The course's cv2.imread(path, flags=cv2.IMREAD_ANYDEPTH): OpenCV's grey reading,
    # 0.299 R + 0.587 G + 0.114 B, in all three channels, as float32 values
    grey_map = EnvironmentMap(str(tmp_path / "map.hdr"))
    opencv = cv2.imread(str(tmp_path / "map.hdr"), flags=cv2.IMREAD_ANYDEPTH)
    assert grey_map.env_map_hdr.dtype == np.float32
    for channel in range(3):
        assert np.array_equal(grey_map.env_map_hdr[:, :, channel], opencv)
    # texel (x=2, y=3) was written as RGB (3, 4, 0.5)
    assert opencv[3, 2] == pytest.approx(0.299 * 3 + 0.587 * 4 + 0.114 * 0.5, rel=1e-2)
    value = grey_map.getValue(Vector3D(0.0, 0.0, -1.0))  # texel (4, 2)
    assert all(type(channel) is np.float32 for channel in rgb(value))
    assert value.r == value.g == value.b == opencv[2, 4]


S3 = 1 / math.sqrt(3)


@pytest.mark.parametrize("direction, u, v", [
    ((0.0, 0.0, -1.0), 0.5, 0.5),    # atan2(0, 1) = 0, acos(0) = pi/2
    ((1.0, 0.0, 0.0), 0.75, 0.5),    # atan2(1, 0) = pi/2: u = (1 + 1/2)/2
    ((-1.0, 0.0, 0.0), 0.25, 0.5),   # atan2(-1, 0) = -pi/2: u = (1 - 1/2)/2
    ((0.0, 0.0, 1.0), 1.0, 0.5),     # atan2(0, -1) = pi: u = (1 + 1)/2
    ((S3, S3, -S3), 0.625, math.acos(S3) / math.pi),  # atan2(s, s) = pi/4: u = (1 + 1/4)/2
])
def test_euclidean_to_lat_long_follows_the_formula(env_map, direction, u, v):
    assert env_map.euclideanToLatLong(Vector3D(*direction)) == pytest.approx((u, v), abs=1e-12)


@pytest.mark.parametrize("direction, v", [
    ((0.0, 1.0, 0.0), 0.0),   # acos(1) = 0: straight up is the top row
    ((0.0, -1.0, 0.0), 1.0),  # acos(-1) = pi: straight down is the bottom row
])
def test_euclidean_to_lat_long_poles(env_map, direction, v):
    assert env_map.euclideanToLatLong(Vector3D(*direction))[1] == pytest.approx(v, abs=1e-12)


@pytest.mark.parametrize("direction, column, row", [
    ((0.0, 0.0, -1.0), 4, 2),   # floor(0.5 * 8), floor(0.5 * 4)
    ((1.0, 0.0, 0.0), 6, 2),    # floor(0.75 * 8)
    ((-1.0, 0.0, 0.0), 2, 2),   # floor(0.25 * 8)
    ((0.0, 0.0, 1.0), 8, 2),    # floor(1.0 * 8)
    ((S3, S3, -S3), 5, 1),      # floor(0.625 * 8), floor(0.3041 * 4)
])
def test_get_value_returns_the_texel_under_the_direction(env_map, direction, column, row):
    value = env_map.getValue(Vector3D(*direction))
    assert isinstance(value, RGBColor)
    assert rgb(value) == pytest.approx((column + 1.0, row + 1.0, 0.5), rel=1e-2)


@pytest.mark.parametrize("direction, row", [((0.0, 1.0, 0.0), 0), ((0.0, -1.0, 0.0), 4)])
def test_get_value_at_the_poles_reads_the_top_and_bottom_rows(env_map, direction, row):
    assert env_map.getValue(Vector3D(*direction)).g == pytest.approx(row + 1.0, rel=1e-2)


# A unit direction computed with rounding can have a component just past 1: acos would
# raise on it. It is straight up (v = 0, the top row) or straight down (v = 1, the bottom
# row), one ulp off.
JUST_PAST_ONE = math.nextafter(1.0, 2.0)


@pytest.mark.parametrize("y, v, row", [(JUST_PAST_ONE, 0.0, 0), (-JUST_PAST_ONE, 1.0, 4)],
                         ids=["up", "down"])
def test_direction_a_rounding_error_past_a_pole_reads_the_pole_row(env_map, y, v, row):
    direction = Vector3D(0.0, y, 0.0)
    assert env_map.euclideanToLatLong(direction)[1] == v
    assert env_map.getValue(direction).g == pytest.approx(row + 1.0, rel=1e-2)


def test_repr_shows_a_component_that_is_not_a_number_as_it_is():
    # A student's slip such as RGBColor(0.5, normal, 0.5) must print, so that error
    # messages can show it; numbers of every kind still print as plain floats.
    assert repr(RGBColor(0.5, Vector3D(0, 1, 0), "0.5")) == \
        "RGBColor(0.5, Vector3D(0.0, 1.0, 0.0), '0.5')"
    assert repr(Vector3D(np.float64(0.25), np.int64(2), None)) == "Vector3D(0.25, 2.0, None)"
