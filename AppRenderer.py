"""Builds a scene, renders it with an integrator, saves the image to out/ and shows it.

Run it with no arguments (the play button of VSCode) to render Figure 1 of the course, Phong
on the Cornell box; `python AppRenderer.py --help` lists the options. With --all-figures it
renders the images of Figures 1-5 and compares them with the course's (see pyrt/compare.py).
"""
import argparse
import sys
import time
from pathlib import Path

from PyRT_Common import *
from PyRT_Core import *
from PyRT_Integrators import *
from PyRT_Common import COURSE_ENV_MAP
from pyrt.compare import REFERENCE_SIZE, compare_figures, write_sheet
from pyrt.explain import explain_pixel
from pyrt.explain_picture import save_picture
from pyrt.images import opencv_problem
# FRAMEWORK ONLY BEGIN
from pyrt.gaussian_pools import make_gp_pool
from pyrt.sampling import ADAPTIVE_TOLERANCE
# FRAMEWORK ONLY END

# out/ next to this script, wherever it is run from
DIRECTORY = str(Path(__file__).resolve().parent / "out") + "/"
FILENAME = "rendered_image"
SHEET_FILENAME = "figures_vs_reference.png"
# The course's environment map, 'env_maps/arch_nozero.hdr', from the folder the script runs
# in as the course's code reads it, or beside this file; where it is in neither, PyRT's own
# sky stands in for it, and one line says so (PyRT_Common.EnvironmentMap)
ENV_MAP_PATH = COURSE_ENV_MAP


# ------------------------------------------------------------------------------------------
# Scenes
# ------------------------------------------------------------------------------------------
def sphere_test_scene(areaLS=False, use_env_map=False, width=500, height=500):
    """A grey sphere above a green floor, lit by one point light (Figures 2 to 5), under
    the 2023-24 handout's name; sphere_scene is the same scene under the 2025-26 one."""
    scene = Scene()
    scene.set_ambient(RGBColor(0.5, 0.5, 0.5))

    sphere = Sphere(Vector3D(0.0, 0.0, -5.0), 2.0)
    sphere.set_BRDF(Lambertian(RGBColor(0.8, 0.8, 0.8)))
    scene.add_object(sphere)

    floor_sides = (Vector3D(8.0, 0.0, 0.0), Vector3D(0.0, 0.0, -8.0))
    floor = Parallelogram(Vector3D(-4.0, -2.0, -1.0), *floor_sides)
    floor.set_BRDF(Lambertian(RGBColor(0.2, 0.8, 0.2)))
    scene.add_object(floor)

    if areaLS:
        light = Parallelogram(Vector3D(-4.0, 6.0, -1.0), *floor_sides,
                              emission=RGBColor(3.5, 3.5, 3.5))
        light.set_BRDF(Lambertian(BLACK))
        scene.add_object(light)
    else:
        scene.add_point_light_sources(PointLight(Vector3D(0.0, 5.0, 0.0),
                                                 RGBColor(80.0, 80.0, 80.0)))
    if use_env_map:
        scene.set_environment_map(ENV_MAP_PATH)

    scene.set_camera(Camera(width, height, 60))
    return scene


def sphere_scene(envMap=None, *, width=500, height=500):
    """The sphere scene of Figures 2 to 5 under the name the 2025-26 handout gives it: the
    scene of sphere_test_scene, lit by its point light. envMap, when given, is the path of
    a latitude-longitude .hdr image set as the scene's environment map; a relative path
    starts from the folder the script runs in, and a file that is not there is refused
    here, with the path in the message."""
    scene = sphere_test_scene(width=width, height=height)
    if envMap is not None:
        scene.set_environment_map(envMap)
    return scene


