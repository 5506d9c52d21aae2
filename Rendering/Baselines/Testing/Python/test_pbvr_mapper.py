"""vtkPBVRVolumeMapper: the wrapped class and its settings, the memory cap (a mesh too big for
it is a clear error), and particles made again only when they must be: when the data, the
opacity, the seed or the sampling change, when the view needs smaller particles, or much larger
ones, or more sets than were made. Bad and unusual input, released resources, resizes and a second
window: test_mapper_robustness.py."""

import math

import numpy as np
import pytest
import vtk

import spt
from spt import render

from robustness_support import ONE, check_clamped_setting, watch, watched_render
from scene_support import bilinear_upsampled, draw_once, window_with

SIZE = (96, 96)


@pytest.mark.parametrize("name, default, low, high", [
    ("RepetitionLevel", 32, 1, 65536),
    ("SubpixelLevel", 1, 1, 8),
    ("MaximumParticleMemory", 2048, 1, 65536),
    ("SamplingMode", 0, 0, 1),
    ("MaximumProgressiveRepetitions", 4096, 1, 1 << 20),
])
def test_settings_have_defaults_and_clamps(name, default, low, high):
    check_clamped_setting(spt.vtkPBVRVolumeMapper(), name, default, low, high)


def test_print_self_lists_every_setting_and_report():
    mapper = spt.vtkPBVRVolumeMapper()
    assert isinstance(mapper, vtk.vtkUnstructuredGridVolumeMapper)
    assert mapper.GetClassName() == "vtkPBVRVolumeMapper"
    mapper.SetSamplingModeToCellAverage()
    mapper.SetSeed(4000000000)
    assert mapper.GetSeed() == 4000000000
    text = str(mapper)
    for setting in ["RepetitionLevel", "SubpixelLevel", "Seed", "SamplingMode: CellAverage",
                    "MaximumParticleMemory", "VectorMode", "VectorComponent",
                    "NumberOfParticles", "NumberOfParticleSets", "ParticleSize",
                    "GenerationCount", "GenerationTime", "NumberOfTetrahedra", "GPUMemorySize",
                    "ScalarMode", "ProgressiveRefinement: Off", "AutoAdjustRepetitions: Off",
                    "LastRepetitionCount", "TimePerRepetition"]:
        assert setting in text


def test_one_tetrahedron_renders_and_reports():
    rendering, messages = watched_render(render.pbvr_mapper(8, seed=1), ONE, size=SIZE)
    report = rendering.report
    assert not messages.errors
    assert rendering.image[..., 3].max() > 0.2
    assert report["particles"] > 100 and report["particle_sets"] == 8
    assert report["gpu_memory"] >= 8 * report["particles"]
    assert report["generation_count"] == 1 and report["generation_seconds"] > 0.0


def test_particles_over_the_memory_cap_are_a_clear_error():
    """1 MiB holds 131072 particles; 512 sets of the default mesh need millions. The error says
    what to change, comes once however often the view is drawn, and nothing is drawn; a larger
    cap then renders."""
    mapper = render.pbvr_mapper(512, seed=1)
    mapper.SetMaximumParticleMemory(1)
    messages = watch(mapper)
    window, _ = window_with(mapper, SIZE[0])
    grid = mapper.GetInput()
    before = grid.GetMTime()
    for _ in range(3):
        window.Render()
    assert len(messages.errors) == 1, messages.errors
    assert "would not fit" in messages.errors[0] and "MaximumParticleMemory" in messages.errors[0]
    assert render.read_rgba(window).max() == 0.0
    assert mapper.GetNumberOfParticles() == 0 and grid.GetMTime() == before
    mapper.SetMaximumParticleMemory(1024)
    window.Render()
    assert len(messages.errors) == 1
    assert mapper.GetNumberOfParticles() > 131072 and mapper.GetGenerationCount() == 1
    assert render.read_rgba(window)[..., 3].max() > 0.2
    # A larger cap keeps the particles; a cap below what they take is an error again.
    mapper.SetMaximumParticleMemory(2048)
    window.Render()
    assert mapper.GetGenerationCount() == 1 and len(messages.errors) == 1
    mapper.SetMaximumParticleMemory(1)
    window.Render()
    assert len(messages.errors) == 2 and "would not fit" in messages.errors[1]
    assert mapper.GetNumberOfParticles() == 0 and render.read_rgba(window).max() == 0.0


