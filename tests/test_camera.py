"""Unit tests for PyRT_Core's Camera, against values computed by hand."""
import math

import pytest

from helpers import approx3, as_tuple
from PyRT_Core import Camera


# ------------------------------------------------------------------------------------------
# Camera
# ------------------------------------------------------------------------------------------
def test_camera_attributes():
    camera = Camera(4, 3, 90)
    assert (camera.width, camera.height) == (4, 3)
    assert camera.vertical_fov == pytest.approx(math.pi / 2, rel=1e-15)  # 90 degrees
    assert camera.aspect_ratio == pytest.approx(4 / 3, rel=1e-15)


@pytest.mark.parametrize("width, height, x, y", [(5, 3, 2, 1), (1, 1, 0, 0), (7, 9, 3, 4)])
def test_camera_centre_pixel_of_odd_image_looks_straight_ahead(width, height, x, y):
    # x_s = 2(x + 0.5)/width - 1 = 0 and y_s = 1 - 2(y + 0.5)/height = 0
    d = Camera(width, height, 60).get_direction(x, y)
    assert as_tuple(d) == approx3((0.0, 0.0, -1.0))


R15 = 1 / math.sqrt(1.5)
R22 = 1 / math.sqrt(22)


@pytest.mark.parametrize("x, y, expected", [
    # 2 x 2, tan(45) = 1, aspect 1: x_s, y_s = +-0.5, point (+-0.5, +-0.5, -1) / sqrt(1.5)
    (0, 0, (-0.5 * R15, 0.5 * R15, -R15)),
    (1, 0, (0.5 * R15, 0.5 * R15, -R15)),
    (0, 1, (-0.5 * R15, -0.5 * R15, -R15)),
    (1, 1, (0.5 * R15, -0.5 * R15, -R15)),
])
def test_camera_direction_at_corners_of_2x2_image(x, y, expected):
    assert as_tuple(Camera(2, 2, 90).get_direction(x, y)) == approx3(expected)


@pytest.mark.parametrize("x, y, expected", [
    # 4 x 3, tan(45) = 1, aspect 4/3: pixel (0, 0) has x_s = 1/4 - 1 = -3/4, y_s = 1 - 1/3 =
    # 2/3, point (-3/4 * 4/3, 2/3, -1) = (-1, 2/3, -1), length sqrt(22)/3: (-3, 2, -3)/sqrt(22)
    (0, 0, (-3 * R22, 2 * R22, -3 * R22)),
    (3, 0, (3 * R22, 2 * R22, -3 * R22)),
    (0, 2, (-3 * R22, -2 * R22, -3 * R22)),
    (3, 2, (3 * R22, -2 * R22, -3 * R22)),
    # pixel (1, 1): x_s = 3/4 - 1 = -1/4, y_s = 0: point (-1/3, 0, -1) -> (-1, 0, -3)/sqrt(10)
    (1, 1, (-1 / math.sqrt(10), 0.0, -3 / math.sqrt(10))),
])
def test_camera_direction_of_4x3_image(x, y, expected):
    assert as_tuple(Camera(4, 3, 90).get_direction(x, y)) == approx3(expected)


def test_camera_direction_uses_the_vertical_fov():
    # fov 60: tan(30) = 1/sqrt(3); 1 x 2 pixel (0, 0): y_s = 1/2, point (0, 1/(2 sqrt 3), -1)
    y = 0.5 / math.sqrt(3)
    length = math.sqrt(1 + y * y)
    d = Camera(1, 2, 60).get_direction(0, 0)
    assert as_tuple(d) == approx3((0.0, y / length, -1.0 / length))


@pytest.mark.parametrize("x, y, u, v, point", [
    # 4 x 2, tan(45) = 1, aspect 2: the point (u, v) of pixel (x, y) has
    # x_s = 2(x + u)/4 - 1 and y_s = 1 - 2(y + v)/2, and lies at (2 x_s, y_s, -1)
    (0, 0, 0.0, 0.0, (-2.0, 1.0, -1.0)),     # the image's top left corner
    (1, 0, 0.0, 1.0, (-1.0, 0.0, -1.0)),     # x_s = -1/2, y_s = 0
    (1, 0, 1.0, 0.0, (0.0, 1.0, -1.0)),      # x_s = 0, y_s = 1
    (2, 1, 0.25, 0.75, (0.25, -0.75, -1.0)),  # x_s = 1/8, y_s = -3/4
    (3, 1, 0.75, 0.25, (1.75, -0.25, -1.0)),  # x_s = 7/8, y_s = -1/4
])
def test_camera_direction_through_a_point_inside_the_pixel(x, y, u, v, point):
    length = math.sqrt(sum(c * c for c in point))
    d = Camera(4, 2, 90).get_direction(x, y, u, v)
    assert as_tuple(d) == approx3(tuple(c / length for c in point))


def test_camera_direction_through_the_pixel_centre_is_the_default():
    camera = Camera(4, 2, 90)
    assert as_tuple(camera.get_direction(2, 1, 0.5, 0.5)) == as_tuple(camera.get_direction(2, 1))


def test_camera_directions_are_unit_length():
    camera = Camera(7, 5, 75)
    for y in range(5):
        for x in range(7):
            d = camera.get_direction(x, y)
            assert math.sqrt(d.x ** 2 + d.y ** 2 + d.z ** 2) == pytest.approx(1.0, abs=1e-15)
