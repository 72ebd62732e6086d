"""Classic Monte Carlo with importance sampling (Practice 4, Part I): CMCIntegrator's
pdf keyword and CMCISIntegrator, which draws from CosinePDF(1).

With p = cos / pi every term of a Lambertian under constant light L is L (c/pi) cos /
(cos/pi) = c L: the white furnace and the emitting box come out exact, up to rounding,
where uniform sampling has noise; a cosine counted twice gives c L cos per term instead,
2/3 c L on average. render()'s fast path gives the plain code's image bit for bit for both
of the pdfs it repeats, and gives way to the plain code for any other."""
import random as random_module

import numpy as np
import pytest

import pyrt.acceleration.accelerated
from benchmarks.flat_loop import flat_cmc
from helpers import (ALBEDO, EMISSION, FURNACE_CENTRE, FURNACE_RADIUS, RADIANCE,
                     emissive_box_scene, furnace_scene, seeded_render, sky_sphere_scene,
                     sphere_pixels)
from PyRT_Common import (BLACK, CosinePDF, Dot, UniformPDF, Vector3D,
                         center_around_normal, sample_set_hemisphere)
from PyRT_Integrators import CMCIntegrator, CMCISIntegrator

# Each term is c L up to the rounding of a few float32 and double operations, and of the
# cosine that get_value computes against the one the pdf drew
ROUNDING = 1e-5


def test_importance_sampled_white_furnace_is_exact_at_any_sample_count(tmp_path):
    scene = furnace_scene(12)
    hit, _ = sphere_pixels(scene.camera, FURNACE_CENTRE, FURNACE_RADIUS)
    c_l = np.array(ALBEDO) * RADIANCE
    for samples in (1, 7):
        image = seeded_render(CMCISIntegrator(samples, str(tmp_path / "is")), scene, 3)
        np.testing.assert_allclose(image[hit], np.broadcast_to(c_l, image[hit].shape),
                                   rtol=ROUNDING, atol=0.0)
        assert np.all(image[~hit] == RADIANCE)


def test_importance_sampled_emitting_box_is_exact(tmp_path):
    scene = emissive_box_scene(12)
    hit, _ = sphere_pixels(scene.camera, FURNACE_CENTRE, FURNACE_RADIUS)
    image = seeded_render(CMCISIntegrator(5, str(tmp_path / "is")), scene, 4)
    c_e = np.array(ALBEDO) * np.array(EMISSION)
    np.testing.assert_allclose(image[hit], np.broadcast_to(c_e, image[hit].shape),
                               rtol=ROUNDING, atol=0.0)
    assert np.all(image[~hit] == 0.0)


class CosineTwiceIS(CMCIntegrator):
    """Importance sampling with the students' mistake: the cosine that get_value holds,
    multiplied in once more."""

    def compute_color(self, ray):
        scene = self.scene
        hit = scene.closest_hit(ray)
        if not hit.has_hit:
            return scene.env_map.getValue(ray.d)
        brdf = scene.object_list[hit.primitive_index].get_BRDF()
        color = BLACK
        for omega, prob in zip(*sample_set_hemisphere(self.n_samples, self.pdf)):
            wi = center_around_normal(omega, hit.normal)
            f = brdf.get_value(wi, Vector3D(0.0, 0.0, 0.0), hit.normal)
            color = color + scene.env_map.getValue(wi).multiply(f) * Dot(wi, hit.normal) / prob
        return color / self.n_samples


def test_importance_sampled_furnace_catches_the_cosine_counted_twice(tmp_path):
    # each term is c L cos with cos distributed as p = cos/pi (density 2 cos on [0, 1] of
    # the cosine): mean 2/3 c L, variance (c L)^2 (1/2 - 4/9); 64 samples per pixel put
    # every pixel within 0.2 c L of 2/3 c L, far from the furnace's c L
    samples = 64
    scene = furnace_scene(12)
    hit, _ = sphere_pixels(scene.camera, FURNACE_CENTRE, FURNACE_RADIUS)
    c_l = np.array(ALBEDO) * RADIANCE
    image = seeded_render(CosineTwiceIS(samples, str(tmp_path / "twice"),
                                           pdf=CosinePDF(1)), scene, 5)
    assert np.all(np.abs(image[hit] / c_l - 2 / 3) < 0.2)
    mean = image[hit].mean(axis=0) / c_l
    assert np.all(np.abs(mean - 2 / 3) < 0.01), mean


# ------------------------------------------------------------------------------------------
# The fast path, with each pdf
# ------------------------------------------------------------------------------------------
class HalfCosinePDF(CosinePDF):
    """A pdf of a student's own: CosinePDF(0.5) under another name."""

    def __init__(self):
        super().__init__(0.5)


@pytest.mark.parametrize("pdf, fused", [(CosinePDF(1), True), (CosinePDF(2.5), True),
                                        (UniformPDF(), True), (HalfCosinePDF(), False)],
                         ids=["cosine", "cosine_2.5", "uniform", "a_pdf_of_ones_own"])
def test_fast_path_gives_the_plain_codes_image_bit_for_bit_for_each_pdf(
        tmp_path, monkeypatch, fused_calls, pdf, fused):
    size, samples = 12, 6
    image = seeded_render(CMCIntegrator(samples, str(tmp_path / "a"), pdf=pdf),
                   sky_sphere_scene(size), 17)
    assert fused_calls[0] == (size * size if fused else 0)
    with monkeypatch.context() as patch:
        patch.delitem(pyrt.acceleration.accelerated.FUSED_INTEGRATORS, "cmc")
        plain = seeded_render(CMCIntegrator(samples, str(tmp_path / "b"), pdf=pdf),
                       sky_sphere_scene(size), 17)
    assert plain.any() and np.array_equal(image, plain)


# ------------------------------------------------------------------------------------------
# File names and the pdf keyword
# ------------------------------------------------------------------------------------------
def test_file_names_tell_the_pdf_and_never_collide():
    names = {CMCIntegrator(40, "out/img").get_filename(),
             CMCIntegrator(40, "out/img", pdf=CosinePDF(1)).get_filename(),
             CMCIntegrator(40, "out/img", pdf=CosinePDF(4)).get_filename(),
             CMCIntegrator(40, "out/img", pdf=HalfCosinePDF()).get_filename()}
    assert {name.replace("\\", "/") for name in names} == {
        "out/img_MC_40_samples", "out/img_MC_cos1_40_samples", "out/img_MC_cos4_40_samples",
        "out/img_MC_HalfCosinePDF_40_samples"}
    integrator = CMCISIntegrator(40, "img", "_test")
    assert integrator.get_filename() == "img_MC_cos1_40_samples_test"
    assert type(integrator.pdf) is CosinePDF and integrator.pdf.exp == 1
    assert integrator.n_samples == 40


def test_a_pdf_that_is_not_one_says_what_to_pass():
    with pytest.raises(TypeError, match=r"pdf must be a PDF such as UniformPDF\(\)"):
        CMCIntegrator(40, "img", pdf="cosine")


def test_flat_loop_gives_renders_importance_sampled_image_bit_for_bit(tmp_path):
    size, samples, seed = 16, 8, 6
    random_module.seed(seed)
    stream_seed = int(random_module.random() * 2 ** 53)  # render()'s one draw
    expected = seeded_render(CMCISIntegrator(samples, str(tmp_path / "f")),
                      sky_sphere_scene(size), seed)
    flat = flat_cmc(sky_sphere_scene(size), samples, stream_seed, pdf_exponent=1)
    assert expected.any() and np.array_equal(flat, expected)
