"""PyRT's own machinery, beneath the course's four modules: what makes the course's loops
fast, parallel and explained, and what saves and compares their images.

    images                  saving, tonemapping and showing images (OpenCV's loader)
    compare                 the comparison with the course's references (students use it:
                            `from pyrt.compare import compare_with_reference`)
    explain, explain_picture  the story of one pixel, and its drawing
    scalar_intersections    the course's intersections on plain floats
    acceleration            the scene's queries and Phong, fast, for the course's loops
    gaussian_pools          the Bayesian integrators' pools of GPs, checked and made
    sampling                a block of rows of an image, and adaptive sampling
    workers                 the worker processes that render blocks of rows
    rendering               Integrator.render()'s loop, on top of all the above

Imports run one way: images < PyRT_Common < PyRT_Core < scalar_intersections, acceleration,
sampling, workers, explain < rendering < PyRT_Integrators < AppRenderer. Nothing is
imported here, so that loading one module loads only what it needs.
"""
