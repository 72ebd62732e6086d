"""PyRT integrators: the algorithms that turn a scene into an image.

An integrator answers one question, ``compute_color(ray)``: what colour arrives along this
ray? ``render()`` asks it once per pixel, for the ray from the camera through the pixel's
centre, and saves the image. Write your own integrator by subclassing ``Integrator`` and
overriding ``compute_color``.

What render() needs besides its loop (worker processes on every core, several samples per
pixel, adaptive sampling, the progress bar, checks, the fast paths) lives beneath it, in
pyrt/rendering.py's decorator @render_loop and the modules it uses.
"""
from PyRT_Common import *
from PyRT_Common import __all__ as _common_names, is_number
import pyrt.explain
from pyrt.images import native_path
# FRAMEWORK ONLY BEGIN
from pyrt.acceleration.fingerprints import register_fused
from pyrt.gaussian_pools import check_gp_pool
from pyrt.rendering import image_loop, render_loop
# FRAMEWORK ONLY END

__all__ = _common_names + [
    "Integrator", "LazyIntegrator", "IntersectionIntegrator", "DepthIntegrator",
    "NormalIntegrator", "PhongIntegrator", "CMCIntegrator", "BayesianMonteCarloIntegrator",
    "CMCISIntegrator", "BMCISIntegrator",
]


# ------------------------------------------------------------------------------------------
# Integrator base class
# ------------------------------------------------------------------------------------------
class Integrator(ABC):
    """Renders ``scene`` into ``filename`` = filename_ + experiment_name (+ '.png', ...).

    The rendering loop, for every pixel (x, y) of the camera:
        ray = the ray from the camera origin through the centre of pixel (x, y)
        scene.set_pixel(self.compute_color(ray), x, y)
    then ``scene.save_image(self.get_filename())``.
    """


    tonemap = True  # the PNG goes through the course's tonemapper (see Scene.save_image)

    def __init__(self, filename_, experiment_name=""):
        # '.\\out\\image' (the 2025-26 handout's) names the folder out on every system
        self.filename = native_path(filename_ + experiment_name)
        self.scene = None
        self.env_map = None

    def get_filename(self):
        return self.filename

    def add_scene(self, scene):
        self.scene = scene

    def add_environment_map(self, env_map_path):
        """Sets the integrator's own environment map, env_map (some 2021-22 copies of the
        course's base code have it; the scene's, scene.env_map, is what the course's
        integrators read)."""
        self.env_map = EnvironmentMap(env_map_path)

    @abstractmethod
    def compute_color(self, ray):
        """The RGBColor arriving along ray."""

    def incoming_light(self, point, direction):
        """L_i, the light arriving at point from direction (a unit vector): the emission of
        the object that the ray from point along direction hits first, or, when it hits
        nothing, the scene's environment map in that direction (BLACK without one)."""
        # ASSIGNMENT 2.3 BEGIN
        scene = self.scene
        hit = scene.closest_hit(Ray(point, direction))
        if hit.has_hit:
            return scene.object_list[hit.primitive_index].emission
        if scene.env_map is not None:
            return scene.env_map.getValue(direction)
        return BLACK  # nothing there, and no map: no light from this direction
        # ASSIGNMENT 2.3 END

    def explain_pixel(self, x, y):
        """Why pixel (x, y) has its colour: compute_color run again on the pixel's camera
        ray, with every closest_hit, any_hit and intersect it asks recorded. print() the
        result to read it as a story (see pyrt/explain.py)."""
        return pyrt.explain.explain_pixel(self, x, y)

    # ASSIGNMENT 1.1-1.2 BEGIN
    @render_loop  # PyRT's machinery: every core, samples per pixel, progress (pyrt/rendering.py)
    def render(self):
        """Renders every pixel of the scene's camera and saves the image.

        PyRT's render_loop runs this loop once per row of the image, on every core, with
        scene.camera a camera over the row's rays (pyrt.rows.TaskCamera: a column of
        them, width 1), and saves the image once all rows are done. render() takes:

        workers: how many processes render rows, this one included: None uses every core
            (for renders long enough to gain from them), 1 renders in this process only.
            The image is the same either way.
        samples_per_pixel: rays per pixel, averaged; 1 is the ray through the centre, more
            (jittered over an even grid inside the pixel) smooth jagged edges. With more
            than one, the estimated error of the image is printed and saved beside it.
        progress: show a progress bar with the time left.
        adaptive: False gives every pixel samples_per_pixel rays. True first traces the
            ray through every pixel's centre, then samples_per_pixel rays in the pixels
            that differ from a neighbour by more than tolerance, a fraction of the
            image's range as its PNG shows it (pyrt.sampling.AdaptiveSampling), and
            saves a map of the rays per pixel."""
        cam = self.scene.camera
        for x in range(cam.width):
            for y in range(cam.height):
                # a camera ray starts at no surface: t_min 0, it sees objects at any distance
                ray = Ray(Vector3D(0.0, 0.0, 0.0), cam.get_direction(x, y), INFINITY, 0.0)
                self.scene.set_pixel(self.compute_color(ray), x, y)
        self.scene.save_image(self.get_filename())
    # ASSIGNMENT 1.1-1.2 END