def cornell_box_scene(dist, side, areaLS=False, width=500, height=500):
    """The Cornell box: a blue sphere in a white box with a red left wall and a green right
    wall, lit by three point lights under the ceiling (Figure 1). The camera looks through
    the open front, `dist` in front of it; `side` is the box's edge length."""
    scene = Scene()
    scene.set_ambient(RGBColor(1.0, 1.0, 0.3))
    white = RGBColor(0.8, 0.8, 0.8)
    z_far = -(dist + side)
    ll = Vector3D(-side / 2, -side / 2, z_far)  # lower left corner of the back wall
    ur = Vector3D(side / 2, side / 2, z_far)    # upper right corner of the back wall

    objects = [
        (Sphere(Vector3D(0.0, 0.0, -(dist + side / 2)), 0.25), RGBColor(0.2, 0.2, 0.7)),
        (Parallelogram(ll, Vector3D(side, 0, 0), Vector3D(0, side, 0)), white),    # back
        (Parallelogram(ll, Vector3D(side, 0, 0), Vector3D(0, 0, side)), white),    # floor
        (Parallelogram(ll, Vector3D(0, side, 0), Vector3D(0, 0, side)),
         RGBColor(0.7, 0.2, 0.2)),                                                 # left
        (Parallelogram(ur, Vector3D(-side, 0, 0), Vector3D(0, 0, side)), white),   # ceiling
        (Parallelogram(ur, Vector3D(0, -side, 0), Vector3D(0, 0, side)),
         RGBColor(0.2, 0.7, 0.2)),                                                 # right
    ]
    for obj, colour in objects:
        obj.set_BRDF(Lambertian(colour))
        scene.add_object(obj)

    if areaLS:
        light = Parallelogram(Vector3D(-side / 4, side / 2 - 0.0001, -(dist + side / 4)),
                              Vector3D(side / 2, 0, 0), Vector3D(0, 0, -side / 2),
                              emission=RGBColor(1.0, 1.0, 1.0))
        light.set_BRDF(Lambertian(BLACK))
        scene.add_object(light)
    else:
        for x in (0.0, -side / 4, side / 4):
            scene.add_point_light_sources(PointLight(
                Vector3D(x, side / 2 - 0.5, -(dist + side / 2)), RGBColor(0.5, 0.5, 0.5)))

    scene.set_camera(Camera(width, height, 70))
    return scene


# ------------------------------------------------------------------------------------------
# The course's figures
# ------------------------------------------------------------------------------------------
INTEGRATORS = {
    "lazy": LazyIntegrator,
    "intersection": IntersectionIntegrator,
    "depth": DepthIntegrator,
    "normal": NormalIntegrator,
    "phong": PhongIntegrator,
}
# Practice 2's classic Monte Carlo, n samples per hit, and Practices 3 and 4's importance
# sampling and Bayesian Monte Carlo; a PyRT_Integrators.py of a student's own, written
# before them, may not have them
for _name, _class in (("cmc", "CMCIntegrator"), ("cmc-is", "CMCISIntegrator"),
                      ("bmc", "BayesianMonteCarloIntegrator"), ("bmc-is", "BMCISIntegrator")):
    if _class in globals():
        INTEGRATORS[_name] = globals()[_class]
del _name, _class
MONTE_CARLO = ("cmc", "cmc-is", "bmc", "bmc-is")  # the integrators that take --samples
# FRAMEWORK ONLY BEGIN
# The Bayesian ones' GPs (GaussianProcess.py), each with a sample set of its own: (the pdf
# of the samples, p_func), as Assignments 3.3 and Practice 4's Part II make them
BAYESIAN = {"bmc": (UniformPDF(), Constant(1)), "bmc-is": (CosinePDF(1), CosineLobe(1))}
DEFAULT_POOL = 16  # GPs in the pool of Assignment 3.3.2
# FRAMEWORK ONLY END
SCENES = {
    "cornell": lambda width, height: cornell_box_scene(0.75, 2, width=width, height=height),
    "sphere": lambda width, height: sphere_test_scene(width=width, height=height),
    # Practice 2's Figure 3: the sphere scene lit by the course's environment map
    "sphere-map": lambda width, height: sphere_scene(ENV_MAP_PATH, width=width,
                                                     height=height),
    # the Cornell box lit by the square area light under its ceiling
    "cornell-area": lambda width, height: cornell_box_scene(0.75, 2, areaLS=True,
                                                            width=width, height=height),
}
# The scene each integrator renders when --scene is not given: Figure 1 of Practice 1, and
# Figure 3 of Practice 2 (Figure 2 of Practice 3) for the Monte Carlo integrators
DEFAULT_SCENES = {name: "sphere-map" for name in MONTE_CARLO}
DEFAULT_SCENE = "cornell"
# Samples per hit of the Monte Carlo integrators when --samples is not given, as in the
# course's Figure 3 of Practice 2 and Figure 2 of Practice 3
DEFAULT_SAMPLES = 40
# (figure, integrator, scene, max_depth): Figure 4 has two images, depth and normal
FIGURES = [
    ("figure1", "phong", "cornell", None),
    ("figure2", "lazy", "sphere", None),
    ("figure3", "intersection", "sphere", None),
    ("figure4", "depth", "sphere", 5),
    ("figure4", "normal", "sphere", None),
    ("figure5", "phong", "sphere", None),
]