class Scene:
    """The default scene in one window, with a property of its own, for counting generations."""

    def __init__(self, repetitions=8):
        self.mapper = render.pbvr_mapper(repetitions, seed=1)
        self.messages = watch(self.mapper)
        self.window, self.renderer = window_with(self.mapper, SIZE[0])
        self.grid = self.mapper.GetInput()
        self.prop = self.renderer.GetVolumes().GetLastProp().GetProperty()
        self.camera = self.renderer.GetActiveCamera()

    def draw(self):
        self.window.Render()
        assert not self.messages.errors
        return render.read_rgba(self.window)

    @property
    def generations(self):
        return self.mapper.GetGenerationCount()


def test_particles_are_made_again_only_when_they_must():
    scene = Scene()
    first = scene.draw()
    assert scene.generations == 1
    assert np.array_equal(scene.draw(), first), "a second render differs"
    # Colors are looked up when drawn: a new color function keeps the particles.
    scene.prop.GetRGBTransferFunction().AddRGBPoint(0.5, 1.0, 0.0, 1.0)
    recolored = scene.draw()
    assert scene.generations == 1 and not np.array_equal(recolored, first)
    # Rotation about the data keeps its nearest point as near.
    scene.camera.Azimuth(50.0)
    scene.camera.Elevation(20.0)
    scene.camera.OrthogonalizeViewUp()
    scene.draw()
    assert scene.generations == 1
    # Closer: smaller pixels need more particles. Slightly farther: the surplus is thinned.
    # Much farther: too many would be thrown away.
    for zoom, generations in ((1.5, 2), (1.0 / 1.2, 2), (0.4, 3)):
        scene.camera.Zoom(zoom)
        scene.draw()
        assert scene.generations == generations, zoom
    # Fewer repetitions draw fewer of the sets; more need new ones.
    sets = scene.mapper.GetNumberOfParticleSets()
    scene.mapper.SetRepetitionLevel(4)
    scene.draw()
    assert scene.generations == 3 and scene.mapper.GetNumberOfParticleSets() == sets
    scene.mapper.SetRepetitionLevel(16)
    scene.draw()
    assert scene.generations == 4 and scene.mapper.GetNumberOfParticleSets() == 16
    for change in (lambda: scene.mapper.SetSeed(2),
                   lambda: scene.mapper.SetSubpixelLevel(2),
                   lambda: scene.mapper.SetSamplingModeToCellAverage(),
                   lambda: scene.prop.GetScalarOpacity().AddPoint(0.5, 0.01),
                   lambda: scene.prop.SetScalarOpacityUnitDistance(0.5),
                   lambda: scene.grid.GetPoints().Modified()):
        count = scene.generations
        change()
        scene.draw()
        assert scene.generations == count + 1
    # A modified property whose opacity samples are the same keeps the particles.
    count = scene.generations
    scene.prop.Modified()
    scene.draw()
    assert scene.generations == count


def test_particle_count_follows_the_optical_model():
    """Twice the attenuation, twice the particles; 2x2 subpixels, four times; each within
    five standard deviations of the Poisson count."""
    scene = Scene(16)
    scene.draw()
    base = scene.mapper.GetNumberOfParticles()
    scene.prop.SetScalarOpacityUnitDistance(0.5 * scene.prop.GetScalarOpacityUnitDistance())
    scene.draw()
    # Var(N2 - 2 N1) = 2 m + 4 m for Poisson counts of means 2 m and m.
    assert abs(scene.mapper.GetNumberOfParticles() - 2 * base) < 5 * math.sqrt(6 * base)
    scene.mapper.SetSubpixelLevel(2)
    scene.draw()
    ratio = scene.mapper.GetNumberOfParticles() / (2 * base)
    assert 3.8 < ratio < 4.2, ratio
    assert scene.mapper.GetGPUMemorySize() >= 8 * scene.mapper.GetNumberOfParticles()


