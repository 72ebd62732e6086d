"""The students' handout of Practice 1, made from this framework (`python -m course_kit
handout DIR`).

The parts that students write are marked in the finished framework, each block of solution
between two comment lines at the same indentation:

    # ASSIGNMENT 1.2 BEGIN
    ...the solution...
    # ASSIGNMENT 1.2 END

The handout has the course's stub in its place (STUBS below, the 2025-26 handout's), at the
block's indentation. Blocks between "# FRAMEWORK ONLY BEGIN" and "# FRAMEWORK ONLY END" are
left out of the handout entirely: they use machinery that the handout does not ship. An
unbalanced, nested, misspelt or unknown marker stops the kit with the file and the line.

docs/course-kit.md is the teaching assistants' guide.
"""
import re
import textwrap
from pathlib import Path
from typing import NamedTuple, Optional

REPO = Path(__file__).resolve().parent.parent  # the folder of AppRenderer.py
KIT = REPO / "course_kit"
CHECKS = KIT / "checks"
EXPECTED = CHECKS / "expected" / "practice1.npz"

# What students write in, made from the framework by replacing the marked blocks
COURSE_MODULES = ("PyRT_Common.py", "PyRT_Core.py", "PyRT_Integrators.py", "AppRenderer.py")
# What AppRenderer.py needs besides them, shipped as it is
# (pyrt/: only the part of the machinery that the handout's modules import)
SHIPPED_AS_IS = ("pyrt/__init__.py", "pyrt/images.py", "pyrt/environment_maps.py",
                 "pyrt/compare.py", "pyrt/explain.py", "pyrt/explain_picture.py",
                 ".vscode/launch.json", ".vscode/settings.json")
# The course's figures, which pyrt/compare.py finds in references/
FIGURES = ("figure1_phong.png", "figure2_lazy.png", "figure3_intersection.png",
           "figure4_depth.png", "figure4_normal.png", "figure5_phong.png")
# The students' checks: course_kit/checks/<name> goes to tests/<name> in the handout
CHECK_FILES = ("practice1_checks.py", "practice1_render.py", "test_practice1.py")
# The packages the handout needs, with the framework's version bounds
HANDOUT_PACKAGES = ("numpy", "opencv-python-headless", "matplotlib", "pytest")
PYTEST_INI = "[pytest]\ntestpaths = tests\npythonpath = .\naddopts = -ra\n"

# ------------------------------------------------------------------------------------------
# The course's stubs (2025-26 handout)
# ------------------------------------------------------------------------------------------
RENDER_STUB = '''\
def render(self):
    # ASSIGNMENTS 1.1 AND 1.2: YOU MUST CHANGE THIS METHOD.
    # For now it paints every pixel of the image GREEN.
    cam = self.scene.camera
    print("Rendering " + self.get_filename())
    for x in range(cam.width):
        for y in range(cam.height):
            pixel = GREEN
            self.scene.set_pixel(pixel, x, y)
        print(f"\\r  progress: {100 * (x + 1) / cam.width:.0f}%", end="")
    print()
    self.scene.save_image(self.get_filename())
'''
# A body stub: the course's comment, then what the method does until the student writes it
BODY_STUBS = {"any_hit": "return False", "compute_color": "pass", "compute_inv_Q": "pass",
              "compute_z": "pass", "compute_integral_BMC": "pass",
              "compute_estimate_bmc": "pass", "practice3_methods": "pass",
              "practice4_methods": "pass"}
# Where each step's blocks may stand: "class" for whole methods, else the methods whose
# body they are
STEP_PLACES = {"1.1-1.2": {"class"}, "1.2": {"any_hit", "compute_color"},
               "1.3": {"compute_color"}, "1.4": {"compute_color"},
               "2.3": {"compute_color"},  # Practice 2's CMCIntegrator, a stub in Practice 1
               # Practices 3 and 4: GaussianProcess.py's stubs, AppWorkbench.py's BMC
               "3.1": {"compute_inv_Q", "compute_z", "compute_integral_BMC"},
               "3.2": {"compute_estimate_bmc", "practice3_methods"},
               "4.1": {"practice4_methods"}, "4.2": {"practice4_methods"}}
FRAMEWORK_ONLY = "FRAMEWORK ONLY"

MARKER = re.compile(r"(?P<indent>[ ]*)# (?P<kind>ASSIGNMENT (?P<step>\S+)|FRAMEWORK ONLY) "
                    r"(?P<edge>BEGIN|END)")
# Anything that looks like a marker, to catch misspelt ones
LOOKS_LIKE_MARKER = re.compile(r"#\s*(ASSIGNMENTS?\s+\d|FRAMEWORK\s*ONLY)")
DEF = re.compile(r"(?P<indent>[ ]*)(async )?def (?P<name>\w+)\(")


class MarkerError(ValueError):
    """A solution marker that the kit cannot turn into a handout: unbalanced, nested,
    misspelt, of an unknown step, or in a place where that step has no stub."""


def _stub(step, place, indent):
    """The lines that replace a block of `step` standing at `place` (see STEP_PLACES)."""
    if place == "class":
        text = RENDER_STUB
    else:
        text = f"# ASSIGNMENT {step}: PUT YOUR CODE HERE\n{BODY_STUBS[place]}\n"
    return textwrap.indent(text, indent).splitlines(keepends=True)


def _place(lines, index, indent):
    """Where the block starting at lines[index] stands: the name of the method whose body it
    is, or "class" when it stands level with the methods of a class."""
    for line in reversed(lines[:index]):
        found = DEF.match(line)
        if found and len(found["indent"]) < len(indent):
            return found["name"]
        if line.strip() and len(line) - len(line.lstrip(" ")) < len(indent):
            return "class" if line.lstrip().startswith("class ") else line.strip()
    return "module"


