"""pyrt/compare.py: comparing an image with a reference counts the pixels that differ by
more than one 8-bit step and the largest difference, refuses images of another size, and
draws the comparison sheet of the course's figures.

The images here are tiny arrays of chosen 8-bit values, so every expected count and step
follows from how they were made."""
import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest

from pyrt.compare import (REFERENCE_DIR, Comparison, MissingReference, compare_figures,
                          compare_with_reference, draw_sheet, write_sheet)

# The 8-bit colours of the heat map for no difference and for the largest one
HEAT_LOW, HEAT_HIGH = matplotlib.colormaps["inferno"]([0.0, 1.0], bytes=True)[:, :3]


def solid(colour, width=8, height=6):
    """An 8-bit image of one colour."""
    return np.tile(np.array(colour, np.uint8), (height, width, 1))


def read_8bit(path):
    """The RGB channels of a PNG as integers 0-255."""
    return (plt.imread(str(path))[:, :, :3] * 255).round().astype(int)


def gradient(width=8, height=6):
    """An 8-bit image whose every pixel differs from its neighbours."""
    y, x = np.mgrid[0:height, 0:width]
    return np.stack([x * 20, y * 30, (x + y) * 10], axis=2).astype(np.uint8)


# ------------------------------------------------------------------------------------------
# compare_with_reference
# ------------------------------------------------------------------------------------------
def test_an_image_matches_itself():
    result = compare_with_reference(gradient(), gradient())
    assert (result.matches, result.differing_pixels, result.max_steps) == (True, 0, 0)
    assert "matches" in result.summary


def test_a_wrong_render_is_reported_with_the_changed_pixels_and_steps():
    reference = gradient()
    wrong = reference.copy()
    changed = [(0, 0), (2, 5), (3, 1), (5, 7), (4, 4)]  # (y, x), five pixels
    for y, x in changed:
        wrong[y, x, 1] += 7   # the green channel, 7 steps up (no value passes 255)
    wrong[4, 4, 0] += 3       # a second channel of one of them, less changed
    result = compare_with_reference(wrong, reference)
    assert not result.matches
    assert result.differing_pixels == 5
    assert result.max_steps == 7
    assert result.summary == "image: 5 of 48 pixels differ, by up to 7/255"


def test_differences_of_one_step_match_and_of_two_steps_do_not():
    reference = solid((100, 100, 100))
    one_step = solid((101, 99, 101))
    assert compare_with_reference(one_step, reference).matches
    assert compare_with_reference(one_step, reference).max_steps == 1
    one_pixel = one_step.copy()
    one_pixel[3, 2] = (100, 102, 100)
    result = compare_with_reference(one_pixel, reference)
    assert (result.differing_pixels, result.max_steps) == (1, 2)
    assert "1 of 48 pixels differs, by up to 2/255" in result.summary


def test_floats_as_a_png_reads_them_compare_with_8_bit_values():
    # plt.imread gives channel k as the float32 nearest to k / 255
    floats = (gradient().astype(np.float32) / np.float32(255)).astype(np.float32)
    assert compare_with_reference(floats, gradient()).max_steps == 0
    grey = np.full((6, 8), 0.5)  # 127.5 rounds to 128
    assert compare_with_reference(grey, solid((128, 128, 128))).max_steps == 0


def test_png_files_and_figure_names_are_read(tmp_path):
    png = tmp_path / "mine.png"
    plt.imsave(png, gradient())  # written with an alpha channel, which is ignored
    assert compare_with_reference(png, gradient()).max_steps == 0
    result = compare_with_reference(REFERENCE_DIR / "figure2_lazy.png", "figure2_lazy")
    assert (result.name, result.matches, result.max_steps) == ("figure2_lazy", True, 0)
    assert result.image.shape == (500, 500, 3)


def test_an_image_of_another_size_is_refused_naming_both_sizes():
    with pytest.raises(ValueError, match=r"image is 10 x 4 .* reference is 8 x 6"):
        compare_with_reference(solid((0, 0, 0), 10, 4), solid((0, 0, 0)))


def test_a_linear_image_is_refused_with_a_hint_to_compare_the_png(tmp_path):
    linear = np.full((6, 8, 3), 2.5)  # radiance above 1: not a display image
    with pytest.raises(ValueError, match=r"\.png"):
        compare_with_reference(linear, solid((0, 0, 0)))
    npy = tmp_path / "rendered_image_Phong.npy"
    np.save(npy, linear)
    with pytest.raises(ValueError, match=r"linear image.*\.png"):
        compare_with_reference(npy, solid((0, 0, 0)))


def test_an_unknown_figure_name_lists_the_figures():
    with pytest.raises(FileNotFoundError, match=r"figure6_phong.*figure1_phong"):
        compare_with_reference(solid((0, 0, 0)), "figure6_phong")


