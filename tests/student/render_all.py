# The student's AppRenderer: renders the course's figures with the student's integrators
# and Scene methods, into the folder given as the first argument, at the size given second.
import sys

import PyRT_Core
import student_scene
from AppRenderer import cornell_box_scene, sphere_test_scene
from PyRT_Integrators import *

PyRT_Core.Scene.any_hit = student_scene.any_hit
PyRT_Core.Scene.closest_hit = student_scene.closest_hit

folder, size = sys.argv[1], int(sys.argv[2])
figures = [
    (PhongIntegrator(folder + '/cornell'), cornell_box_scene(0.75, 2, width=size, height=size)),
    (LazyIntegrator(folder + '/sphere'), sphere_test_scene(width=size, height=size)),
    (IntersectionIntegrator(folder + '/sphere'), sphere_test_scene(width=size, height=size)),
    (DepthIntegrator(folder + '/sphere', 5), sphere_test_scene(width=size, height=size)),
    (NormalIntegrator(folder + '/sphere'), sphere_test_scene(width=size, height=size)),
    (PhongIntegrator(folder + '/sphere'), sphere_test_scene(width=size, height=size)),
]
for integrator, scene in figures:
    integrator.add_scene(scene)
    integrator.render()