class Block(NamedTuple):
    """A marked block of a framework module: FRAMEWORK ONLY or an assignment step, at an
    indentation, from the line of its BEGIN to the line of its END (numbered from 1), and
    where it stands (see STEP_PLACES; None for FRAMEWORK ONLY)."""

    kind: str
    step: Optional[str]
    indent: str
    begin: int
    end: int
    place: Optional[str]


def marked_blocks(source, filename):
    """The Blocks of a framework module's source, in order. Raises MarkerError naming the
    file and line of a marker that is unbalanced, nested, misspelt, of an unknown step or
    in a place where its step has no stub."""
    lines = source.splitlines(keepends=True)
    found, open_block, render_blocks = [], None, 0  # open_block: (kind, step, indent, line)
    for number, line in enumerate(lines, 1):
        where = f"{filename}, line {number}"
        marker = MARKER.fullmatch(line.rstrip("\n"))
        if marker is None:
            if LOOKS_LIKE_MARKER.search(line):
                raise MarkerError(f"{where}: not a marker the kit knows: {line.strip()!r}; "
                                  "markers read '# ASSIGNMENT <step> BEGIN' (or END) and "
                                  "'# FRAMEWORK ONLY BEGIN' (or END)")
            continue
        kind = FRAMEWORK_ONLY if marker["step"] is None else "ASSIGNMENT"
        step, indent = marker["step"], marker["indent"]
        if marker["edge"] == "BEGIN":
            if open_block is not None:
                raise MarkerError(f"{where}: a block begins inside the block begun at line "
                                  f"{open_block[3]}; blocks do not nest")
            if kind == "ASSIGNMENT" and step not in STEP_PLACES:
                raise MarkerError(f"{where}: unknown step {step!r}; the steps are "
                                  + ", ".join(STEP_PLACES))
            open_block = (kind, step, indent, number)
            continue
        if open_block is None or (kind, step, indent) != open_block[:3]:
            begun = "no block is open" if open_block is None else (
                f"the block begun at line {open_block[3]} is "
                f"{open_block[0]} {open_block[1] or ''}".strip()
                + f" at indentation {len(open_block[2])}")
            raise MarkerError(f"{where}: {line.strip()!r} does not close a block: {begun}")
        place = None
        if kind == "ASSIGNMENT":
            place = _place(lines, open_block[3] - 1, indent)
            if place not in STEP_PLACES[step]:
                raise MarkerError(f"{filename}, line {open_block[3]}: a block of step {step} "
                                  f"in {place!r}, where that step has no stub (it may "
                                  "stand in: " + ", ".join(sorted(STEP_PLACES[step])) + ")")
            render_blocks += place == "class"
            if render_blocks > 1:
                raise MarkerError(f"{filename}, line {open_block[3]}: a second block of step "
                                  f"{step}; one block holds all of render's methods")
        found.append(Block(kind, step, indent, open_block[3], number, place))
        open_block = None
    if open_block is not None:
        raise MarkerError(f"{filename}, line {open_block[3]}: the block begun here is never "
                          "closed")
    return found


def strip_solution(source, filename):
    """The handout's version of a framework module: every marked block replaced by its
    stub, or dropped when FRAMEWORK ONLY (with one of the blank lines around it, when both
    are blank). Raises MarkerError as marked_blocks does."""
    lines = source.splitlines(keepends=True)
    out, taken = [], 0  # taken: the lines of source dealt with so far
    for block in marked_blocks(source, filename):
        out += lines[taken:block.begin - 1]
        taken = block.end
        if block.kind == FRAMEWORK_ONLY:
            if out and not out[-1].strip() and taken < len(lines) and not lines[taken].strip():
                out.pop()
        else:
            out += _stub(block.step, block.place, block.indent)
    return "".join(out + lines[taken:])


def _requirements():
    """requirements.txt of the handout: the framework's lines for HANDOUT_PACKAGES."""
    lines = []
    for name in ("requirements.txt", "requirements-dev.txt"):
        for line in (REPO / name).read_text(encoding="utf-8").splitlines():
            package = re.match(r"[A-Za-z0-9_.-]+", line)
            if package and package[0].lower() in HANDOUT_PACKAGES:
                lines.append(line)
    return "# What the handout needs: pip install -r requirements.txt\n" + "\n".join(
        lines) + "\n"


def handout_files():
    """Every file of the handout, {relative path: bytes}, sorted by path."""
    files = {name: strip_solution((REPO / name).read_text(encoding="utf-8"), name).encode()
             for name in COURSE_MODULES}
    files.update({name: (REPO / name).read_bytes() for name in SHIPPED_AS_IS})
    files.update({f"references/{name}": (REPO / "references" / name).read_bytes()
                  for name in FIGURES})
    files.update({f"tests/{name}": (CHECKS / name).read_bytes() for name in CHECK_FILES})
    files["tests/expected/practice1.npz"] = EXPECTED.read_bytes()
    files["requirements.txt"] = _requirements().encode()
    files["pytest.ini"] = PYTEST_INI.encode()
    files["out/.gitkeep"] = b""
    return dict(sorted(files.items()))


def write_handout(directory):
    """Writes the handout into directory, which must be empty or not exist yet."""
    directory = Path(directory)
    if directory.exists() and any(directory.iterdir()):
        raise FileExistsError(f"{directory} is not empty; the handout goes into a new folder")
    for name, content in handout_files().items():
        path = directory / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(content)
    return directory
