# A Practice 1 solution written against the course's base code, as a student hands it in:
# the rendering loop of Assignment 1.1 and the five integrators, in the student's own
# PyRT_Integrators.py, stored here under another name so that it shadows nothing: the
# test that runs it (tests/test_integrators.py) copies it in as PyRT_Integrators.py.
from PyRT_Common import *
from abc import ABC, abstractmethod


class Integrator(ABC):

    def __init__(self, filename_, experiment_name=''):
        self.filename = filename_ + experiment_name
        self.scene = None

    def get_filename(self):
        return self.filename

    def add_scene(self, scene):
        self.scene = scene

    @abstractmethod
    def compute_color(self, ray):
        pass

    def render(self):
        cam = self.scene.camera
        for x in range(cam.width):
            for y in range(cam.height):
                direction = cam.get_direction(x, y)
                ray = Ray(Vector3D(0, 0, 0), direction)
                pixel_color = self.compute_color(ray)
                self.scene.set_pixel(pixel_color, x, y)
        self.scene.save_image(self.get_filename())


class LazyIntegrator(Integrator):
    def __init__(self, filename_):
        super().__init__(filename_ + '_Lazy')

    def compute_color(self, ray):
        return BLACK

    def render(self):
        cam = self.scene.camera
        for x in range(cam.width):
            for y in range(cam.height):
                pixel = RGBColor(x / cam.width, y / cam.height, 0)
                self.scene.set_pixel(pixel, x, y)
        self.scene.save_image(self.get_filename())


class IntersectionIntegrator(Integrator):

    def __init__(self, filename_):
        super().__init__(filename_ + '_Intersection')

    def compute_color(self, ray):
        if self.scene.any_hit(ray):
            return RED
        return BLACK


class DepthIntegrator(Integrator):

    def __init__(self, filename_, max_depth_=10):
        super().__init__(filename_ + '_Depth')
        self.max_depth = max_depth_

    def compute_color(self, ray):
        hit_data = self.scene.closest_hit(ray)
        if hit_data.has_hit:
            c = max(1 - hit_data.hit_distance / self.max_depth, 0)
            return RGBColor(c, c, c)
        return BLACK


class NormalIntegrator(Integrator):

    def __init__(self, filename_):
        super().__init__(filename_ + '_Normal')

    def compute_color(self, ray):
        hit_data = self.scene.closest_hit(ray)
        if hit_data.has_hit == False:
            return BLACK
        if type(hit_data.normal) == Vector3D:
            n = hit_data.normal
        else:
            n = Vector3D(hit_data.normal[0], hit_data.normal[1], hit_data.normal[2])
        c = (n + Vector3D(1, 1, 1)) / 2
        return RGBColor(c.x, c.y, c.z)


class PhongIntegrator(Integrator):

    def __init__(self, filename_):
        super().__init__(filename_ + '_Phong')

    def compute_color(self, ray):
        hit_data = self.scene.closest_hit(ray)
        if not hit_data.has_hit:
            return BLACK
        primitive = self.scene.object_list[hit_data.primitive_index]
        brdf = primitive.get_BRDF()
        color = brdf.kd.multiply(self.scene.i_a)
        for light in self.scene.pointLights:
            light_vector = light.pos - hit_data.hit_point
            distance = Length(light_vector)
            wi = Normalize(light_vector)
            shadow_ray = Ray(hit_data.hit_point, wi, distance)
            if not self.scene.any_hit(shadow_ray):
                diffuse = light.intensity.multiply(brdf.get_value(wi, 0, hit_data.normal))
                color += diffuse / (distance ** 2)
        return color
