from PyRT_Integrators import *


class BayesianMonteCarloIntegrator(Integrator):
    def __init__(self, n, myGP, filename_, experiment_name=''):
        filename_bmc = filename_ + '_BMC_' + str(n) + '_samples' + experiment_name
        super().__init__(filename_bmc)
        self.n_samples = n
        self.myGP = myGP

    def compute_color(self, ray):
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            if self.scene.env_map is None:
                return BLACK
            return self.scene.env_map.getValue(ray.d)
        if isinstance(self.myGP, list):
            gp = self.myGP[floor(random() * len(self.myGP))]
        else:
            gp = self.myGP
        brdf = self.scene.object_list[hit.primitive_index].get_BRDF()
        alpha = 2 * pi * random()
        sample_values = []
        for omega in gp.samples_pos:
            wi = center_around_normal(rotate_around_y(alpha, omega), hit.normal)
            sample_hit = self.scene.closest_hit(Ray(hit.hit_point, wi))
            if sample_hit.has_hit:
                l_i = self.scene.object_list[sample_hit.primitive_index].emission
            elif self.scene.env_map is not None:
                l_i = self.scene.env_map.getValue(wi)
            else:
                l_i = BLACK
            sample_values.append(l_i.multiply(brdf.get_value(wi, Vector3D(0, 0, 0), hit.normal)))
        gp.add_sample_val(sample_values)
        return gp.compute_integral_BMC()
