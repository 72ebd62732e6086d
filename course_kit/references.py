"""The expected data of the students' checks, rendered by the finished framework into
course_kit/checks/expected/practice1.npz (by `python -m course_kit expected`, and only on purpose: when
the framework's images change by an intended change, with the reason in the commit).

For each image of practice1_checks.IMAGES, at practice1_checks.SIZE pixels:
- <name>: the image that the framework's own render() makes, the expected image;
- <name>.seam_pixels and <name>.seam_colors: the seams, (y, x) of each pixel whose colour
  changes when its ray leaves the pixel's centre by SEAM_WIDTH of a pixel (up, down, left
  or right), or, in a Phong image, when its shadow rays ignore the first EPSILON of their
  way as the course's Ray does, or when the course's own arithmetic (course_kit/arithmetic.py)
  traces its ray, with each shadow ray that students write (SHADOW_RAYS); and for each
  such pixel the colours of all those rays;
- <name>.mistake.<mistake>: the image of a known mistake (practice1_checks.LIKELY): rays
  through the pixels' corners for every ray-traced image, and the mistakes of
  practice1_checks.RENDERED_MISTAKES, rendered by the variants of the framework's
  integrators below.

The file is written the same, byte for byte, whenever the framework's images are.
"""
import contextlib
import io
import os
import sys
import tempfile
import threading
import zipfile
from collections.abc import Mapping
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent / "checks"))

import practice1_checks as checks  # noqa: E402  (found through the line above)
import practice1_render as render  # noqa: E402
import PyRT_Integrators  # noqa: E402
from course_kit.arithmetic import with_course_arithmetic  # noqa: E402
from PyRT_Common import BLACK, EPSILON, Ray, RGBColor  # noqa: E402
from pyrt.course_model import PhongParts, never_blocked  # noqa: E402

# The rays of a seam pixel's alternatives: its centre moved by SEAM_WIDTH of a pixel
SEAM_OFFSETS = [(checks.SEAM_WIDTH, 0.0), (-checks.SEAM_WIDTH, 0.0),
                (0.0, checks.SEAM_WIDTH), (0.0, -checks.SEAM_WIDTH)]
CORNER = (-0.5, -0.5)  # from a pixel's centre to its top-left corner
ZIP_DATE = (1980, 1, 1, 0, 0, 0)  # the earliest a zip file holds: no date of writing


# ------------------------------------------------------------------------------------------
# The variants of the framework's integrators that make the mistakes' images
# ------------------------------------------------------------------------------------------
class UnclampedDepth(PyRT_Integrators.DepthIntegrator):
    """Depth without the max(.., 0): the grey 1 - hit_distance / max_depth, negative beyond
    max_depth."""

    def compute_color(self, ray):
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        c = 1.0 - hit.hit_distance / self.max_depth
        return RGBColor(c, c, c)


class UnmappedNormals(PyRT_Integrators.NormalIntegrator):
    """Normal without the mapping to [0, 1]: the normal itself as the colour."""

    def compute_color(self, ray):
        hit = self.scene.closest_hit(ray)
        if not hit.has_hit:
            return BLACK
        n = hit.normal
        return RGBColor(n.x, n.y, n.z)


def blocked_beyond_t_min(scene, hit, wi, r):
    """A shadow ray Ray(hit point, wi, r), which ignores the first EPSILON (its t_min)."""
    return scene.any_hit(Ray(hit.hit_point, wi, r))


def blocked_from_lifted_start(scene, hit, wi, r):
    """A shadow ray that starts EPSILON along the normal."""
    return scene.any_hit(Ray(hit.hit_point + hit.normal * EPSILON, wi, r))


def blocked_nearer_than_the_light(scene, hit, wi, r):
    """The closest hit towards the light, nearer than the light."""
    towards = scene.closest_hit(Ray(hit.hit_point, wi))
    return towards.has_hit and towards.hit_distance < r


def blocked_by_another_object(scene, hit, wi, r):
    """The closest hit on the way to the light, on an object other than the one lit."""
    towards = scene.closest_hit(Ray(hit.hit_point, wi, r))
    return towards.has_hit and towards.primitive_index != hit.primitive_index


# The shadow rays that students write (PYRT_SPEC.md, "What students hand in")
SHADOW_RAYS = (blocked_beyond_t_min, blocked_from_lifted_start,
               blocked_nearer_than_the_light, blocked_by_another_object)


