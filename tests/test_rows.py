"""pyrt/rows.py: every row of a render draws its random numbers from a stream of its own,
so that a seeded render is the same image however many processes render it."""
import random

import numpy as np
import pytest

from helpers import RandomGrey, fov90_scene, render_image
from pyrt.rows import CourseRows, RowStreams, render_block
from PyRT_Integrators import Integrator
from pyrt.workers import START_METHOD_VARIABLE


def seeded_render(tmp_path, name, seed, **options):
    """The image of RandomGrey on a 6 x 5 scene rendered after random.seed(seed), and the
    next number Python's global generator gives after the render."""
    random.seed(seed)
    image = render_image(RandomGrey(str(tmp_path / name)), fov90_scene(6, 5), **options)
    return image, random.random()


def second_draw(seed):
    """The second number Python's global generator gives after random.seed(seed)."""
    random.seed(seed)
    random.random()
    return random.random()


@pytest.mark.parametrize("start_method", [None, "spawn"])
def test_a_seeded_render_is_the_same_image_for_any_number_of_workers(tmp_path, monkeypatch,
                                                                     start_method):
    if start_method:
        monkeypatch.setenv(START_METHOD_VARIABLE, start_method)
    one, after_one = seeded_render(tmp_path, "one", 7, workers=1)
    two, after_two = seeded_render(tmp_path, "two", 7, workers=2)
    assert np.array_equal(one, two)
    # the render takes one number of the generator, whatever its rows drew
    assert after_one == after_two == second_draw(7)


def test_every_pixel_draws_its_own_numbers_and_another_seed_gives_another_image(tmp_path):
    image, _ = seeded_render(tmp_path, "seven", 7, workers=1)
    other, _ = seeded_render(tmp_path, "eight", 8, workers=1)
    assert len(np.unique(image[:, :, 0])) == 30  # 6 x 5 pixels, no two rows alike
    assert not np.array_equal(image, other)


def test_a_rows_stream_depends_on_the_seed_the_pass_and_the_row_alone():
    def first_numbers(streams, y):
        streams.start(y)
        return [random.random() for _ in range(3)]

    streams = RowStreams(12345)
    row_3 = first_numbers(streams, 3)
    random.random()  # whatever was drawn in between
    assert first_numbers(streams, 3) == row_3
    assert first_numbers(RowStreams(12345, 0), 3) == row_3  # the first pass is pass 0
    for other in (first_numbers(streams, 4), first_numbers(RowStreams(12346), 3),
                  first_numbers(RowStreams(12345, 1), 3)):
        assert other != row_3


def test_a_block_of_rows_is_the_same_whatever_was_rendered_before_it(tmp_path):
    # what lets any process render any block: rows 3 and 4 made after rows 0 to 2, as one
    # process makes them, or first, as a worker that takes that block first makes them
    integrator = RandomGrey(str(tmp_path / "img"))
    integrator.add_scene(fov90_scene(6, 5))
    rows = CourseRows(RowStreams(99), Integrator.render.loop)
    in_order = render_block(integrator, 0, 5, rows)
    random.random()
    assert np.array_equal(render_block(integrator, 3, 5, rows), in_order[3:])
    assert np.array_equal(render_block(integrator, 0, 3, rows), in_order[:3])