# ------------------------------------------------------------------------------------------
# Lazy integrator (Assignment 1.1)
# ------------------------------------------------------------------------------------------
class LazyIntegrator(Integrator):
    """Colours pixel (x, y) by its position: (x/width, y/height, 0), red growing to the
    right and green downwards. It traces no rays, and its PNG shows the linear values
    without tonemapping, as Figure 2 of the course does."""

    tonemap = False

    def __init__(self, filename_, experiment_name=""):
        super().__init__(filename_ + "_Lazy", experiment_name)

    # FRAMEWORK ONLY BEGIN
    @image_loop  # one exact value per pixel, however many samples are asked for
    def render(self):
        """Assignment 1.1's loop: pixel (x, y) gets (x/width, y/height, 0)."""
        cam = self.scene.camera
        for x in range(cam.width):
            for y in range(cam.height):
                self.scene.set_pixel(RGBColor(x / cam.width, y / cam.height, 0.0), x, y)
        self.scene.save_image(self.get_filename())
    # FRAMEWORK ONLY END

    def compute_color(self, ray):
        """A ray carries no pixel position, so on its own it gets BLACK (see render)."""
        return BLACK


# ------------------------------------------------------------------------------------------
# Intersection integrator (Assignment 1.2)
# ------------------------------------------------------------------------------------------
class IntersectionIntegrator(Integrator):
    """RED where the ray hits any object, BLACK where it escapes."""

    def __init__(self, filename_, experiment_name=""):
        super().__init__(filename_ + "_Intersection", experiment_name)

    def compute_color(self, ray):
        # ASSIGNMENT 1.2 BEGIN
        return RED if self.scene.any_hit(ray) else BLACK
        # ASSIGNMENT 1.2 END


# ------------------------------------------------------------------------------------------
# Depth and Normal integrators (Assignment 1.3)
# ------------------------------------------------------------------------------------------
class DepthIntegrator(Integrator):
    """Grey c = max(1 - hit_distance / max_depth, 0) at the closest hit: white close to the
    camera, black at max_depth and beyond or on a miss."""

    def __init__(self, filename_, max_depth_=10, experiment_name=""):
        super().__init__(filename_ + "_Depth", experiment_name)
        if not (is_number(max_depth_) and 0.0 < max_depth_ < INFINITY):
            raise ValueError(f"DepthIntegrator: max_depth_ must be a positive finite distance, "
                             f"got {max_depth_!r}")
        self.max_depth = max_depth_

    def compute_color(self, ray):
        # ASSIGNMENT 1.3 BEGIN
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        c = 1.0 - hit.hit_distance / self.max_depth
        return RGBColor(c, c, c) if c > 0.0 else BLACK  # c = max(1 - distance/max_depth, 0)
        # ASSIGNMENT 1.3 END


