"""PyRT's own machinery, beneath the course's modules: what makes the course's loops
fast, parallel and explained, and what saves and compares their images.

    images                  saving, tonemapping and showing images (OpenCV's loader)
    environment_maps        PyRT's own environment maps, made by code
    compare                 the comparison with the course's references (students use it:
                            `from pyrt.compare import compare_with_reference`)
    scalar_intersections    the course's intersections on plain floats
    acceleration            the scene's queries, Phong, classic and Bayesian Monte Carlo, fast
    gaussian_pools          the Bayesian integrators' pools of GPs, checked and made
    gp_*                    GaussianProcess.py's machinery: inputs, kernels, integrals, solves
    course_model            the course's Phong model taken apart (what one light adds)
    explain, explain_picture  the story of one pixel, and its drawing
    rows                    how a task of a render is made: one row, its random stream,
                            the integrator's loop run on its rays
    workers                 who renders: this process and worker processes, block by block
    sampling                what to sample: the passes of a render, adaptive sampling
    rendering               render_loop, the decorator of Integrator.render()'s loop

A render goes one way down: rendering -> sampling -> workers -> rows -> the loop's body,
compute_color and the scene's queries. Imports run one way: images < PyRT_Common <
PyRT_Core < scalar_intersections < acceleration < course_model < explain, and acceleration
< rows < workers < sampling < rendering < PyRT_Integrators < AppRenderer. Nothing is
imported here, so that loading one module loads only what it needs.
"""
