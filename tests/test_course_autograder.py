"""Gradescope's autograder (course_autograder.py): the settings of its results.json."""
import pytest

import course_grader
from helpers import REPO


def test_the_gradescope_table_sets_the_visibilities_of_results_json(tmp_path):
    path = tmp_path / "grading.toml"
    path.write_text((REPO / "kit" / "grading.toml").read_text().replace(
        'stdout_visibility = "hidden"', 'stdout_visibility = "after_published"'))
    config = course_grader.load_config(path)
    assert config.gradescope == {"visibility": "visible",
                                 "stdout_visibility": "after_published"}
    assert course_grader.load_config().gradescope == course_grader.GRADESCOPE_DEFAULTS
    path.write_text(path.read_text() + 'tests = "hidden"\n')
    with pytest.raises(ValueError) as error:
        course_grader.load_config(path)
    assert str(error.value) == (f"{path}: [gradescope] may give only visibility, "
                                "stdout_visibility")