class NormalIntegrator(Integrator):
    """The closest hit's unit normal n shown as a colour, c = (n + (1, 1, 1)) / 2, which
    maps each component from [-1, 1] to [0, 1]."""

    def __init__(self, filename_, experiment_name=""):
        super().__init__(filename_ + "_Normal", experiment_name)

    def compute_color(self, ray):
        # ASSIGNMENT 1.3 BEGIN
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        n = hit.normal
        return RGBColor((n.x + 1.0) / 2.0, (n.y + 1.0) / 2.0, (n.z + 1.0) / 2.0)
        # ASSIGNMENT 1.3 END


# ------------------------------------------------------------------------------------------
# Phong integrator (Assignment 1.4)
# ------------------------------------------------------------------------------------------
class PhongIntegrator(Integrator):
    """The course's Phong model with Lambertian surfaces, at the closest hit p with normal n:

        colour = kd (x) i_a + sum over the point lights visible from p of
                 intensity (x) BRDF.get_value(wi, wo, n) / r^2

    wi is the unit direction from p to the light, r its distance, wo the direction back
    along the ray, (x) the per-channel product. A light is visible when nothing lies
    between p and the light, which a shadow ray tells; a light behind the surface
    (n.wi <= 0) lights nothing there. There is no specular term."""

    def __init__(self, filename_, experiment_name=""):
        super().__init__(filename_ + "_Phong", experiment_name)

    def compute_color(self, ray):
        # ASSIGNMENT 1.4 BEGIN
        scene = self.scene
        hit = scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        brdf = scene.object_list[hit.primitive_index].get_BRDF()
        color = brdf.kd.multiply(scene.i_a)  # the ambient term
        wo = ray.d * -1.0
        for light in scene.pointLights:
            to_light = light.pos - hit.hit_point
            r = Length(to_light)
            if r * r == 0.0 or Dot(hit.normal, to_light) <= 0.0:
                continue  # the light is at the point, behind the surface or on it
            if scene.any_hit(shadow_ray(hit, light.pos)):
                continue  # something lies between the point and the light
            wi = to_light / r
            f = brdf.get_value(wi, wo, hit.normal)
            color = color + light.intensity.multiply(f) / (r * r)
        return color
        # ASSIGNMENT 1.4 END


# ------------------------------------------------------------------------------------------
# Classic Monte Carlo integrator (Practice 2, Assignment 2.3)
# ------------------------------------------------------------------------------------------
class CMCIntegrator(Integrator):
    """The light reflected towards the camera at the closest hit p with normal n, estimated
    by classic Monte Carlo from n_samples directions omega_j drawn over the hemisphere
    around n with density p(omega_j):

        L_o = (1 / n_samples) sum over j of L_i(omega_j) (x) BRDF.get_value(omega_j, wo, n)
              / p(omega_j)

    L_i(omega_j) is the emission of the object the ray from p along omega_j hits, or, when
    it hits nothing, the scene's environment map in that direction (black without one).
    The Lambertian's get_value already holds the cosine. A camera ray that hits nothing
    sees the environment map; the emission of the object it hits is not added.

    pdf is the density the directions are drawn from: UniformPDF() by default, p = 1/(2 pi);
    CosinePDF(1) (p = cos/pi) samples by importance (Practice 4). A pdf other than the
    uniform one is named in the file name, _MC_cos1_<n>_samples for CosinePDF(1)."""

    def __init__(self, n, filename_, experiment_name="", pdf=UniformPDF()):
        filename_mc = (filename_ + "_MC_" + pdf_label(pdf) + str(n) + "_samples"
                       + experiment_name)
        super().__init__(filename_mc)
        self.n_samples = n
        self.pdf = pdf

    def compute_color(self, ray):
        # ASSIGNMENT 2.3 BEGIN
        scene = self.scene
        hit = scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK if scene.env_map is None else scene.env_map.getValue(ray.d)
        brdf = scene.object_list[hit.primitive_index].get_BRDF()
        wo = Vector3D(0.0, 0.0, 0.0)  # unused by the Lambertian BRDF
        sample_set, sample_prob = sample_set_hemisphere(self.n_samples, self.pdf)
        color = RGBColor(0.0, 0.0, 0.0)
        for omega, prob in zip(sample_set, sample_prob):
            wi = center_around_normal(omega, hit.normal)
            l_i = self.incoming_light(hit.hit_point, wi)
            color = color + l_i.multiply(brdf.get_value(wi, wo, hit.normal)) / prob
        return color / self.n_samples
        # ASSIGNMENT 2.3 END


