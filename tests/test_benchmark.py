"""benchmark.py: the measurement protocol and a quick run of the documented command."""
import time

import pytest

import numpy as np

from AppRenderer import cornell_box_scene, sphere_test_scene
from benchmark import flat_phong, time_renders
from helpers import REPO, render_image, run_python
from PyRT_Integrators import PhongIntegrator


class RecordingIntegrator:
    """Stands in for an integrator: records the worker count of every render() call."""

    def __init__(self):
        self.calls = []

    def render(self, workers=None, samples_per_pixel=1, progress=True):
        self.calls.append(workers)


class FakeClock:
    """A perf_counter that stands still until advanced."""

    def __init__(self):
        self.now = 1000.0

    def __call__(self):
        return self.now


@pytest.fixture
def clock(monkeypatch):
    """A fake time.perf_counter, in place of the real one while the test runs."""
    fake = FakeClock()
    monkeypatch.setattr(time, "perf_counter", fake)
    return fake


class TimedIntegrator(RecordingIntegrator):
    """A stand-in whose renders take the given durations, in turn, on the fake clock."""

    def __init__(self, clock, durations):
        super().__init__()
        self.clock = clock
        self.durations = list(durations)

    def render(self, workers=None, samples_per_pixel=1, progress=True):
        super().render(workers, samples_per_pixel, progress)
        self.clock.now += self.durations.pop(0)


def test_worker_counts_take_turns_and_each_gets_the_median_of_its_times(clock):
    # The renders alternate 1 worker, 2 workers: 1 worker takes 5, 1 and 3 seconds
    # (median 3), 2 workers take 2, 8 and 4 (median 4).
    integrator = TimedIntegrator(clock, [5.0, 2.0, 1.0, 8.0, 3.0, 4.0])
    medians = time_renders(lambda: integrator, [1, 2], repeats=3)
    assert integrator.calls == [1, 2, 1, 2, 1, 2]
    assert medians == [3.0, 4.0]


def test_median_of_an_even_number_of_renders_is_the_mean_of_the_middle_two(clock):
    # 4, 1, 8 and 2 seconds: the middle two are 2 and 4
    integrator = TimedIntegrator(clock, [4.0, 1.0, 8.0, 2.0])
    assert time_renders(lambda: integrator, [1], repeats=4) == [3.0]


def test_every_render_gets_an_integrator_of_its_own():
    made = []

    def make():
        made.append(RecordingIntegrator())
        return made[-1]

    time_renders(make, [1, 2], repeats=2)
    assert [integrator.calls for integrator in made] == [[1], [2], [1], [2]]


def test_quick_run_writes_the_speed_table_and_the_accuracy_plot(tmp_path):
    result = run_python([REPO / "benchmark.py", "--size", "12", "--repeats", "1",
                         "--accuracy-size", "8", "--samples", "1", "4",
                         "--reference-samples", "16", "--out", tmp_path], cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    table = (tmp_path / "benchmark.md").read_text()
    for row in ("Figure 1 | Phong | Cornell box", "Figure 3 | Intersection",
                "StudentPhong | sphere scene", "StudentPhong | Cornell box"):
        assert row in table
    assert "| Flat loop (µs/pixel) | 1 process (µs/pixel) | 1 process / flat loop |" in table
    assert "Phong, Cornell box (Figure 1) | 4 |" in (tmp_path / "speed_accuracy.md").read_text()
    assert (tmp_path / "speed_accuracy.png").stat().st_size > 0


@pytest.mark.parametrize("make", [
    lambda: cornell_box_scene(0.75, 2, width=24, height=20),
    lambda: sphere_test_scene(width=20, height=24)], ids=["figure1", "figure5"])
def test_the_flat_loop_gives_the_image_render_gives(tmp_path, make):
    expected = render_image(PhongIntegrator(str(tmp_path / "img")), make(), workers=1)
    image = flat_phong(make())
    assert expected.any()
    assert np.abs(image - expected).max() <= 1e-15