def make_integrator(name, filename, max_depth=None, experiment_name="", samples=None,
                    pool=None):
    """The integrator called `name` (a key of INTEGRATORS) writing to `filename`; samples
    is the Monte Carlo integrators' n (default DEFAULT_SAMPLES), pool the number of GPs of
    the Bayesian ones (default DEFAULT_POOL), whose making is timed and said once."""
    if name == "depth" and max_depth is not None:
        return DepthIntegrator(filename, max_depth, experiment_name)
    samples = samples or DEFAULT_SAMPLES
    # FRAMEWORK ONLY BEGIN
    if name in BAYESIAN:
        pdf, p_func = BAYESIAN[name]
        gps = make_gp_pool(pool or DEFAULT_POOL, samples, pdf, p_func)
        print(f"Made {len(gps.gps)} GPs of {samples} samples each (Q^-1, z and the weights, "
              f"p = {type(p_func).__name__}) in {gps.seconds:.2f} s")
        return INTEGRATORS[name](samples, gps.gps, filename, experiment_name)
    # FRAMEWORK ONLY END
    if name in MONTE_CARLO:
        return INTEGRATORS[name](samples, filename, experiment_name)
    return INTEGRATORS[name](filename, experiment_name=experiment_name)


def figure_integrator(entry, filename):
    """The integrator of an entry of FIGURES, writing to filename_<Integrator>_<figure>."""
    figure, name, _, max_depth = entry
    return make_integrator(name, filename, max_depth, "_" + figure)


def reference_name(entry):
    """The name of an entry of FIGURES among the course's reference images in
    references/: figure1_phong, figure2_lazy, ..., figure4_depth, figure4_normal."""
    figure, name, _, _ = entry
    return f"{figure}_{name}"


def compare_with_course(renders, folder, size, samples_per_pixel=1):
    """Compares the renders of the course's figures (a dict from their reference names to
    their PNGs) with the reference images, prints one line per figure and writes the
    comparison sheet figures_vs_reference.png into folder. Returns the sheet's path, or None
    when the images are not the size of the references (size is (width, height))."""
    if size != (REFERENCE_SIZE, REFERENCE_SIZE):
        print(f"The course's reference images are {REFERENCE_SIZE} x {REFERENCE_SIZE} "
              f"pixels and these {size[0]} x {size[1]}: not compared with them (render at "
              f"the default size to compare).")
        return None
    print("Compared with the course's figures (references/):")
    if samples_per_pixel != 1:
        print("(the figures have one ray per pixel: with more, the edges differ from them)")
    comparisons = compare_figures(renders)
    for comparison in comparisons:
        print("  " + comparison.summary)
    sheet = write_sheet(comparisons, Path(folder) / SHEET_FILENAME)
    print(f"Saved {sheet}: each figure beside the course's, and their difference")
    return sheet


def render(integrator, scene, **options):
    """Renders scene with integrator (which says where it saved the image), prints the
    rendering time and returns the PNG path.

    options: keyword arguments of Integrator.render() (workers, samples_per_pixel, adaptive,
    tolerance), none for its defaults: the course's handout has a render() that takes no
    arguments, and runs this script too."""
    integrator.add_scene(scene)
    start = time.perf_counter()
    integrator.render(**options)
    print(f"Rendering time: {time.perf_counter() - start:.2f} s")
    return integrator.get_filename() + ".png"


# Room a window needs on the screen besides its image, in pixels (width, height): borders,
# title bar and matplotlib's toolbar, and a task bar at the edge of the screen
WINDOW_FRAME = (40, 160)
# The narrowest window, in pixels: room for all of matplotlib's toolbar (zoom, save, ...).
# A narrower image is shown at its size at the window's left edge.
MIN_WINDOW_WIDTH = 320


def explain(integrator, x, y, folder):
    """Prints the story of pixel (x, y) of the integrator's image (see pyrt/explain.py) and
    saves the picture of its rays as folder/pixel_X_Y.png."""
    history = explain_pixel(integrator, x, y)
    print(history)
    picture = save_picture(history, integrator.scene, Path(folder) / f"pixel_{x}_{y}.png")
    print(f"Saved {picture}: the rays of pixel ({x}, {y}), from the side and from above")


