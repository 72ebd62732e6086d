from PyRT_Common import *
from PyRT_Core import *
from PyRT_Integrators import *
import time


# -------------------------------------------------Main
# Create Integrator
DIRECTORY = 'out/'
FILENAME = 'rendered_image'


def sphere_test_scene(areaLS=False, use_env_map=False):
    # Create a scene object
    scene_ = Scene()
    scene_.set_ambient(RGBColor(0.5, 0.5, 0.5))

    # Create the materials (BRDFs)
    white_diffuse = Lambertian(RGBColor(0.8, 0.8, 0.8))
    green_diffuse = Lambertian(RGBColor(0.2, 0.8, 0.2))

    # Create a sphere and a floor
    object_1 = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    object_1.set_BRDF(white_diffuse)
    scene_.add_object(object_1)
    floor = Parallelogram(Vector3D(-4.0, -2.0, -1.0), Vector3D(8.0, 0.0, 0.0), Vector3D(0.0, 0.0, -8.0))
    floor.set_BRDF(green_diffuse)
    scene_.add_object(floor)

    if areaLS:
        # an emissive parallelogram (for later practices)
        area_light = Parallelogram(Vector3D(-4.0, 6.0, -1.0), Vector3D(8.0, 0.0, 0.0), Vector3D(0.0, 0.0, -8.0),
                                   RGBColor(3.5, 3.5, 3.5))
        area_light.set_BRDF(Lambertian(BLACK))
        scene_.add_object(area_light)
    else:
        scene_.add_point_light_sources(PointLight(Vector3D(0.0, 5.0, 0.0), RGBColor(80.0, 80.0, 80.0)))

    if use_env_map:
        scene_.set_environment_map('env_maps/arch_nozero.hdr')

    # Create a camera and add it to the scene
    scene_.set_camera(Camera(500, 500, 60))
    return scene_


def cornell_box_scene(dist, side, areaLS=False):
    scene_ = Scene()
    scene_.set_ambient(RGBColor(1.0, 1.0, 0.3))

    white_diffuse = Lambertian(RGBColor(0.8, 0.8, 0.8))
    red_diffuse = Lambertian(RGBColor(0.7, 0.2, 0.2))
    green_diffuse = Lambertian(RGBColor(0.2, 0.7, 0.2))
    blue_diffuse = Lambertian(RGBColor(0.2, 0.2, 0.7))

    z_far = -(dist + side)
    ll = Vector3D(-side / 2, -side / 2, z_far)
    ur = Vector3D(side / 2, side / 2, z_far)

    sphere = Sphere(Vector3D(0.0, 0.0, -(dist + side / 2)), 0.25)
    sphere.set_BRDF(blue_diffuse)
    scene_.add_object(sphere)
    back_wall = Parallelogram(ll, Vector3D(side, 0.0, 0.0), Vector3D(0.0, side, 0.0))
    back_wall.set_BRDF(white_diffuse)
    scene_.add_object(back_wall)
    floor = Parallelogram(ll, Vector3D(side, 0.0, 0.0), Vector3D(0.0, 0.0, side))
    floor.set_BRDF(white_diffuse)
    scene_.add_object(floor)
    left_wall = Parallelogram(ll, Vector3D(0.0, side, 0.0), Vector3D(0.0, 0.0, side))
    left_wall.set_BRDF(red_diffuse)
    scene_.add_object(left_wall)
    ceiling = Parallelogram(ur, Vector3D(-side, 0.0, 0.0), Vector3D(0.0, 0.0, side))
    ceiling.set_BRDF(white_diffuse)
    scene_.add_object(ceiling)
    right_wall = Parallelogram(ur, Vector3D(0.0, -side, 0.0), Vector3D(0.0, 0.0, side))
    right_wall.set_BRDF(green_diffuse)
    scene_.add_object(right_wall)

    if areaLS:
        area_light = Parallelogram(Vector3D(-side / 4, side / 2 - 0.0001, -(dist + side / 4)),
                                   Vector3D(side / 2, 0.0, 0.0), Vector3D(0.0, 0.0, -side / 2),
                                   RGBColor(1.0, 1.0, 1.0))
        area_light.set_BRDF(Lambertian(BLACK))
        scene_.add_object(area_light)
    else:
        light_y = side / 2 - 0.5
        light_z = -(dist + side / 2)
        scene_.add_point_light_sources(PointLight(Vector3D(0.0, light_y, light_z), RGBColor(0.5, 0.5, 0.5)))
        scene_.add_point_light_sources(PointLight(Vector3D(-side / 4, light_y, light_z), RGBColor(0.5, 0.5, 0.5)))
        scene_.add_point_light_sources(PointLight(Vector3D(side / 4, light_y, light_z), RGBColor(0.5, 0.5, 0.5)))

    scene_.set_camera(Camera(500, 500, 70))
    return scene_


# Choose the integrator and the scene
integrator = LazyIntegrator(DIRECTORY + FILENAME)
scene = sphere_test_scene()
# scene = cornell_box_scene(0.75, 2.0)
integrator.add_scene(scene)

# Render and time it
start_time = time.time()
integrator.render()
end_time = time.time()
print('Rendering time: ' + str(end_time - start_time) + ' seconds')

# Show the result
img = cv2.imread(integrator.get_filename() + '.png')
cv2.imshow('Rendered Image', img)
cv2.waitKey(0)