def test_the_difference_png_shows_where_the_images_differ(tmp_path):
    reference = solid((50, 50, 50))
    image = reference.copy()
    image[1, 2] = (50, 80, 50)   # 30 steps: the largest, drawn as the top colour
    image[4, 6] = (65, 50, 50)   # 15 steps
    image[0, 7] = (51, 51, 51)   # one step: within the tolerance, drawn as no difference
    path = tmp_path / "sub" / "difference.png"
    compare_with_reference(image, reference, difference_png=path)
    heat = read_8bit(path)
    assert heat.shape == (6, 8, 3)
    assert (heat[1, 2] == HEAT_HIGH).all()
    different = (heat != HEAT_LOW).any(axis=2)
    assert sorted(map(tuple, np.argwhere(different))) == [(1, 2), (4, 6)]


# ------------------------------------------------------------------------------------------
# compare_figures and the sheet
# ------------------------------------------------------------------------------------------
def test_a_missing_reference_is_reported_not_raised(tmp_path):
    plt.imsave(tmp_path / "figure_a.png", gradient())
    results = compare_figures({"figure_a": gradient(), "figure_b": gradient()},
                              reference_dir=tmp_path)
    assert [type(r) for r in results] == [Comparison, MissingReference]
    assert results[0].matches and not results[1].matches
    assert "figure_b: no reference image" in results[1].summary
    assert "figure_b.png is missing" in results[1].summary
    assert write_sheet(results, tmp_path / "sheet.png").is_file()


def sheet_size(rows, width, height):
    """The pixel size (width, height) of the sheet of `rows` matching width x height images."""
    figure = draw_sheet([compare_with_reference(gradient(width, height),
                                                gradient(width, height))] * rows)
    return tuple(round(v) for v in figure.get_size_inches() * figure.dpi)


def test_the_sheet_grows_with_the_image_size_and_the_number_of_figures():
    one_row, two_rows, three_rows = (sheet_size(rows, 20, 10) for rows in (1, 2, 3))
    # three panels side by side: 10 more pixels of image width widen the sheet by 30
    assert sheet_size(1, 30, 10)[0] - one_row[0] == 30
    # each row adds the same height, and 10 more pixels of image height add 10 per row
    assert two_rows[0] == three_rows[0] == one_row[0]
    assert three_rows[1] - two_rows[1] == two_rows[1] - one_row[1]
    assert sheet_size(2, 20, 20)[1] - two_rows[1] == 20


def box(pixels, colour):
    """(top, left, height, width) of the pixels of exactly `colour`, checking that they
    fill that rectangle."""
    where = np.argwhere((pixels == colour).all(axis=2))
    (top, left), (bottom, right) = where.min(axis=0), where.max(axis=0)
    assert len(where) == (bottom - top + 1) * (right - left + 1), f"{colour} is not one box"
    return top, left, bottom - top + 1, right - left + 1


def test_the_sheet_shows_each_image_pixel_for_pixel_in_its_row_and_column(tmp_path):
    # Row 1: a green render against a darker green reference, 90 steps apart everywhere;
    # row 2: a blue render that matches its reference.
    render1, reference1, render2 = (10, 200, 30), (10, 110, 30), (40, 40, 220)
    rows = [compare_with_reference(solid(render1, 20, 10), solid(reference1, 20, 10)),
            compare_with_reference(solid(render2, 20, 10), solid(render2, 20, 10))]
    sheet = read_8bit(write_sheet(rows, tmp_path / "sheet.png"))
    top1, left1, *size1 = box(sheet, render1)
    top_ref, left_ref, *size_ref = box(sheet, reference1)
    assert size1 == size_ref == [10, 20]
    assert top_ref == top1 and left_ref > left1 + 20
    # the heat map: the same distance further right, all of it the colour of the largest
    left_heat = 2 * left_ref - left1
    assert (sheet[top1:top1 + 10, left_heat:left_heat + 20] == HEAT_HIGH).all()
    # row 2's render and reference are the same colour: two boxes, below row 1
    blue = np.argwhere((sheet == render2).all(axis=2))
    top2 = blue[:, 0].min()
    assert top2 > top1 + 10
    assert sorted(set(blue[:, 0])) == list(range(top2, top2 + 10))
    assert sorted(set(blue[:, 1])) == (list(range(left1, left1 + 20))
                                       + list(range(left_ref, left_ref + 20)))
    assert len(blue) == 2 * 10 * 20


def test_the_sheet_labels_every_panel_with_the_largest_difference():
    rows = [compare_with_reference(solid((10, 200, 30)), solid((10, 110, 30))),
            compare_with_reference(solid((40, 40, 220)), solid((40, 40, 220))),
            MissingReference("figure_c", REFERENCE_DIR / "figure_c.png",
                             solid((0, 0, 0)))]
    sheet = draw_sheet(rows)
    titles = [axes.get_title(loc="left") for axes in sheet.axes if axes.get_title(loc="left")]
    assert titles == [
        "your render\nimage", "reference\nimage",
        "difference: 48 pixels differ\nlargest: 90/255 (8-bit steps)",
        "your render\nimage", "reference\nimage",
        "difference: matches\nlargest: 0/255 (8-bit steps)",
        "your render\nfigure_c", "reference\nmissing", "difference\nnothing to compare with"]
    texts = [text.get_text() for text in sheet.texts]
    assert texts == ["Your renders beside the course's figures: 1 of 3 match"]