# The handouts keep pdf_label: CMCIntegrator's constructor names its pdf with it
def pdf_label(pdf):
    """The part of a Monte Carlo integrator's file name that names its pdf: '' for
    UniformPDF (the course's names), 'cos<exp>_' for CosinePDF(exp), else the pdf's class
    name and '_'; a TypeError for what is not a PDF."""
    if not (callable(getattr(pdf, "get_val", None))
            and callable(getattr(pdf, "generate_dir", None))):
        raise TypeError(f"pdf must be a PDF such as UniformPDF() or CosinePDF(1) (with "
                        f"get_val and generate_dir), got {pdf!r}")
    if type(pdf) is UniformPDF:
        return ""
    if type(pdf) is CosinePDF:
        return f"cos{pdf.exp:g}_" if is_number(pdf.exp) else f"cos{pdf.exp}_"
    return type(pdf).__name__ + "_"


# ------------------------------------------------------------------------------------------
# Classic Monte Carlo with importance sampling (Practice 4, Part I)
# ------------------------------------------------------------------------------------------
class CMCISIntegrator(CMCIntegrator):
    """Classic Monte Carlo with importance sampling: CMCIntegrator's estimate with the
    directions drawn from CosinePDF(1), p(omega) = cos(theta) / pi, the cosine that the
    Lambertian's value holds. For a Lambertian under constant light L every term
    L (kd cos) / (cos / pi) is the same, L kd pi: the white furnace has no noise at all.
    File name filename_ + '_MC_cos1_' + n + '_samples' + experiment_name, as
    CMCIntegrator(n, filename_, experiment_name, pdf=CosinePDF(1)), the same render."""

    def __init__(self, n, filename_, experiment_name=""):
        # ASSIGNMENT 4.1 BEGIN
        super().__init__(n, filename_, experiment_name, pdf=CosinePDF(1))
        # ASSIGNMENT 4.1 END


