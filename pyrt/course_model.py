"""The course's Phong model taken apart: PhongIntegrator.compute_color itself, run on a
stand-in for its scene (PhongParts) that changes a part of the model, so that the
formula stays written once, in PyRT_Integrators.py. The stories of pyrt/explain.py take
from it what one visible light adds (phong_term); the course kit's mistaken variants of
Phong (course_kit/references.py) leave out the ambient term or the shadows, or let the
light fall off otherwise. It computes Assignment 1.4's answer, so it is the framework's
only, never in the students' handout nor in the grader's working copies
(course_kit/grader.py)."""
from typing import Optional, Tuple

from PyRT_Common import BLACK, HitData, Length, Ray
from pyrt.acceleration.fingerprints import fused_integrator

Vec = Tuple[float, float, float]


class PhongParts:
    """A scene as PhongIntegrator.compute_color sees it, with parts of the course's Phong
    model changed; everything else is the scene's own.

    ambient: False gives i_a = BLACK, the model without its ambient term kd (x) i_a.
    lights: the point lights the sum goes over (None: the scene's).
    blocked(scene, hit, wi, r): whether the light is hidden, told from the unit direction
        wi to the light and its distance r, as a student's shadow ray tells it, in place
        of the course's shadow ray (never_blocked: the model without shadows).
    falloff: p of the light's 1/r^p; the course's is 2.
    hit: the closest hit to give the camera ray (None: the scene's closest_hit)."""

    def __init__(self, scene, blocked, ambient=True, lights=None, falloff=2, hit=None):
        self.scene, self.ambient, self.blocked, self.falloff = scene, ambient, blocked, falloff
        self.lights = scene.pointLights if lights is None else lights
        self.given_hit = hit
        self.hit = self.light = None

    def __getattr__(self, name):
        return getattr(self.scene, name)

    @property
    def i_a(self):
        return self.scene.i_a if self.ambient else BLACK

    def closest_hit(self, ray):
        self.hit = self.scene.closest_hit(ray) if self.given_hit is None else self.given_hit
        return self.hit

    @property
    def pointLights(self):
        for light in self.lights:
            self.light = light
            yield light if self.falloff == 2 else _FallingOff(light, self.hit, self.falloff)

    def any_hit(self, ray):  # the course's shadow ray, for the light of the sum
        to_light = self.light.pos - self.hit.hit_point
        r = Length(to_light)
        return self.blocked(self.scene, self.hit, to_light / r, r)


class _FallingOff:
    """A point light whose term intensity (x) f, which the course divides by r^2, is
    divided by r^falloff instead."""

    def __init__(self, light, hit, falloff):
        self.pos = light.pos
        self.intensity = _Intensity(light.intensity, Length(light.pos - hit.hit_point) ** falloff)


class _Intensity:
    def __init__(self, intensity, divisor):
        self.intensity, self.divisor = intensity, divisor

    def multiply(self, f):
        return _Term(self.intensity.multiply(f), self.divisor)


class _Term:
    def __init__(self, term, divisor):
        self.term, self.divisor = term, divisor

    def __truediv__(self, course_divisor):  # the course's r * r, replaced
        return self.term / self.divisor


def never_blocked(scene, hit, wi, r):
    """A light is never hidden: the model without shadows."""
    return False


def phong_term(scene, hit, light, camera_ray, Vector3D) -> Optional[Vec]:
    """intensity (x) BRDF.get_value(wi, wo, n) / r^2 at the object hit (a HitRecord of
    pyrt/explain.py), as the course's Phong model adds it for a visible light: the course's
    PhongIntegrator.compute_color with that light alone, no ambient term and no shadow.
    None when the scene's classes cannot tell."""
    phong = fused_integrator("phong")  # PyRT_Integrators registers its PhongIntegrator
    if phong is None:
        return None
    try:
        course_hit = HitData(True, Vector3D(*hit.point), Vector3D(*hit.normal),
                             primitive_index=hit.index)
        integrator = phong("unused")
        integrator.scene = PhongParts(scene, never_blocked, ambient=False, lights=[light],
                                      hit=course_hit)
        direction = Vector3D(*camera_ray.direction)
        color = phong.compute_color(integrator, Ray(Vector3D(0.0, 0.0, 0.0), direction))
        return (color.r, color.g, color.b)
    except Exception:  # a student's classes may lack any of these; the story does without
        return None
