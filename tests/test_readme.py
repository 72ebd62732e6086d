"""The README as a first read: short enough to be read through, and every link in it (and
in the guide it sends readers on to) leads to a file of the repository, and to a heading
of it when the link names one."""
import re

import pytest

from helpers import REPO

README = REPO / "README.md"
GUIDE = REPO / "docs" / "working-with-pyrt.md"  # where the README sends a reader on
# A first read; the detail lives in docs/
MAX_README_BYTES = 12_000
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
FENCE = re.compile(r"^```.*?^```", re.MULTILINE | re.DOTALL)


def anchor(heading):
    """The anchor of a Markdown heading as GitHub makes it: lower case, spaces to hyphens,
    punctuation left out."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def anchors(text):
    """The anchors of the headings of a Markdown text, outside its code blocks."""
    return {anchor(line.lstrip("#")) for line in FENCE.sub("", text).splitlines()
            if line.startswith("#")}


def broken_links(path):
    """The relative links of the Markdown file at path whose file or heading is missing."""
    text = path.read_text(encoding="utf-8")
    broken = []
    for target in LINK.findall(FENCE.sub("", text)):
        if re.match(r"[a-z]+:", target):  # https:, mailto:: not a file of the repository
            continue
        name, _, heading = target.partition("#")
        linked = (path.parent / name).resolve() if name else path
        if not linked.exists():
            broken.append(target)
        elif heading and linked.suffix == ".md" and heading not in anchors(
                linked.read_text(encoding="utf-8")):
            broken.append(target)
    return broken


def test_the_readme_is_a_first_read_under_12_kb():
    assert len(README.read_bytes()) < MAX_README_BYTES


@pytest.mark.parametrize("page", [README, GUIDE], ids=lambda page: page.name)
def test_every_relative_link_leads_to_a_file_and_heading_that_exist(page):
    assert LINK.findall(page.read_text(encoding="utf-8"))  # the page has links at all
    assert broken_links(page) == []


def test_headings_give_githubs_anchors():
    assert anchor(" Why is this pixel this colour?") == "why-is-this-pixel-this-colour"
    assert anchor(" Writing an integrator: good to know") == (
        "writing-an-integrator-good-to-know")
    assert anchor(" Compare your images with the course's") == (
        "compare-your-images-with-the-courses")


def test_a_link_to_a_missing_file_or_heading_is_found(tmp_path):
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "guide.md").write_text("# Guide\n\n## First steps\n")
    page = tmp_path / "README.md"
    page.write_text("# Title\n\n## Options\n\n"
                    "[a](docs/guide.md) [b](docs/guide.md#first-steps) [c](#options)\n"
                    "![d](docs/missing.png) [e](docs/guide.md#last-steps) [f](#usage)\n"
                    "[g](https://example.org/x)\n"
                    "```\n[h](docs/in_code.md)\n```\n")
    assert broken_links(page) == ["docs/missing.png", "docs/guide.md#last-steps", "#usage"]