# ------------------------------------------------------------------------------------------
# Bayesian Monte Carlo integrator (Practice 3, Assignments 3.3 and 3.3.2)
# ------------------------------------------------------------------------------------------
class BayesianMonteCarloIntegrator(Integrator):
    """The light reflected towards the camera at the closest hit p with normal n, estimated
    by Bayesian Monte Carlo: a Gaussian process over the hemisphere, given the values Y_j
    of the integrand at its sample directions omega_j, has the integral

        L_o = sum over j of w_j Y_j,    Y_j = L_i(omega_j) (x) BRDF.get_value(omega_j, wo, n)

    with the weights w = z^T Q^-1 of the GP (GaussianProcess.py). Q and z depend only on
    the directions' positions relative to each other, so one GP's weights serve every hit:
    its sample set is turned to the hit's normal (center_around_normal). The Lambertian's
    value holds the cosine, so the GP models the whole integrand (p = 1 in its z).

    myGP is one GP, or a list of GPs (a pool) of the same number of samples, each given its
    sample positions (add_sample_pos) before the integrator receives it. The same sample
    set at every hit leaves a pattern in the image; Assignment 3.3.2 breaks it: at each hit
    a GP of the pool chosen at random, its set turned about +y by a random angle
    (rotate_around_y) before it is centred. L_i is as in CMCIntegrator.
    File name filename_ + '_BMC_' + n + '_samples' + experiment_name."""

    def __init__(self, n, myGP, filename_, experiment_name=""):
        filename_bmc = filename_ + "_BMC_" + str(n) + "_samples" + experiment_name
        super().__init__(filename_bmc)
        self.n_samples = n
        self.myGP = myGP

    # FRAMEWORK ONLY BEGIN
    cosine_prior = False  # whether the GPs' p must be the cosine (BMCISIntegrator's)

    def check_inputs(self):
        """Before a render: the error that says what to fix in myGP, if anything."""
        check_gp_pool(type(self).__name__, self.myGP, self.n_samples, self.cosine_prior)
    # FRAMEWORK ONLY END

    def compute_color(self, ray):
        # ASSIGNMENT 3.3 BEGIN
        scene = self.scene
        hit = scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK if scene.env_map is None else scene.env_map.getValue(ray.d)
        brdf = scene.object_list[hit.primitive_index].get_BRDF()
        wo = Vector3D(0.0, 0.0, 0.0)  # unused by the Lambertian BRDF
        gp, alpha = self.pick_sample_set()
        sample_values = []
        for omega in gp.samples_pos:
            wi = center_around_normal(rotate_around_y(alpha, omega), hit.normal)
            l_i = self.incoming_light(hit.hit_point, wi)
            sample_values.append(self.sample_value(l_i, brdf, wi, wo, hit.normal))
        gp.add_sample_val(sample_values)
        return gp.compute_integral_BMC()
        # ASSIGNMENT 3.3 END

    def pick_sample_set(self):
        """(gp, alpha): the GP whose sample set estimates this hit's light and the angle, in
        radians, by which the set turns about +y: a GP of the pool drawn at random, then an
        angle drawn uniformly in [0, 2 pi), each from random()."""
        # ASSIGNMENT 3.3.2 BEGIN
        pool = self.myGP if isinstance(self.myGP, (list, tuple)) else [self.myGP]
        gp = pool[floor(random() * len(pool))]
        alpha = 2 * pi * random()
        return gp, alpha
        # ASSIGNMENT 3.3.2 END

    def sample_value(self, l_i, brdf, wi, wo, normal):
        """Y_j, the value the GP is given for the sample direction wi: L_i times the BRDF's
        value, which holds the cosine."""
        # ASSIGNMENT 3.3 BEGIN
        return l_i.multiply(brdf.get_value(wi, wo, normal))
        # ASSIGNMENT 3.3 END


# ------------------------------------------------------------------------------------------
# Bayesian Monte Carlo with importance sampling (Practice 4, Part II)
# ------------------------------------------------------------------------------------------
class BMCISIntegrator(BayesianMonteCarloIntegrator):
    """Bayesian Monte Carlo with the cosine as prior knowledge: the integrand is f p with
    p = cos(theta) known and f = L_i kd for a Lambertian, so the GP models f alone,

        L_o = sum over j of w_j Y_j,    Y_j = L_i(omega_j) (x) kd,

    with GPs whose z integrates k p: GP(SobolevCov(), CosineLobe(1)), their sample
    positions drawn from CosinePDF(1). Everything else is BayesianMonteCarloIntegrator's.
    File name filename_ + '_BMCIS_' + n + '_samples' + experiment_name."""

    # FRAMEWORK ONLY BEGIN
    cosine_prior = True
    # FRAMEWORK ONLY END

    def __init__(self, n, myGP, filename_, experiment_name=""):
        super().__init__(n, myGP, filename_, experiment_name)
        self.filename = native_path(filename_ + "_BMCIS_" + str(n) + "_samples"
                                    + experiment_name)

    def sample_value(self, l_i, brdf, wi, wo, normal):
        """Y_j for the GP of f alone: L_i times kd, the Lambertian's value without its
        cosine, which the GP's p holds."""
        # ASSIGNMENT 4.2 BEGIN
        return l_i.multiply(brdf.kd)
        # ASSIGNMENT 4.2 END


# FRAMEWORK ONLY BEGIN
# PyRT's acceleration repeats these compute_color methods on plain floats, bit for bit: it
# may stand in for them, and only while their source is unchanged (pyrt/acceleration/)
register_fused("phong", PhongIntegrator)
register_fused("cmc", CMCIntegrator)
register_fused("bmc", BayesianMonteCarloIntegrator)
register_fused("bmcis", BMCISIntegrator)
# FRAMEWORK ONLY END
