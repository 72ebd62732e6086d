"""Lookahead: the colours of the camera rays a task's loop traces next, made together on
arrays before the loop asks for them, and handed out only when the loop asks for that very
ray and random() gives the very numbers they were made with.

During a render the scene's camera is a task's camera (pyrt.rows.TaskCamera): a column of
rays, which the course's loop traces in order, y = 0, 1, ..., each as
Ray(Vector3D(0, 0, 0), camera.get_direction(0, y), INFINITY, 0.0). A fused integrator
whose compute_color draws a few numbers per pixel (AcceleratedBMC) predicts the next
`window` rays: their camera hits, and the draws each would make, from a copy of the
random generator's state. A prediction is used only if the ray asked for has the
predicted ray's origin, direction and range, and the numbers the live generator then
draws, in the plain code's order, are the predicted ones: a colour depends on nothing
else, so it is the one compute_color would make then. Any other loop (rays in another
order, draws of its own between pixels, a camera of its own) ends the lookahead for the
task, and each pixel is made on its own from then on.
"""
import random
from math import copysign
from typing import NamedTuple, Optional

from PyRT_Common import INFINITY, Ray, Vector3D

# Camera rays predicted at once: enough to share numpy's cost per operation among many
# sample rays, few enough to keep the arrays small
WINDOW = 256


class Prediction(NamedTuple):
    """What compute_color makes of one predicted camera ray: the ray's direction, the
    numbers random() draws for it (none for a ray that misses), its camera hit (to make
    its colour again from other draws) and `made`, what the colour is made from."""

    dx: float
    dy: float
    dz: float
    draws: tuple
    hit: object
    made: object


class Lookahead:
    """Hands out the predictions of a task's next camera rays (see the module's docstring).

    predict(rays, draw) gives a Prediction for each Ray of `rays`, in order, or stops at a
    ray it cannot predict (whose colour the plain code makes): a shorter list; draw is
    random() of a copy of `generator`, the live random.Random whose numbers compute_color
    draws."""

    def __init__(self, scene, generator, predict):
        self.scene, self.generator, self.predict = scene, generator, predict
        self.camera = None  # the task camera whose rays are predicted
        self.directions = ()
        self.next_ray = 0  # the number of the ray the loop traces next
        self.predictions, self.first = [], 0  # predictions of rays first, first + 1, ...
        self.copy = random.Random()  # the live generator's copy the predictions draw from

    def prediction(self, ray) -> Optional[Prediction]:
        """The prediction of ray if it is the next ray of the task's loop, else None (and
        none for the rest of the task)."""
        camera = self.scene.camera
        if camera is not self.camera:  # a new task: its rays from the first
            self.camera, self.next_ray, self.predictions = camera, 0, []
            self.directions = getattr(camera, "directions", ())
        k = self.next_ray
        if k < 0:
            return None
        index = k - self.first
        if not 0 <= index < len(self.predictions):
            self.first, index = k, 0
            self.predictions = self.predicted(k)
            if not self.predictions:  # compute_color makes this ray's colour on its own
                if self.next_ray >= 0:
                    self.next_ray = k + 1
                return None
        guess = self.predictions[index]
        o, d = ray.o, ray.d
        if (d.x == guess.dx and d.y == guess.dy and d.z == guess.dz and o.x == 0.0
                and o.y == 0.0 and o.z == 0.0 and ray.t_min == 0.0 and ray.t_max == INFINITY
                # and no zero of the origin or of t_min is a negative zero
                and copysign(1.0, o.x) + copysign(1.0, o.y) + copysign(1.0, o.z)
                + copysign(1.0, ray.t_min) == 4.0):
            self.next_ray += 1
            return guess
        self.stop()
        return None

    def predicted(self, k) -> list:
        """The predictions of rays k, k + 1, ... of the task, up to WINDOW of them."""
        directions = self.directions[k:k + WINDOW]
        if not directions:
            return []
        rays = [Ray(Vector3D(0.0, 0.0, 0.0), d, INFINITY, 0.0) for d in directions]
        self.copy.setstate(self.generator.getstate())
        try:
            return self.predict(rays, self.copy.random)
        except (ArithmeticError, ValueError):  # a colour that fails: made on its own, it
            self.stop()                         # fails at its own pixel
            return []

    def stop(self):
        """No prediction for the rest of the task (the loop is not the one predicted)."""
        self.next_ray, self.predictions = -1, []