def test_time_budget_and_progressive_refinement_complete_the_image():
    """With a budget of 1 ms a render draws only the sets that fit (at least one); progressive
    refinement adds the next sets at each render until all are drawn, and the image is then
    the image of one render of all of them, bit for bit. A change of the camera starts anew."""
    level = 16
    mapper = render.pbvr_mapper(level, seed=1)
    mapper.AutoAdjustRepetitionsOn()
    mapper.AutoAdjustSampleDistancesOff()  # every pixel: the image of one render of them all
    mapper.ProgressiveRefinementOn()
    window, renderer = window_with(mapper, SIZE[0])
    window.Render()  # measures the time of a set
    assert mapper.GetLastRepetitionCount() == level
    assert mapper.GetTimePerRepetition() > 0.0
    renderer.GetActiveCamera().Azimuth(10.0)
    window.SetDesiredUpdateRate(1000.0)
    counts = []
    for _ in range(level):
        window.Render()
        counts.append(mapper.GetLastRepetitionCount())
        if counts[-1] == level:
            break
    assert 1 <= counts[0] < level, f"the budget drew {counts[0]} of {level} sets"
    assert counts == sorted(set(counts)) and counts[-1] == level, counts
    progressive = render.read_rgba(window)
    assert progressive[..., 3].max() > 0.2

    full_window, full_renderer = window_with(render.pbvr_mapper(level, seed=1), SIZE[0])
    full_renderer.SetActiveCamera(renderer.GetActiveCamera())
    full_renderer.ResetCameraClippingRange()
    renderer.ResetCameraClippingRange()
    full_window.Render()
    assert np.array_equal(render.read_rgba(full_window), progressive)
    window.Finalize()
    full_window.Finalize()


def test_a_sample_distance_of_two_draws_the_sets_of_half_the_pixels_interpolated():
    """At sample distance 2 in a viewport of 2n x 2n pixels PBVR draws the particles of an
    n x n viewport (their size and number follow the image's pixels) and the resolve
    interpolates them bilinearly."""
    fine_mapper = render.pbvr_mapper(8, seed=3)
    fine_mapper.AutoAdjustSampleDistancesOff()
    fine_mapper.SetImageSampleDistance(2.0)
    fine = draw_once(window_with(fine_mapper, 2 * SIZE[0])[0])
    coarse = draw_once(window_with(render.pbvr_mapper(8, seed=3), SIZE[0])[0])
    assert coarse[..., 3].max() > 0.2, "an empty image"
    assert np.abs(fine - bilinear_upsampled(coarse, 2)).max() <= 1.0 / 255.0 + 1e-6


def test_with_the_time_budget_interactive_sets_have_fewer_pixels():
    mapper = render.pbvr_mapper(4, seed=1)
    mapper.AutoAdjustRepetitionsOn()
    window, _ = window_with(mapper, SIZE[0])
    window.Render()
    assert mapper.GetImageSampleDistance() == 1.0
    window.SetDesiredUpdateRate(1.0e6)  # 1 us: not even one set, at any sample distance
    for _ in range(3):
        window.Render()
    assert mapper.GetTimePerRepetition() > 1.0e-6
    assert mapper.GetImageSampleDistance() == mapper.GetMaximumImageSampleDistance() == 4.0
    assert render.read_rgba(window)[..., 3].max() > 0.2, "an empty interactive image"
    window.SetDesiredUpdateRate(0.0001)
    window.Render()
    assert mapper.GetImageSampleDistance() == 1.0
    window.Finalize()
