"""course_kit/judging.py: what the grader draws at grading time leaves the handout's
published data nothing to earn."""
import numpy as np
import pytest

import course_kit.judging as judging


@pytest.mark.parametrize("size", judging.DRAWN_SIZES)
def test_the_published_lazy_image_taken_pixel_for_pixel_is_wrong_at_every_drawn_size(size):
    # A submission that carries the handout's 40-pixel Lazy image and samples it at the
    # drawn size, pixel for pixel, hands back x' / 40 with x' = floor(40 x / size) where
    # x / size is expected. The checks admit an image that is a * expected + b (the
    # course's tonemapper removes that): at 39 pixels it would be, 0.975 times; never at a
    # size the grader draws.
    published = judging.render.SIZE
    x = np.arange(size)
    expected, handed_back = x / size, (x * published // size) / published
    a, b = np.polyfit(expected, handed_back, 1)
    assert not np.allclose(a * expected + b, handed_back, rtol=1e-6, atol=1e-9)
    assert size != published
