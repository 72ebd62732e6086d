# A student's script in the style of the 2025-26 handout's AppRenderer.py: the handout's
# sphere_scene with its environment map, its output path (a Windows one) and the student's
# own rendering loop of Assignment 1.2, over the columns x and then the rows y, with the
# progress printed after each column. tests/test_app_scenes.py runs it unchanged, without a
# screen, from a folder holding env_maps/arch_nozero.hdr.
import time

from PyRT_Common import *
from PyRT_Integrators import *
from AppRenderer import sphere_scene

DIRECTORY = '.\\out\\'
FILENAME = 'rendered_image'


class MyIntersectionIntegrator(IntersectionIntegrator):

    def render(self):
        cam = self.scene.camera
        for x in range(cam.width):
            for y in range(cam.height):
                ray = Ray(direction=cam.get_direction(x, y))
                pixel_color = self.compute_color(ray)
                self.scene.set_pixel(pixel_color, x, y)
            print('\r Progress: ' + str(round(100 * (x + 1) / cam.width)) + '%', end='')
        print()
        self.scene.save_image(self.get_filename())


integrator = MyIntersectionIntegrator(DIRECTORY + FILENAME)
scene = sphere_scene(envMap='env_maps/arch_nozero.hdr')
integrator.add_scene(scene)
start_time = time.time()
integrator.render()
end_time = time.time() - start_time
print('--- Rendering time: %s seconds ---' % end_time)

# The handout shows the PNG in a window with cv2.imshow, which needs a screen; the script
# reads it back by the same name, as the handout does before showing it.
img = cv2.imread(integrator.get_filename() + '.png')
print('Read back ' + integrator.get_filename() + '.png: ' + str(img.shape))
