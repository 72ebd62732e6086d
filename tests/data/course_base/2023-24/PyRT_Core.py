# ------------------------------------------------------------------------------------------
# PyRT: Python Ray Tracer - core classes
# ------------------------------------------------------------------------------------------
from PyRT_Common import *
from math import tan


# -------------------------------------------------SCENE CLASS
class Scene:
    def __init__(self):
        self.camera = None
        self.env_map = None
        self.rendered_image = None
        self.object_list = []
        self.pointLights = []
        self.i_a = RGBColor(0.0, 0.0, 0.0)  # ambient intensity

    def set_ambient(self, i_a):
        self.i_a = i_a

    def set_camera(self, camera):
        self.camera = camera
        self.rendered_image = np.zeros((camera.height, camera.width, 3))

    def set_environment_map(self, env_map_path):
        self.env_map = EnvironmentMap(env_map_path)

    def add_object(self, new_object):
        self.object_list.append(new_object)

    def add_point_light_sources(self, point_light):
        self.pointLights.append(point_light)

    # returns True if the ray hits any object of the scene, False otherwise
    def any_hit(self, ray):
        # ASSIGNMENT 1.2: PUT YOUR CODE HERE
        return False

    # returns the intersection data of the closest object hit by the ray
    def closest_hit(self, ray):
        hit_data = HitData()
        for i in range(len(self.object_list)):
            current = self.object_list[i].intersect(ray)
            if current.has_hit:
                if current.hit_distance < hit_data.hit_distance:
                    hit_data = current
                    hit_data.primitive_index = i
        return hit_data

    def set_pixel(self, pixel_val, x, y):
        self.rendered_image[y, x, 0] = pixel_val.r
        self.rendered_image[y, x, 1] = pixel_val.g
        self.rendered_image[y, x, 2] = pixel_val.b

    def save_image(self, full_filename):
        image = np.float32(self.rendered_image)
        tonemap = cv2.createTonemap(gamma=2.5)
        ldr = tonemap.process(image)
        plt.imsave(full_filename + '.png', np.clip(ldr, 0, 1))
        np.save(full_filename, self.rendered_image)
        cv2.imwrite(full_filename + '.hdr', cv2.cvtColor(image, cv2.COLOR_RGB2BGR))
        print("Image Saved")


# -------------------------------------------------PRIMITIVES
class Primitive(ABC):
    def __init__(self, emission=BLACK):
        self.emission = emission
        self.BRDF = None

    @abstractmethod
    def intersect(self, ray):
        pass

    def set_BRDF(self, BRDF):
        self.BRDF = BRDF

    def get_BRDF(self):
        return self.BRDF


class Sphere(Primitive):
    def __init__(self, sphere_origin, sphere_radius, emission=BLACK):
        super().__init__(emission)
        self.origin = sphere_origin
        self.radius = sphere_radius
        self.radius_squared = sphere_radius * sphere_radius

    def intersect(self, ray):
        d = Normalize(ray.d)
        oc = ray.o - self.origin
        A = Dot(d, d)
        B = 2.0 * Dot(d, oc)
        C = Dot(oc, oc) - self.radius_squared
        discriminant = B * B - 4.0 * A * C
        if discriminant < 0.0:
            return HitData()
        root = sqrt(discriminant)
        t = (-B - root) / (2.0 * A)
        if t < ray.t_min or t > ray.t_max:
            t = (-B + root) / (2.0 * A)
            if t < ray.t_min or t > ray.t_max:
                return HitData()
        hit_point = ray.get_hitpoint(t)
        normal = Normalize(hit_point - self.origin)
        return HitData(has_hit=True, hit_point=hit_point, normal=normal, hit_distance=t)


class InfinitePlane(Primitive):
    def __init__(self, plane_origin, plane_normal, emission=BLACK):
        super().__init__(emission)
        self.origin = plane_origin
        self.normal = Normalize(plane_normal)

    def intersect(self, ray):
        d = Normalize(ray.d)
        denominator = Dot(d, self.normal)
        if denominator == 0.0:
            return HitData()
        t = Dot(self.normal, self.origin - ray.o) / denominator
        if t < ray.t_min or t > ray.t_max:
            return HitData()
        return HitData(has_hit=True, hit_point=ray.get_hitpoint(t), normal=self.normal, hit_distance=t)


class Parallelogram(Primitive):
    def __init__(self, point, s1, s2, emission=BLACK):
        super().__init__(emission)
        self.point = point
        self.s1 = s1
        self.s2 = s2
        self.normal = Normalize(Cross(s1, s2))

    def intersect(self, ray):
        d = Normalize(ray.d)
        denominator = Dot(d, self.normal)
        if denominator == 0.0:
            return HitData()
        t = Dot(self.normal, self.point - ray.o) / denominator
        if t < ray.t_min or t > ray.t_max:
            return HitData()
        hit_point = ray.get_hitpoint(t)
        # projection of the hit point on both sides of the parallelogram
        p_ph = hit_point - self.point
        q1 = Dot(Normalize(self.s1), Normalize(p_ph)) * Length(p_ph)
        q2 = Dot(Normalize(self.s2), Normalize(p_ph)) * Length(p_ph)
        if q1 < 0.0 or q2 < 0.0 or q1 > Length(self.s1) or q2 > Length(self.s2):
            return HitData()
        normal = self.normal
        if Dot(normal, d) > 0.0:
            normal = normal * -1.0
        return HitData(has_hit=True, hit_point=hit_point, normal=normal, hit_distance=t)


# -------------------------------------------------BRDFs
class BRDF(ABC):
    @abstractmethod
    def get_value(self, incoming, outgoing, normal):
        pass


class Lambertian(BRDF):
    def __init__(self, diffuse_colour):
        self.kd = diffuse_colour / pi

    def get_value(self, wi, wo, normal):
        cos_theta = Dot(normal, wi)
        if cos_theta > 0.0:
            return self.kd * cos_theta
        return BLACK

    def get_kd(self):
        return self.kd


# -------------------------------------------------LIGHTS
class PointLight:
    def __init__(self, pos_, intensity_):
        self.pos = pos_
        self.intensity = intensity_


# -------------------------------------------------CAMERA
class Camera:
    def __init__(self, width_, height_, vertical_fov_):
        self.width = width_
        self.height = height_
        self.vertical_fov = vertical_fov_ * pi / 180.0  # degrees to radians
        self.aspect_ratio = width_ / height_

    # direction of the ray from the camera through the centre of pixel (x, y)
    def get_direction(self, x, y):
        x_s = 2.0 * (x + 0.5) / self.width - 1.0
        y_s = 1.0 - 2.0 * (y + 0.5) / self.height
        scale = tan(self.vertical_fov / 2.0)
        direction = Vector3D(x_s * scale * self.aspect_ratio, y_s * scale, -1.0)
        return Normalize(direction)