def clicked_pixel(event, width, height):
    """The pixel (x, y) of an image of width x height pixels that a click on the window
    (a matplotlib button_press_event) falls on; None for a click outside the image, with
    another button than the left one, or while the zoom or pan tool of the toolbar is on.
    The image is drawn with the centre of pixel (x, y) at the point (x, y)."""
    toolbar = getattr(event.canvas, "toolbar", None)
    if event.button != 1 or event.xdata is None or getattr(toolbar, "mode", ""):
        return None
    x, y = int(floor(event.xdata + 0.5)), int(floor(event.ydata + 0.5))
    return (x, y) if 0 <= x < width and 0 <= y < height else None


def show(png, on_click=None):
    """Shows the saved image in a window titled with its file name, pixel for pixel: one
    screen pixel for each pixel of the image, nothing smoothed, so that stair steps and
    edges look as they are. An image too large for the screen is scaled down to fit, and a
    message says so. Without a screen it only says that the image is saved.

    on_click(x, y), when given, is called with the pixel that a left click falls on."""
    if not _has_display():
        print("No display: the image is saved, not shown.")
        return
    pixels = plt.imread(png)
    height, width = pixels.shape[:2]
    # Created one pixel small and enlarged below: matplotlib's toolbar keeps the window at
    # least as wide as the figure was when it was created, too wide for a scaled-down image.
    one_pixel = 1 / plt.rcParams["figure.dpi"]
    figure = plt.figure(Path(png).name, figsize=(one_pixel, one_pixel))
    screen = _screen_size(figure)
    scale = 1.0 if screen is None else window_scale((width, height), screen)
    if scale < 1.0:
        print(f"The image is {width} x {height} pixels, too large for this screen "
              f"({screen[0]} x {screen[1]}): the window shows it scaled to {scale:.0%}. "
              f"Zoom in with the window's magnifier, or open {png}, to see every pixel.")
    axes = figure.add_axes((0, 0, 1, 1))  # the whole window, no margins
    axes.set_axis_off()
    axes.set_anchor("W")  # whole pixels from the left edge, where centring could split them
    # Scaled down, "antialiased" averages the pixels that share a screen pixel
    axes.imshow(pixels, interpolation="none" if scale == 1.0 else "antialiased")
    _keep_size_in_pixels(figure, (max(MIN_WINDOW_WIDTH, round(width * scale)),
                                  max(1, round(height * scale))))
    if on_click is not None:
        def clicked(event):
            pixel = clicked_pixel(event, width, height)
            if pixel is not None:
                on_click(*pixel)

        figure.canvas.mpl_connect("button_press_event", clicked)
        print("Click a pixel of the window to print why it has its colour.")
    plt.show()


def window_scale(image_size, screen_size):
    """The factor by which a window shows an image of image_size = (width, height) pixels on
    a screen of screen_size pixels: 1, one screen pixel per image pixel, when the image fits
    on the screen beside the window's frame (WINDOW_FRAME), else the largest factor that
    fits."""
    room = [max(screen - frame, 1) for screen, frame in zip(screen_size, WINDOW_FRAME)]
    return min(1.0, room[0] / image_size[0], room[1] / image_size[1])


def _screen_size(figure):
    """(width, height) of the screen in pixels, as the figure's window reports it; None when
    it cannot tell. Only Tk's windows are asked: matplotlib uses Tk on Windows and Linux
    unless another GUI toolkit is installed."""
    window = getattr(figure.canvas.manager, "window", None)
    try:
        return window.winfo_screenwidth(), window.winfo_screenheight()
    except AttributeError:
        return None


def _keep_size_in_pixels(figure, size):
    """Makes figure `size` = (width, height) screen pixels large. matplotlib sizes figures
    in inches and enlarges them by the screen's scaling (125% in Windows' display settings,
    say), which it learns once the window is on the screen, and then resizes the figure: so
    the size is set now, and again when the figure is resized after a change of its dots
    per inch. Resizing the window by hand still works."""
    sized_for = None

    def fit(event=None):
        nonlocal sized_for
        if figure.dpi != sized_for:
            sized_for = figure.dpi
            figure.set_size_inches(size[0] / figure.dpi, size[1] / figure.dpi)

    fit()
    figure.canvas.mpl_connect("resize_event", fit)


def _has_display():
    import matplotlib
    backend = matplotlib.get_backend().lower()
    return backend not in ("agg", "pdf", "ps", "svg", "pgf", "cairo", "template")


