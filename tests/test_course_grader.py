"""course_kit/grader.py: grading a folder leaves the temporary directory as it found it,
whether the grading ends well or not."""
import random
import tempfile

import pytest

import course_kit.grader
import course_kit.handout
import course_kit.isolation
import course_kit_students as students

pytestmark = pytest.mark.skipif(course_kit.isolation.unsupported() is not None,
                                reason=str(course_kit.isolation.unsupported()))


@pytest.fixture
def private_temp(tmp_path, monkeypatch):
    """An empty temporary directory of the grader's and of its step servers' own, so that
    nothing else on the machine puts anything there."""
    temp = tmp_path / "temp"
    temp.mkdir()
    monkeypatch.setenv("TMPDIR", str(temp))
    monkeypatch.setattr(tempfile, "tempdir", str(temp))
    return temp


@pytest.fixture
def submissions(tmp_path):
    handout = course_kit.handout.write_handout(tmp_path / "handout")
    folder = tmp_path / "submissions"
    students.write_submission(folder / "right", handout, {})
    students.write_submission(folder / "no_inverse_square", handout,
                              students.VARIANTS["no_inverse_square"])
    return folder


def test_grading_a_folder_leaves_the_temporary_directory_as_it_found_it(
        private_temp, submissions, tmp_path):
    records = course_kit.grader.grade_folder(submissions, tmp_path / "results",
                                             course_kit.grader.load_config(), jobs=2,
                                             progress=False, isolation="process",
                                             draws=random.Random(41))
    assert [record["total"] for record in records] == [75, 100]
    assert list(private_temp.iterdir()) == []


def test_a_grading_that_fails_leaves_the_temporary_directory_as_it_found_it(
        private_temp, submissions, tmp_path, monkeypatch):
    def fails(*args, **options):
        raise RuntimeError("the grading failed")

    monkeypatch.setattr(course_kit.grader, "grade_submission", fails)
    with pytest.raises(RuntimeError, match="the grading failed"):
        course_kit.grader.grade_folder(submissions, tmp_path / "results",
                                       course_kit.grader.load_config(), jobs=2,
                                       progress=False, isolation="process",
                                       draws=random.Random(41))
    assert list(private_temp.iterdir()) == []
