from PyRT_Common import *
from PyRT_Core import *
from PyRT_Integrators import *
import time


def sphere_scene(envMap=None):
    # Create a scene object
    scene_ = Scene()
    scene_.set_ambient(RGBColor(0.5, 0.5, 0.5))

    # Create the materials (BRDFs)
    white_diffuse = Lambertian(RGBColor(0.8, 0.8, 0.8))
    green_diffuse = Lambertian(RGBColor(0.2, 0.8, 0.2))

    # Create the primitives: a sphere above a floor
    object_1 = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    object_1.set_BRDF(white_diffuse)
    scene_.add_object(object_1)
    floor = Parallelogram(Vector3D(-4.0, -2.0, -1.0), Vector3D(8.0, 0.0, 0.0), Vector3D(0.0, 0.0, -8.0))
    floor.set_BRDF(green_diffuse)
    scene_.add_object(floor)

    # A point light source
    scene_.add_point_light_sources(PointLight(Vector3D(0.0, 5.0, 0.0), RGBColor(80.0, 80.0, 80.0)))

    # Environment map (for later practices)
    if envMap is not None:
        scene_.set_environment_map(envMap)

    # Create a camera and add it to the scene
    scene_.set_camera(Camera(500, 500, 60))
    return scene_


if __name__ == '__main__':
    DIRECTORY = '.\\out\\'
    FILENAME = 'rendered_image'

    # Create the integrator and the scene, and attach the scene to the integrator
    integrator = LazyIntegrator(DIRECTORY + FILENAME)
    scene = sphere_scene(envMap='env_maps/arch_nozero.hdr')
    integrator.add_scene(scene)

    # Render the scene
    start_time = time.time()
    integrator.render()
    end_time = time.time()
    print('Rendering time: ' + str(end_time - start_time) + ' seconds')

    # Show the result
    img = cv2.imread(integrator.get_filename() + '.png')
    cv2.imshow('Rendered Image', img)
    cv2.waitKey(0)