def fraction_arg(text):
    """An argparse type: a number from 0 to 1."""
    try:
        value = float(text)
    except ValueError:
        value = None
    if value is None or not 0.0 <= value <= 1.0:
        raise argparse.ArgumentTypeError(f"must be a number from 0 to 1, got {text!r}")
    return value


def pixel_arg(text):
    """An argparse type: a pixel given as X,Y, two whole numbers from 0 (x to the right,
    y down)."""
    parts = text.split(",")
    if len(parts) != 2 or not all(part.strip().isdigit() for part in parts):
        raise argparse.ArgumentTypeError(f"must be a pixel X,Y such as 250,400 (two whole "
                                         f"numbers from 0), got {text!r}")
    return int(parts[0]), int(parts[1])


def positive_arg(kind):
    """An argparse type: a number of the given kind (int or float) greater than 0."""
    def convert(text):
        try:
            value = kind(text)
        except ValueError:
            value = None
        if value is None or not 0 < value < float("inf"):
            what = "a whole number" if kind is int else "a number"
            raise argparse.ArgumentTypeError(f"must be {what} greater than 0, got {text!r}")
        return value
    convert.__name__ = kind.__name__  # argparse names the type in its messages
    return convert


def parse_args(argv):
    parser = argparse.ArgumentParser(
        description="Render a scene of the course with PyRT. With no options: Phong on the "
                    "Cornell box (Figure 1), saved as out/rendered_image_Phong.png "
                    "(.npy, .hdr) and shown in a window.")
    parser.add_argument("--integrator", choices=INTEGRATORS, default="phong",
                        help="how to colour each pixel (default: phong; cmc: classic Monte "
                             "Carlo, Practice 2; cmc-is: the same with cosine-weighted "
                             "samples, Practice 4; bmc: Bayesian Monte Carlo with a pool of "
                             "GPs, Practice 3; bmc-is: the same with the cosine in the GPs' "
                             "p, Practice 4)")
    parser.add_argument("--scene", choices=SCENES, default=None,
                        help="cornell: the Cornell box of Figure 1; sphere: the sphere above "
                             "a floor of Figures 2-5; sphere-map: the same lit by the "
                             "course's environment map (Practice 2, Figure 3); cornell-area: "
                             "the Cornell box lit by an area light (default: cornell, and "
                             "sphere-map for the Monte Carlo integrators)")
    parser.add_argument("--samples", type=positive_arg(int), default=None,
                        help="with a Monte Carlo --integrator: the directions sampled at "
                             "each hit "
                             f"(default {DEFAULT_SAMPLES}), apart from --spp, the camera rays "
                             "per pixel")
    # FRAMEWORK ONLY BEGIN
    parser.add_argument("--pool", type=positive_arg(int), default=None,
                        help="with --integrator bmc or bmc-is: the GPs of the pool, one drawn "
                             f"at random at each hit (default {DEFAULT_POOL})")
    # FRAMEWORK ONLY END
    parser.add_argument("--width", type=positive_arg(int), default=500,
                        help="image width in pixels (default 500)")
    parser.add_argument("--height", type=positive_arg(int), default=500,
                        help="image height in pixels (default 500)")
    parser.add_argument("--max-depth", type=positive_arg(float), default=None,
                        help="distance drawn black by the depth integrator (default 10; "
                             "Figure 4 uses 5)")
    parser.add_argument("--out", default=DIRECTORY,
                        help="folder for the images (default: out/ next to this script)")
    # FRAMEWORK ONLY BEGIN
    parser.add_argument("--workers", type=positive_arg(int), default=None,
                        help="processes that render (default: all cores; 1: this process "
                             "only, needed to stop at breakpoints)")
    parser.add_argument("--spp", type=positive_arg(int), default=1,
                        help="samples (rays) per pixel, averaged: more smooth jagged "
                             "edges and cost proportionally more time (default 1)")
    parser.add_argument("--adaptive", action="store_true",
                        help="spend the rays where the image needs them: first the ray "
                             "through every pixel's centre, then --spp N rays in the pixels "
                             "that differ from a neighbour; also saves a map of the rays, "
                             "<image>_samples.png")
    parser.add_argument("--tolerance", type=fraction_arg, default=None,
                        help="with --adaptive: how much two neighbouring pixels may differ, "
                             "as a fraction of the image's range in the PNG, before both "
                             f"get more rays (default {ADAPTIVE_TOLERANCE}, about 8 of the "
                             "PNG's 255 steps; smaller is more accurate and slower)")
    # FRAMEWORK ONLY END
    parser.add_argument("--no-window", action="store_true",
                        help="save the image without showing it")
    parser.add_argument("--explain", type=pixel_arg, default=None, metavar="X,Y",
                        help="print why pixel (X, Y) of the image has its colour (every "
                             "question compute_color asks the scene, and its answer) and "
                             "save a picture of its rays as out/pixel_X_Y.png; clicking a "
                             "pixel of the window does the same")
    parser.add_argument("--all-figures", action="store_true",
                        help="render the six images of the course's Figures 1-5 as "
                             "out/rendered_image_<Integrator>_figure<N>.png, compare them "
                             "with the course's and show them side by side in "
                             f"out/{SHEET_FILENAME}")
    args = parser.parse_args(argv)
    if args.explain is not None:
        x, y = args.explain
        if args.all_figures:
            parser.error("argument --explain: explains a pixel of one image; leave out "
                         "--all-figures")
        if not (x < args.width and y < args.height):
            parser.error(f"argument --explain: pixel ({x}, {y}) is not in the {args.width} "
                         f"x {args.height} image: x goes from 0 to {args.width - 1}, y from "
                         f"0 to {args.height - 1}")
    if args.samples is not None and args.integrator not in MONTE_CARLO:
        parser.error("argument --samples: only applies with a Monte Carlo --integrator ("
                     + ", ".join(MONTE_CARLO) + ")")
    if args.scene is None:
        args.scene = DEFAULT_SCENES.get(args.integrator, DEFAULT_SCENE)
    # FRAMEWORK ONLY BEGIN
    if args.pool is not None and args.integrator not in BAYESIAN:
        parser.error("argument --pool: only applies with --integrator "
                     + " or ".join(BAYESIAN))
    if args.adaptive and args.spp == 1:
        parser.error("argument --adaptive: needs --spp N with N of 2 or more, the rays the "
                     "pixels at edges get")
    if args.tolerance is not None and not args.adaptive:
        parser.error("argument --tolerance: only applies with --adaptive")
    if args.adaptive and args.integrator in MONTE_CARLO:
        parser.error("argument --adaptive: refines where neighbouring pixels differ, which "
                     "Monte Carlo noise makes them do nearly everywhere: measured, no less "
                     "error for the time (docs/monte-carlo.md); give --samples N instead")
    # FRAMEWORK ONLY END
    return args


