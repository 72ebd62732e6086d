"""course_kit/judging.py: what the grader draws at grading time leaves the handout's
published data nothing to earn."""
import random

import numpy as np
import pytest

import course_kit.judging as judging
import course_kit.references as references

checks, render = judging.checks, judging.render
PUBLISHED = checks.expected_data()


def copies(published, size):
    """{how: the image} of the ways a submission carrying the published image (of
    render.SIZE pixels) can take it, pixel for pixel, at size: where the two overlap (the
    rest black), or sampled at floor(SIZE x / size)."""
    overlap = min(size, published.shape[0])
    cropped = np.zeros((size, size, 3))
    cropped[:overlap, :overlap] = published[:overlap, :overlap]
    sampled = np.arange(size) * published.shape[0] // size
    return {"overlap": cropped, "sampled": published[np.ix_(sampled, sampled)]}


def test_the_grader_draws_sizes_above_the_published_one_only():
    assert judging.DRAWN_SIZES and min(judging.DRAWN_SIZES) > render.SIZE
    drawn = {judging.draw_inputs(random.Random(seed))[0].size for seed in range(200)}
    assert drawn == set(judging.DRAWN_SIZES)


@pytest.mark.parametrize("size", judging.DRAWN_SIZES)
def test_the_published_images_copied_earn_nothing_at_any_drawn_size(size, tmp_path):
    # Below the published size, every pixel of the Lazy image's copy is the published
    # corner, 40/size times the expected colour, which the rule of a scaled image admits;
    # the grader never draws such a size, and above it no copy is right in any image
    offset = tuple(random.Random(size).uniform(-judging.DRAWN_OFFSET, judging.DRAWN_OFFSET)
                   for _ in range(3))
    data = references.GradingData(render.Draw(size, offset, render.PUBLISHED.any_hit),
                                  tmp_path)
    admitted = [(name, how) for name in checks.IMAGES
                for how, image in copies(PUBLISHED[name], size).items()
                if checks.judge(image, name, data).right]
    assert admitted == []


def test_below_the_published_size_the_lazy_images_copy_would_be_admitted(tmp_path):
    # Why the sizes below are never drawn: the test above would fail there
    size = render.SIZE - 8
    data = references.GradingData(render.Draw(size, (0.0, 0.0, 0.0),
                                              render.PUBLISHED.any_hit), tmp_path)
    verdict = checks.judge(copies(PUBLISHED["lazy"], size)["overlap"], "lazy", data)
    assert verdict.right
    assert verdict.note.startswith(f"your values are {size / render.SIZE:.6g} times the "
                                   "expected ones")
