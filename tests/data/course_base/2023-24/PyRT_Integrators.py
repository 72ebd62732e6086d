# ------------------------------------------------------------------------------------------
# PyRT: Python Ray Tracer - integrators
# ------------------------------------------------------------------------------------------
from PyRT_Common import *


# -------------------------------------------------INTEGRATOR (ABSTRACT BASE CLASS)
class Integrator(ABC):
    def __init__(self, filename_, experiment_name=''):
        self.filename = filename_ + experiment_name
        self.scene = None

    @abstractmethod
    def compute_color(self, ray):
        pass

    def add_scene(self, scene):
        self.scene = scene

    def get_filename(self):
        return self.filename

    def render(self):
        # ASSIGNMENTS 1.1 AND 1.2: YOU MUST CHANGE THIS METHOD
        cam = self.scene.camera
        print('Rendering Image: ' + self.get_filename())
        for x in range(0, cam.width):
            for y in range(0, cam.height):
                pixel = GREEN
                self.scene.set_pixel(pixel, x, y)
            print(str(round(100.0 * (x + 1) / cam.width, 2)) + '%')
        self.scene.save_image(self.get_filename())


# -------------------------------------------------LAZY INTEGRATOR
class LazyIntegrator(Integrator):
    def __init__(self, filename_):
        super().__init__(filename_ + '_Lazy')

    def compute_color(self, ray):
        return BLACK


# -------------------------------------------------INTERSECTION INTEGRATOR
class IntersectionIntegrator(Integrator):
    def __init__(self, filename_):
        super().__init__(filename_ + '_Intersection')

    def compute_color(self, ray):
        # ASSIGNMENT 1.2: PUT YOUR CODE HERE
        pass


# -------------------------------------------------DEPTH INTEGRATOR
class DepthIntegrator(Integrator):
    def __init__(self, filename_, max_depth_=10):
        super().__init__(filename_ + '_Depth')
        self.max_depth = max_depth_

    def compute_color(self, ray):
        # ASSIGNMENT 1.3: PUT YOUR CODE HERE
        pass


# -------------------------------------------------NORMAL INTEGRATOR
class NormalIntegrator(Integrator):
    def __init__(self, filename_):
        super().__init__(filename_ + '_Normal')

    def compute_color(self, ray):
        # ASSIGNMENT 1.3: PUT YOUR CODE HERE
        pass


# -------------------------------------------------PHONG INTEGRATOR
class PhongIntegrator(Integrator):
    def __init__(self, filename_):
        super().__init__(filename_ + '_Phong')

    def compute_color(self, ray):
        # ASSIGNMENT 1.4: PUT YOUR CODE HERE
        pass


# -------------------------------------------------CLASSIC MONTE CARLO INTEGRATOR (PRACTICE 2)
class CMCIntegrator(Integrator):
    def __init__(self, n, filename_, experiment_name=''):
        filename_mc = filename_ + '_MC_' + str(n) + '_samples' + experiment_name
        super().__init__(filename_mc)
        self.n_samples = n

    def compute_color(self, ray):
        # ASSIGNMENT 2.3: PUT YOUR CODE HERE
        pass


# -------------------------------------------------BAYESIAN MONTE CARLO INTEGRATOR (PRACTICE 3)
class BayesianMonteCarloIntegrator(Integrator):
    def __init__(self, n, myGP, filename_, experiment_name=''):
        filename_bmc = filename_ + '_BMC_' + str(n) + '_samples' + experiment_name
        super().__init__(filename_bmc)
        self.n_samples = n
        self.myGP = myGP

    def compute_color(self, ray):
        # ASSIGNMENT 3: PUT YOUR CODE HERE
        pass
