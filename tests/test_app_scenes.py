"""AppRenderer.py's scenes: importing it renders nothing, and its scenes hold the course's
numbers, the 2025-26 handout's sphere scene included."""
import math
import shutil

import cv2
import numpy as np
import pytest

import AppRenderer
from AppRenderer import sphere_test_scene
from helpers import REPO, as_tuple, render_image, rgb, run_python
from pyrt.compare import compare_with_reference
from pyrt.environment_maps import sky_map
from PyRT_Core import Parallelogram, Sphere
from PyRT_Integrators import PhongIntegrator


def albedo(primitive):
    """The diffuse colour of a Lambertian primitive: kd * pi."""
    return pytest.approx([channel * math.pi for channel in rgb(primitive.get_BRDF().kd)],
                         abs=1e-12)


def assert_parallelogram(obj, point, s1, s2):
    assert isinstance(obj, Parallelogram)
    assert (as_tuple(obj.point), as_tuple(obj.s1), as_tuple(obj.s2)) == (point, s1, s2)


def file_states(folder):
    return {path.name: path.stat().st_mtime_ns for path in folder.iterdir()}


# ------------------------------------------------------------------------------------------
# Importing
# ------------------------------------------------------------------------------------------
def test_importing_app_renderer_renders_and_writes_nothing(tmp_path):
    out = REPO / "out"
    before = file_states(out)
    result = run_python(["-c", "import AppRenderer; print('imported')"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout == "imported\n"
    assert list(tmp_path.iterdir()) == []
    assert file_states(out) == before


# ------------------------------------------------------------------------------------------
# The scenes' numbers, from the spec
# ------------------------------------------------------------------------------------------
def test_sphere_test_scene_has_the_course_numbers():
    scene = AppRenderer.sphere_test_scene()
    assert rgb(scene.i_a) == (0.5, 0.5, 0.5)
    sphere, floor = scene.object_list
    assert isinstance(sphere, Sphere)
    assert (as_tuple(sphere.origin), sphere.radius) == ((0, 0, -5), 2)
    assert albedo(sphere) == (0.8, 0.8, 0.8)
    assert_parallelogram(floor, (-4, -2, -1), (8, 0, 0), (0, 0, -8))
    assert albedo(floor) == (0.2, 0.8, 0.2)
    assert all(rgb(obj.emission) == (0, 0, 0) for obj in scene.object_list)
    [light] = scene.pointLights
    assert (as_tuple(light.pos), rgb(light.intensity)) == ((0, 5, 0), (80, 80, 80))
    camera = scene.camera
    assert (camera.width, camera.height) == (500, 500)
    assert camera.vertical_fov == pytest.approx(math.radians(60))
    assert scene.rendered_image.shape == (500, 500, 3)


def test_sphere_test_scene_area_light_replaces_the_point_light():
    scene = AppRenderer.sphere_test_scene(areaLS=True)
    assert scene.pointLights == []
    assert len(scene.object_list) == 3
    light = scene.object_list[2]
    assert_parallelogram(light, (-4, 6, -1), (8, 0, 0), (0, 0, -8))
    assert rgb(light.emission) == (3.5, 3.5, 3.5)
    assert rgb(light.get_BRDF().kd) == (0, 0, 0)


def test_sphere_test_scene_environment_map_is_the_courses_from_the_current_folder(
        monkeypatch, tmp_path):
    # the course's relative path, env_maps/arch_nozero.hdr, read in grey as the course reads
    # it: OpenCV's own grey reading of the file, in all three channels
    write_env_map(tmp_path / "env_maps" / "arch_nozero.hdr")
    monkeypatch.chdir(tmp_path)
    scene = AppRenderer.sphere_test_scene(use_env_map=True)
    assert np.array_equal(scene.env_map.env_map_hdr, opencv_grey(tmp_path / ENV_MAP))
    assert AppRenderer.sphere_test_scene().env_map is None


def test_without_the_courses_map_one_line_says_where_it_comes_from_and_the_sky_stands_in(
        monkeypatch, tmp_path, capsys):
    # the course's map is the course's, not PyRT's to ship: where neither the current folder
    # nor AppRenderer.py's has it, PyRT's own sky is used instead, and one line says so
    monkeypatch.chdir(tmp_path)
    assert not (REPO / ENV_MAP).exists()
    scene = AppRenderer.sphere_test_scene(use_env_map=True)
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 1
    assert "env_maps/ folder of the course's base code" in lines[0]
    assert "PyRT's own sky map stands in" in lines[0]
    assert np.array_equal(scene.env_map.env_map_hdr, sky_map())


def test_cornell_box_scene_has_the_course_numbers():
    # dist 0.75, side 2: z_far = -2.75, ll = (-1, -1, -2.75), ur = (1, 1, -2.75).
    scene = AppRenderer.cornell_box_scene(0.75, 2)
    assert rgb(scene.i_a) == (1, 1, 0.3)
    sphere, back, floor, left, ceiling, right = scene.object_list
    assert isinstance(sphere, Sphere)
    assert (as_tuple(sphere.origin), sphere.radius) == ((0, 0, -1.75), 0.25)
    assert albedo(sphere) == (0.2, 0.2, 0.7)
    ll, ur = (-1, -1, -2.75), (1, 1, -2.75)
    assert_parallelogram(back, ll, (2, 0, 0), (0, 2, 0))
    assert_parallelogram(floor, ll, (2, 0, 0), (0, 0, 2))
    assert_parallelogram(left, ll, (0, 2, 0), (0, 0, 2))
    assert_parallelogram(ceiling, ur, (-2, 0, 0), (0, 0, 2))
    assert_parallelogram(right, ur, (0, -2, 0), (0, 0, 2))
    for wall in (back, floor, ceiling):
        assert albedo(wall) == (0.8, 0.8, 0.8)
    assert albedo(left) == (0.7, 0.2, 0.2)
    assert albedo(right) == (0.2, 0.7, 0.2)
    # Lights at y = side/2 - 0.5 = 0.5, z = -(dist + side/2) = -1.75, x = 0, -0.5, 0.5.
    assert [as_tuple(light.pos) for light in scene.pointLights] == [
        (0, 0.5, -1.75), (-0.5, 0.5, -1.75), (0.5, 0.5, -1.75)]
    assert all(rgb(light.intensity) == (0.5, 0.5, 0.5) for light in scene.pointLights)
    camera = scene.camera
    assert (camera.width, camera.height) == (500, 500)
    assert camera.vertical_fov == pytest.approx(math.radians(70))


def test_cornell_box_area_light_is_a_square_under_the_ceiling():
    # Corner (-side/4, side/2 - 0.0001, -(dist + side/4)) = (-0.5, 0.9999, -1.25).
    scene = AppRenderer.cornell_box_scene(0.75, 2, areaLS=True)
    assert scene.pointLights == []
    assert len(scene.object_list) == 7
    light = scene.object_list[6]
    assert_parallelogram(light, (-0.5, 1 - 0.0001, -1.25), (1, 0, 0), (0, 0, -1))
    assert rgb(light.emission) == (1, 1, 1)
    assert rgb(light.get_BRDF().kd) == (0, 0, 0)


# ------------------------------------------------------------------------------------------
# The 2025-26 handout's sphere_scene(envMap=None)
# ------------------------------------------------------------------------------------------
ENV_MAP = "env_maps/arch_nozero.hdr"  # the course's map, as its scenes name it


def write_env_map(path):
    """Writes a 1 x 2 latitude-longitude map at path: left texel red (2, 0, 0), right texel
    blue (0, 0, 4)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    cv2.imwrite(str(path), np.array([[[0, 0, 2], [4, 0, 0]]], dtype=np.float32))  # BGR


def opencv_grey(path):
    """The map at path as the course reads it: OpenCV's grey reading (IMREAD_ANYDEPTH),
    repeated in three channels."""
    grey = cv2.imread(str(path), flags=cv2.IMREAD_ANYDEPTH)
    return np.repeat(grey[:, :, None], 3, axis=2)


@pytest.fixture(scope="session")
def sphere_test_scene_phong(tmp_path_factory):
    """Phong on sphere_test_scene() at its own 500 x 500 pixels: the objects, their
    materials, the light, the ambient light and the camera all show in this image."""
    folder = tmp_path_factory.mktemp("sphere_test_scene")
    return render_image(PhongIntegrator(str(folder / "img")), sphere_test_scene())


@pytest.mark.parametrize("make_scene", [lambda: AppRenderer.sphere_scene(),
                                        lambda: AppRenderer.sphere_scene(envMap=None)],
                         ids=["sphere_scene()", "sphere_scene(envMap=None)"])
def test_sphere_scene_renders_the_image_of_sphere_test_scene(tmp_path, make_scene,
                                                             sphere_test_scene_phong):
    scene = make_scene()
    assert scene.env_map is None
    image = render_image(PhongIntegrator(str(tmp_path / "img")), scene)
    assert image.shape == (500, 500, 3)
    assert np.array_equal(image, sphere_test_scene_phong)


def test_sphere_scene_sets_the_environment_map_at_a_path_from_the_script_folder(
        tmp_path, monkeypatch):
    write_env_map(tmp_path / "env_maps" / "arch_nozero.hdr")
    monkeypatch.chdir(tmp_path)  # the handout's relative path, from the student's folder
    scene = AppRenderer.sphere_scene(envMap="env_maps/arch_nozero.hdr", width=20, height=20)
    # 0.299 of red 2 and 0.114 of blue 4, to the rounding of the file's 8-bit mantissas
    assert scene.env_map.env_map_hdr[0, :, 0] == pytest.approx([0.598, 0.456], rel=1e-2)
    assert np.array_equal(scene.env_map.env_map_hdr, opencv_grey(tmp_path / ENV_MAP))
    # the rest is the sphere scene: Phong, which never looks at the map, sees no difference
    expected = render_image(PhongIntegrator(str(tmp_path / "expected")),
                            sphere_test_scene(width=20, height=20))
    assert np.array_equal(render_image(PhongIntegrator(str(tmp_path / "img")), scene),
                          expected)


@pytest.mark.parametrize("relative", [True, False], ids=["relative", "absolute"])
def test_sphere_scene_refuses_a_missing_environment_map_naming_its_path(tmp_path,
                                                                       monkeypatch,
                                                                       relative):
    # any map but the course's own, which has a stand-in (above)
    monkeypatch.chdir(tmp_path)
    missing = (tmp_path / "env_maps" / "other.hdr").resolve()
    given = "env_maps/other.hdr" if relative else str(missing)
    with pytest.raises(FileNotFoundError) as error:
        AppRenderer.sphere_scene(given)  # the handout's first argument, envMap
    message = str(error.value)
    assert repr(str(missing)) in message
    assert "latitude-longitude .hdr image" in message


def test_a_2025_26_student_script_runs_unchanged_and_renders_figure_3(tmp_path):
    # tests/student/render_2025_26.py imports sphere_scene, builds its rays with
    # Ray(direction=...) in its own loop over x and then y, and saves to the handout's
    # '.\\out\\' + 'rendered_image', which names the folder out on Windows, and on Linux
    # and macOS too: there get_filename() gives it with their separators, so that the
    # script reads its PNG back by the same name.
    shutil.copy(REPO / "tests" / "student" / "render_2025_26.py", tmp_path)
    write_env_map(tmp_path / "env_maps" / "arch_nozero.hdr")
    result = run_python(["render_2025_26.py"], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    name = "./out/rendered_image_Intersection.png"  # DIRECTORY + FILENAME + suffix
    assert f"Read back {name}: (500, 500, 3)" in result.stdout
    assert "Progress: 100%" in result.stdout
    assert compare_with_reference(tmp_path / name, "figure3_intersection").matches


# ------------------------------------------------------------------------------------------
