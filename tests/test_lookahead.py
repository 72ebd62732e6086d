"""pyrt/acceleration/lookahead.py, through AcceleratedBMC: a task's colours made together
ahead of the loop are handed out only for the ray and the draws they were made with, so
that any loop gets the plain code's colours, bit for bit; the course's loop gets them
made together, and a loop of another kind ends the lookahead."""
import random as random_module

import pytest

import pyrt.acceleration.accelerated
from helpers import emitter, fov90_scene, sky_sphere_scene, with_map_and_emitter
from pyrt.acceleration import lookahead
from pyrt.acceleration.accelerated import accelerated
from pyrt.acceleration.bayesian import AcceleratedBMC
from pyrt.gaussian_pools import make_gp_pool
from pyrt.rows import TaskCamera
from PyRT_Common import (INFINITY, Constant, CosineLobe, CosinePDF, Ray, RGBColor, UniformPDF,
                         Vector3D)
from PyRT_Core import Parallelogram
from PyRT_Integrators import BayesianMonteCarloIntegrator, BMCISIntegrator

SIZE, ROW = 16, 9  # the scene's pixels a side; the row whose rays a task traces


def course_ray(direction):
    """A camera ray as the course's render loop makes it."""
    return Ray(Vector3D(0.0, 0.0, 0.0), direction, INFINITY, 0.0)


def in_order(compute_color, directions):
    """The course's loop: every ray once, in order."""
    return [compute_color(course_ray(d)) for d in directions]


def drawing_between(compute_color, directions):
    """A loop that draws a number of its own before each pixel."""
    colours = []
    for d in directions:
        random_module.random()
        colours.append(compute_color(course_ray(d)))
    return colours


def backwards(compute_color, directions):
    """The rays from the last to the first."""
    return [compute_color(course_ray(d)) for d in reversed(directions)]


def each_twice(compute_color, directions):
    """Every ray traced twice over."""
    return [compute_color(course_ray(d)) for d in directions for _ in range(2)]


def own_rays(compute_color, directions):
    """Rays of its own: the default range of a Ray, and an origin of -0.0."""
    return [compute_color(Ray(Vector3D(-0.0, 0.0, 0.0), d) if k % 2 else
                          Ray(Vector3D(0.0, 0.0, 0.0), d)) for k, d in enumerate(directions)]


def short_of_the_scene(compute_color, directions):
    """Every other ray ending at a distance of 1, before anything of the scene."""
    return [compute_color(Ray(Vector3D(0.0, 0.0, 0.0), d, 1.0 if k % 2 else INFINITY, 0.0))
            for k, d in enumerate(directions)]


def coincident_emitters(size):
    """A white floor under two emitting ceilings in one place, of different emissions: a
    sample ray meets both at one distance, and the first in object_list is the one met."""
    floor = Parallelogram(Vector3D(-4.0, -1.0, -1.0), Vector3D(8.0, 0.0, 0.0),
                          Vector3D(0.0, 0.0, -8.0))
    ceilings = [emitter(Parallelogram(Vector3D(-4.0, 1.0, -1.0), Vector3D(0.0, 0.0, -8.0),
                                      Vector3D(8.0, 0.0, 0.0)), emission)
                for emission in [(1.0, 1.0, 1.0), (5.0, 0.0, 0.0)]]
    scene = fov90_scene(size, size, [(floor, RGBColor(1.0, 1.0, 1.0))])
    for ceiling in ceilings:
        scene.add_object(ceiling)
    return scene


LOOPS = [in_order, drawing_between, backwards, each_twice, own_rays, short_of_the_scene]
KINDS = {"bmc": (BayesianMonteCarloIntegrator, UniformPDF(), Constant(1)),
         "bmc_is": (BMCISIntegrator, CosinePDF(1), CosineLobe(1))}


