"""Scene queries made fast, with the answers of the plain ones: PyRT's acceleration.

``Scene.closest_hit`` and ``Scene.any_hit`` (PyRT_Core.py) are the course's loops: every
object's ``intersect(ray)``, the nearest hit kept. They are what students read and write,
and they run whenever code of a student's own could be involved. During a render,
``accelerated(integrator)`` stands in for the two methods of a scene of PyRT's own classes
with those of ``AcceleratedQueries``, for ``PhongIntegrator.compute_color`` with that of
``AcceleratedPhong``, for ``CMCIntegrator.compute_color`` with that of ``AcceleratedCMC``
and for the Bayesian integrators' with that of ``AcceleratedBMC`` (the same draws of
random(), in the same order); all give the plain code's answers, bit for bit, faster:

- scalar fast paths: the intersection tests of Sphere, InfinitePlane and Parallelogram
  (pyrt/scalar_intersections.py) and the Phong sum, written out on plain floats in the
  operations and order of the plain code, with a HitData made only for the nearest hit;
  for rays from the camera, a wall along the axes is tested without the products by
  zero, which add nothing;
- arrays of rays: the Bayesian integrators' sample rays, of all the pixels of a window of
  a task's camera rays at once, tested on numpy arrays in the operations and order of the
  scalar tests (pyrt/array_intersections.py), the colours handed out only for the very
  ray and draws of random() they were made with (lookahead.py);
- culling: a ray from the camera, or a shadow ray ending at a point light, tests only the
  objects that a ray from that point in its direction can reach (each object's cone, seen
  from the camera or the light, with a margin far above rounding); and a flat object
  cannot block a shadow ray that starts clearly on the light's side of its plane.

It never runs in place of a student's code. A subclass of Scene with its own closest_hit
or any_hit, a method assigned to the scene, and a change to one of the functions the fast
paths mirror (the tables of fingerprints.py: replaced, or edited in place) leave the plain code to run. An object of a class of its own (a subclass of
Sphere, say) is asked through its own ``intersect`` at every query, in the order of
object_list. With a debugger attached the plain code runs, so that breakpoints in it work.

The setup takes time proportional to objects x (lights + 1), and renders too small to
repay it keep the plain code. tests/test_acceleration.py shows the answers equal to the
plain code's on random scenes and rays.

The modules, each on one concern, in the order they import each other:

    fingerprints   which functions the fast paths repeat, and whether they are unchanged;
                   the integrators whose compute_color a fused version repeats register
                   themselves here (register_fused)
    culling        which objects a ray from a point can reach: cones and planes
    queries        AcceleratedQueries: closest_hit and any_hit on plain floats
    phong          AcceleratedPhong: PhongIntegrator.compute_color on plain floats
    monte_carlo    AcceleratedCMC: CMCIntegrator.compute_color on plain floats
    lookahead      the colours of a task's next camera rays, made together ahead of the
                   loop and handed out only for the ray and draws they were made with
    bayesian       AcceleratedBMC, AcceleratedBMCIS: the Bayesian integrators' compute_color
    accelerated    the with-block that stands them in for a render (accelerated, plain)

`python -m pyrt.acceleration` prints the fingerprints of the functions as they are now
(docs/maintaining.md). Nothing is imported here, so that importing one module loads only
what it needs.
"""