class PhongVariant(PyRT_Integrators.PhongIntegrator):
    """Phong as the assignment describes it, written the way a student writes it (a shadow
    ray per light, one of SHADOW_RAYS), with parts that can be left out: the ambient
    term, the shadows; and a falloff of 1/r^falloff, of which the course's is 2. It is
    the course's own compute_color on the scene with those parts changed
    (pyrt.course_model.PhongParts)."""

    def __init__(self, filename_, ambient=True, shadows=True, falloff=2,
                 blocked=blocked_beyond_t_min):
        super().__init__(filename_)
        self.ambient, self.shadows, self.falloff = ambient, shadows, falloff
        self.blocked = blocked

    def compute_color(self, ray):
        scene = self.scene
        blocked = self.blocked if self.shadows else never_blocked
        self.scene = PhongParts(scene, blocked, self.ambient, falloff=self.falloff)
        try:
            return super().compute_color(ray)
        finally:
            self.scene = scene


def mistake_integrator(mistake, filename):
    """The integrator that makes the image of a mistake of RENDERED_MISTAKES."""
    return {
        "unclamped_depth": lambda: UnclampedDepth(filename, 5),
        "unmapped_normals": lambda: UnmappedNormals(filename),
        "no_ambient": lambda: PhongVariant(filename, ambient=False),
        "no_shadows": lambda: PhongVariant(filename, shadows=False),
        "no_inverse_square": lambda: PhongVariant(filename, falloff=0),
        "inverse_distance": lambda: PhongVariant(filename, falloff=1),
    }[mistake]()


# ------------------------------------------------------------------------------------------
# Rendering
# ------------------------------------------------------------------------------------------
def framework_image(name, folder, draw=render.PUBLISHED):
    """The expected image of IMAGES[name] at draw: the framework's integrator and its
    render()."""
    integrator = render.make_integrator(name, str(Path(folder) / name), PyRT_Integrators)
    scene = render.scene_of(name, draw)
    integrator.add_scene(scene)
    integrator.render(workers=1, progress=False)
    return np.array(scene.rendered_image, dtype=float)


def course_shadow_rays(scene):
    """scene, whose any_hit now ignores the first EPSILON of every ray, as the course's Ray
    does by default (its t_min): what a shadow ray Ray(hit point, wi, r) sees."""
    plain = scene.any_hit

    def any_hit(ray):
        return plain(Ray(ray.o, ray.d, ray.t_max, max(ray.t_min, EPSILON)))

    scene.any_hit = any_hit
    return scene


def students_integrators(name, folder):
    """The integrators of IMAGES[name] as students write them: for Phong one per shadow
    ray of SHADOW_RAYS, else the framework's own."""
    if render.RENDERED[name][1] == "PhongIntegrator":
        return [PhongVariant(str(Path(folder) / name), blocked=blocked)
                for blocked in SHADOW_RAYS]
    return [render.make_integrator(name, str(Path(folder) / name), PyRT_Integrators)]


def seams(name, expected, folder, draw=render.PUBLISHED, pixels=None):
    """(seam_pixels, seam_colors) of IMAGES[name] at draw, as the module docstring says,
    among pixels ((y, x) pairs; None: all)."""
    integrator_name = render.RENDERED[name][1]
    if integrator_name == "LazyIntegrator":
        return np.zeros((0, 2), np.int64), np.zeros((0, 0, 3))

    def scene():
        return render.scene_of(name, draw)

    integrator = render.make_integrator(name, str(Path(folder) / name), PyRT_Integrators)
    alternatives = [render.traced_image(integrator, scene(), offset, pixels)
                    for offset in SEAM_OFFSETS]
    if integrator_name == "PhongIntegrator":
        alternatives.append(render.traced_image(integrator, course_shadow_rays(scene()),
                                                pixels=pixels))
    alternatives += [render.traced_image(student, with_course_arithmetic(scene()),
                                         pixels=pixels)
                     for student in students_integrators(name, folder)]
    stack = np.stack(alternatives)  # (K, height, width, 3)
    differs = np.zeros(expected.shape[:2], bool)
    for alternative in stack:
        differs |= ~checks.close(alternative, expected, checks.SEAM_TOLERANCE)
    if pixels is not None:  # the pixels not traced are no seams
        asked = np.zeros(expected.shape[:2], bool)
        asked[tuple(np.array(pixels, dtype=np.int64).reshape(-1, 2).T)] = True
        differs &= asked
    found = np.argwhere(differs)
    return found, stack[:, found[:, 0], found[:, 1]].transpose(1, 0, 2)