def render_options(args):
    """The keyword arguments of Integrator.render() that the command line asks for: only
    those that differ from render()'s defaults."""
    options = {}
    # FRAMEWORK ONLY BEGIN
    if args.workers is not None:
        options["workers"] = args.workers
    if args.spp != 1:
        options["samples_per_pixel"] = args.spp
    if args.adaptive:
        options["adaptive"] = True
    if args.tolerance is not None:
        options["tolerance"] = args.tolerance
    # FRAMEWORK ONLY END
    return options


def command_line_error(message):
    """Says message as a bad option is said, on stderr without a traceback (the fix is all
    a student needs here), and returns the exit status 1."""
    print(f"{Path(sys.argv[0]).name}: error: {message}", file=sys.stderr)
    return 1


def main(argv=None):
    """Runs the command line argv (sys.argv's by default) and returns the exit status."""
    args = parse_args(argv)
    problem = opencv_problem()
    if problem:  # a script that calls Integrator.render() gets it as a RuntimeError
        return command_line_error(problem)
    base = str(Path(args.out) / FILENAME)
    if args.all_figures:
        jobs = [(figure_integrator(entry, base), SCENES[entry[2]]) for entry in FIGURES]
    else:
        jobs = [(make_integrator(args.integrator, base, args.max_depth, samples=args.samples,
                                 pool=getattr(args, "pool", None)), SCENES[args.scene])]
    options = render_options(args)
    try:
        pngs = [render(integrator, make_scene(args.width, args.height), **options)
                for integrator, make_scene in jobs]
    except PermissionError as error:  # an --out folder that cannot be written
        return command_line_error(error)
    shown = pngs[-1]
    if args.all_figures:
        renders = {reference_name(entry): png for entry, png in zip(FIGURES, pngs)}
        sheet = compare_with_course(renders, args.out, (args.width, args.height),
                                    options.get("samples_per_pixel", 1))
        shown = sheet or shown
    integrator = jobs[-1][0]
    if args.explain is not None:
        explain(integrator, *args.explain, args.out)
    if not args.no_window:
        show(shown, None if args.all_figures else
             lambda x, y: explain(integrator, x, y, args.out))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        sys.exit(130)