def task_colours(kind, make_scene, loop, fused):
    """The channels of the colours `loop` gets from the integrator `kind` on one task's
    camera (a row of the scene's), with the fused compute_color or the plain one."""
    integrator_class, pdf, p_func = KINDS[kind]
    random_module.seed(3)
    pool = make_gp_pool(3, 10, pdf, p_func).gps
    integrator = integrator_class(10, pool, "unused")
    integrator.add_scene(make_scene(SIZE))
    scene = integrator.scene
    directions = [scene.camera.get_direction(x, ROW) for x in range(SIZE)]
    random_module.seed(11)
    with accelerated(integrator):
        assert (type(getattr(integrator.compute_color, "__self__", None)) is not
                integrator_class) is fused
        if not fused:
            return [(c.r, c.g, c.b) for c in loop(integrator.compute_color, directions)]
        scene.camera = TaskCamera(scene.camera, directions)
        colours = loop(integrator.compute_color, directions)
    return [(c.r, c.g, c.b) for c in colours]


@pytest.mark.parametrize("loop", LOOPS)
@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("make_scene", [sky_sphere_scene, with_map_and_emitter,
                                        coincident_emitters])
def test_any_loop_gets_the_plain_codes_colours_bit_for_bit(monkeypatch, kind, make_scene,
                                                           loop):
    fused = task_colours(kind, make_scene, loop, True)
    with monkeypatch.context() as patch:
        for name in ("bmc", "bmcis"):
            patch.delitem(pyrt.acceleration.accelerated.FUSED_INTEGRATORS, name)
        plain = task_colours(kind, make_scene, loop, False)
    assert any(any(colour) for colour in plain)
    assert fused == plain


def pixels_made_together(monkeypatch, loop):
    """The numbers of pixels made() made at once, and whether the lookahead stopped."""
    sizes, stops = [], []
    made, stop = AcceleratedBMC.made, lookahead.Lookahead.stop
    monkeypatch.setattr(AcceleratedBMC, "made",
                        lambda self, frames, draws: sizes.append(len(frames))
                        or made(self, frames, draws))
    monkeypatch.setattr(lookahead.Lookahead, "stop",
                        lambda self: stops.append(True) or stop(self))
    task_colours("bmc", sky_sphere_scene, loop, True)
    return sizes, bool(stops)


def test_the_courses_loop_gets_its_rows_colours_made_together(monkeypatch):
    sizes, stopped = pixels_made_together(monkeypatch, in_order)
    # one call for all the row's hits (the row's 16 rays, a window of 256)
    assert len(sizes) == 1 and sizes[0] > 1 and not stopped


@pytest.mark.parametrize("loop", [drawing_between, backwards, own_rays, short_of_the_scene])
def test_a_loop_of_another_kind_ends_the_lookahead_and_each_pixel_is_made_alone(monkeypatch,
                                                                                loop):
    sizes, stopped = pixels_made_together(monkeypatch, loop)
    # the first call makes the window's hits together; from the first ray or draw that
    # differs on, each hit is made alone
    assert stopped and sizes[0] > 1 and len(sizes) > 4 and set(sizes[1:]) == {1}


def test_a_prediction_that_fails_leaves_the_failure_to_its_own_pixel():
    class Failing:
        camera = TaskCamera(None, [Vector3D(0.0, 0.0, -1.0)] * 4)

    def predict(rays, draw):
        raise ValueError("cannot convert float NaN to integer")

    ahead = lookahead.Lookahead(Failing, random_module.Random(1), predict)
    ray = course_ray(Failing.camera.directions[0])
    assert [ahead.prediction(ray) for _ in range(4)] == [None] * 4
    assert ahead.next_ray == -1  # stopped: nothing predicted again for the task


@pytest.mark.parametrize("origin, t_min", [((-0.0, 0.0, 0.0), 0.0), ((0.0, 0.0, 0.0), -0.0)])
def test_a_ray_with_a_negative_zero_is_not_the_predicted_one(origin, t_min):
    class Task:
        camera = TaskCamera(None, [Vector3D(0.0, 0.0, -1.0)] * 2)

    ahead = lookahead.Lookahead(Task, random_module.Random(1), lambda rays, draw: [
        lookahead.Prediction(r.d.x, r.d.y, r.d.z, (), None, None) for r in rays])
    assert ahead.prediction(course_ray(Task.camera.directions[0])) is not None
    assert ahead.prediction(Ray(Vector3D(*origin), Task.camera.directions[1], INFINITY,
                                t_min)) is None