def mistake_image(name, mistake, folder, draw=render.PUBLISHED):
    """The image of IMAGES[name] at draw with a known mistake: corner_rays, or one of
    RENDERED_MISTAKES[name]."""
    if mistake == "corner_rays":
        integrator = render.make_integrator(name, str(Path(folder) / name), PyRT_Integrators)
        return render.traced_image(integrator, render.scene_of(name, draw), CORNER)
    return render.traced_image(mistake_integrator(mistake, str(Path(folder) / mistake)),
                               render.scene_of(name, draw))


def mistakes_of(name):
    """The known mistakes whose images the expected data of IMAGES[name] holds."""
    if name == "lazy":
        return ()
    return ("corner_rays",) + checks.RENDERED_MISTAKES.get(name, ())


def expected_arrays():
    """Every array of course_kit/checks/expected/practice1.npz, by key."""
    arrays = {}
    with tempfile.TemporaryDirectory() as folder:
        for name in checks.IMAGES:
            expected = arrays[name] = framework_image(name, folder)
            arrays[f"{name}.seam_pixels"], arrays[f"{name}.seam_colors"] = seams(
                name, expected, folder)
            for mistake in mistakes_of(name):
                arrays[f"{name}.mistake.{mistake}"] = mistake_image(name, mistake, folder)
    return arrays


class GradingData(Mapping):
    """The expected data of a draw made at grading time, by the finished framework, in
    the form of the stored one (practice1_checks reads both): the expected images made at
    once, the mistakes' images when first asked for, and the seams only at the pixels a
    judged image gets wrong (seams_at), where they matter. The framework's renders go into
    folder, which belongs to the grading (and goes with it). Safe for the grader's
    threads."""

    def __init__(self, draw, folder):
        self.draw = draw
        self._arrays = {}
        self._seams = {}  # (name, y, x) -> the colours of the seam there, or None
        self._lock = threading.Lock()
        self._folder = str(folder)
        os.makedirs(self._folder, exist_ok=True)
        with contextlib.redirect_stdout(io.StringIO()):  # render() says where it saved
            for name in checks.IMAGES:
                self._arrays[name] = framework_image(name, self._folder, draw)
        self._keys = list(checks.IMAGES) + [f"{name}.mistake.{mistake}"
                                            for name in checks.IMAGES
                                            for mistake in mistakes_of(name)]

    def __getitem__(self, key):
        if key not in self._keys:
            raise KeyError(key)
        with self._lock:
            if key not in self._arrays:
                name, _, mistake = key.partition(".mistake.")
                self._arrays[key] = mistake_image(name, mistake, self._folder, self.draw)
            return self._arrays[key]

    def __iter__(self):
        return iter(self._keys)

    def __len__(self):
        return len(self._keys)

    def seams_at(self, name, wrong):
        """[((y, x), the colours its rays may see)] of the seam pixels among those where
        the mask `wrong` is True."""
        with self._lock:
            todo = [(int(y), int(x)) for y, x in np.argwhere(wrong)
                    if (name, int(y), int(x)) not in self._seams]
            if todo:
                found, colours = seams(name, self._arrays[name], self._folder, self.draw,
                                       todo)
                self._seams.update(dict.fromkeys(((name, y, x) for y, x in todo)))
                self._seams.update(((name, int(y), int(x)), c)
                                   for (y, x), c in zip(found, colours))
            return [((int(y), int(x)), self._seams[(name, int(y), int(x))])
                    for y, x in np.argwhere(wrong)
                    if self._seams[(name, int(y), int(x))] is not None]


def npz_bytes(arrays):
    """arrays as an .npz file (what np.load reads), the same bytes for the same arrays:
    sorted by key, compressed, with no date."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        for key in sorted(arrays):
            member = io.BytesIO()
            np.save(member, arrays[key], allow_pickle=False)
            info = zipfile.ZipInfo(key + ".npy", date_time=ZIP_DATE)
            info.compress_type = zipfile.ZIP_DEFLATED
            archive.writestr(info, member.getvalue())
    return buffer.getvalue()


def framework_story(name, x, y, draw=render.PUBLISHED):
    """The finished framework's history of pixel (x, y) of IMAGES[name] at draw
    (pyrt/explain.py), as text: what the feedback page shows beside a student's story of
    the same pixel."""
    integrator = render.make_integrator(name, "unused", PyRT_Integrators)
    integrator.add_scene(render.scene_of(name, draw))
    return str(integrator.explain_pixel(x, y))


def write_expected(path):
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(npz_bytes(expected_arrays()))
    return path
