"""benchmarks/: the measurement protocol, the flat loop and quick runs of the documented
commands."""
import time

import pytest

import numpy as np

from AppRenderer import cornell_box_scene, sphere_test_scene
from benchmarks.accuracy import Point, equal_time_error, target_checks
from benchmarks.flat_loop import flat_phong
from benchmarks.timing import paired_ratio, time_renders
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


def test_ratios_are_medians_of_the_ratios_within_each_turn():
    # Turn by turn, a takes 2, 9 and 3 seconds while b takes 1, 3 and 3: the ratios of the
    # turns are 2, 3 and 1 (median 2), where the ratio of the medians would be 3/3 = 1.
    assert paired_ratio([2.0, 9.0, 3.0], [1.0, 3.0, 3.0]) == 2.0


def test_every_render_gets_an_integrator_of_its_own():
    made = []

    def make():
        made.append(RecordingIntegrator())
        return made[-1]

    time_renders(make, [1, 2], repeats=2)
    assert [integrator.calls for integrator in made] == [[1], [2], [1], [2]]


def test_quick_run_writes_the_speed_table_with_its_targets(tmp_path):
    result = run_python(["-m", "benchmarks.speed", "--size", "12", "--repeats", "1",
                         "--out", tmp_path], cwd=REPO)
    assert result.returncode == 0, result.stderr
    table = (tmp_path / "benchmark.md").read_text()
    for row in ("| Figure 1 | Phong | Cornell box |", "| Figure 3 | Intersection |",
                "|  | Phong, own code | Cornell box |", "|  | Phong, own code | sphere scene |"):
        assert row in table
    assert "| Flat loop (µs/pixel) | 1 process (µs/pixel) | 1 process / flat loop |" in table
    assert "Phong, Cornell box, 1 process / flat loop: " in table
    assert "(target at most 1.25: " in table and "(target at most 2.0: " in table
    assert "| 1000 | " in table and "1000 tiles / 100 tiles: " in table


def test_quick_run_writes_the_accuracy_tables_and_plot(tmp_path):
    result = run_python(["-m", "benchmarks.accuracy", "--size", "8", "--repeats", "1",
                         "--samples", "1", "4", "--adaptive-samples", "4",
                         "--reference-samples", "16", "--out", tmp_path], cwd=REPO)
    assert result.returncode == 0, result.stderr
    accuracy = (tmp_path / "speed_accuracy.md").read_text()
    assert "Phong, Cornell box (Figure 1) | uniform | 4 |" in accuracy
    assert "Phong, Cornell box (Figure 1) | adaptive | 4 |" in accuracy
    assert "## Targets" in accuracy
    assert (tmp_path / "speed_accuracy.png").stat().st_size > 0


def uniform_points(*time_and_error):
    return [Point("uniform", n, t, e, 0.0, e) for n, (t, e) in enumerate(time_and_error)]


def test_equal_time_error_interpolates_the_uniform_curve_on_log_log_axes():
    # Between (1 s, 0.1) and (4 s, 0.025) the line on log-log axes has slope -1: at 2 s,
    # the error is 0.05; outside 1 - 4 s there is no uniform point to compare with.
    uniform = uniform_points((4.0, 0.025), (1.0, 0.1))
    assert equal_time_error(uniform, 2.0) == pytest.approx(0.05, rel=1e-12)
    assert equal_time_error(uniform, 0.5) != equal_time_error(uniform, 0.5)  # NaN


def test_targets_compare_adaptive_16_with_uniform_16_and_at_equal_time():
    points = [Point("uniform", 1, 1.0, 0.1, 0.0, float("nan")),
              Point("uniform", 16, 4.0, 0.025, 0.0, 0.03),
              Point("adaptive", 16, 0.5, 0.026, 0.0, 0.013),
              Point("adaptive", 64, 2.0, 0.01, 0.0, 0.01)]
    errors, times, equal_time, estimate = target_checks(points)
    assert errors == "1.040 (met)"    # 0.026 / 0.025
    assert times == "0.125 (met)"     # 0.5 s / 4 s
    # at 0.5 s there is no uniform point; at 2 s uniform has 0.05 (above): 5 times 0.01
    assert equal_time == "N=16: n/a, N=64: 5.0 (met)"
    assert estimate == "0.50 - 1.20 (met)"  # 0.013 / 0.026 and 0.03 / 0.025


@pytest.mark.parametrize("make", [
    lambda: cornell_box_scene(0.75, 2, width=24, height=20),
    lambda: sphere_test_scene(width=20, height=24)], ids=["figure1", "figure5"])
def test_the_flat_loop_gives_the_image_render_gives(tmp_path, make):
    expected = render_image(PhongIntegrator(str(tmp_path / "img")), make(), workers=1)
    image = flat_phong(make())
    assert expected.any()
    assert np.array_equal(image, expected)
