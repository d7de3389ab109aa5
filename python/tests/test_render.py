"""tessera.Scene.render against the command line: the same options give the same pixels, bit for
bit, and every layer has the EXR's name, shape and type."""

import os
import subprocess
import sys

import numpy as np
import pytest

import tessera
from conftest import scene_path

BOX = scene_path("khronos/Box/glTF-Binary/Box.glb")
VARIANTS = scene_path("material-variants/material-variants.gltf")
ANIMATED = scene_path("khronos/BoxAnimated/glTF-Binary/BoxAnimated.glb")


def cli_layers(run_cli, tmp_path, scene, args):
    out = tmp_path / "cli.exr"
    done = run_cli("render", scene, "-q", "-o", out, *args)
    assert done.returncode == 0, done.stderr
    return tessera.read_exr(out)


@pytest.mark.parametrize(
    "options, args",
    [
        (dict(width=48, height=32, spp=4, seed=3, aovs=["albedo", "normal", "depth"]),
         ["--width", "48", "--height", "32", "--spp", "4", "--seed", "3", "--aov", "albedo,normal,depth"]),
        (dict(width=40, height=30, spp=3, orbit=(30.0, 20.0), max_bounces=3, aovs=["halves"]),
         ["--width", "40", "--height", "30", "--spp", "3", "--orbit", "30.0,20.0", "--max-bounces", "3",
          "--aov", "halves"]),
        (dict(width=40, height=24, spp=2, look_at=((2, 1.5, 2.5), (0, 0, 0), (0, 1, 0)), film_transparent=True),
         ["--width", "40", "--height", "24", "--spp", "2", "--look-at", "2,1.5,2.5,0,0,0,0,1,0", "--film-transparent"]),
    ],
)
def test_the_same_options_give_the_command_lines_pixels(run_cli, tmp_path, options, args):
    layers = tessera.Scene(BOX).render(threads=2, **options)
    expected = cli_layers(run_cli, tmp_path, BOX, args)
    assert list(layers) == list(expected)
    for name in expected:
        assert np.array_equal(layers[name], expected[name]), name
    for key in ("seed", "samplesPerPixel", "maxBounces", "camera", "worldToCamera", "worldToNDC"):
        assert np.array_equal(layers.metadata[key], expected.metadata[key]), key


@pytest.mark.parametrize("camera", [0, "Camera"])
def test_a_camera_of_the_file_by_index_or_name_gives_the_command_lines_pixels(run_cli, tmp_path, camera):
    layers = tessera.Scene(VARIANTS).render(width=32, height=24, spp=2, camera=camera, variant="red")
    expected = cli_layers(run_cli, tmp_path, VARIANTS,
                          ["--width", "32", "--height", "24", "--spp", "2", "--camera", str(camera), "--variant", "red"])
    assert np.array_equal(layers["RGBA"], expected["RGBA"])
    assert layers.metadata["camera"] == expected.metadata["camera"] == "Camera"
    assert layers.metadata["materialVariant"] == "red"


def test_denoised_render_equals_the_command_lines(run_cli, tmp_path):
    layers = tessera.Scene(BOX).render(width=32, height=32, spp=8, denoise=True)
    expected = cli_layers(run_cli, tmp_path, BOX, ["--width", "32", "--height", "32", "--spp", "8", "--denoise"])
    assert layers.metadata["denoised"] == 1
    for name in expected:
        assert np.array_equal(layers[name], expected[name]), name


def test_every_layer_is_float32_height_by_width_by_its_channels():
    layers = tessera.Scene(BOX).render(width=20, height=10, spp=2, aovs=["albedo", "normal", "depth", "halves", "cost"])
    channels = {"RGBA": 4, "Albedo": 3, "N": 3, "Z": 1, "cost": 1, "even": 3, "odd": 3, "even.Albedo": 3,
                "odd.Albedo": 3, "even.N": 3, "odd.N": 3, "variance": 3, "spp": 1}
    assert set(layers) == set(channels)
    for name, count in channels.items():
        assert layers[name].dtype == np.float32, name
        assert layers[name].shape == (10, 20, count), name
    assert np.all(layers["RGBA"][..., 3] == 1.0)  # no --film-transparent: opaque
    assert np.all(layers["spp"] == 2.0)
    assert layers.stats["samples"] == 20 * 10 * 2


def test_a_variant_or_time_set_between_renders_equals_a_fresh_load():
    options = dict(width=32, height=24, spp=2)
    scene = tessera.Scene(VARIANTS)
    scene.render(**options)
    switched = scene.render(variant="green", **options)
    fresh = tessera.Scene(VARIANTS, variant="green").render(**options)
    assert np.array_equal(switched["RGBA"], fresh["RGBA"])
    assert not np.array_equal(switched["RGBA"], scene.render(variant="red", **options)["RGBA"])

    animated = tessera.Scene(ANIMATED)
    animated.render(time=0.0, **options)
    later = animated.render(time=1.5, **options)
    assert np.array_equal(later["RGBA"], tessera.Scene(ANIMATED).render(time=1.5, **options)["RGBA"])
    assert later.metadata["sceneTime"] == np.float32(1.5)


def test_a_camera_changed_between_renders_equals_a_fresh_load():
    options = dict(width=32, height=24, spp=2, threads=1)
    scene = tessera.Scene(BOX)
    first = scene.render(orbit=(0, 10), **options)
    turned = scene.render(orbit=(120, 30), **options)
    assert turned.stats["updated"] and not first.stats["updated"]  # the same scene, only the camera moved
    assert np.array_equal(turned["RGBA"], tessera.Scene(BOX).render(orbit=(120, 30), **options)["RGBA"])


def test_an_environment_set_between_renders_equals_a_fresh_load():
    options = dict(width=24, height=16, spp=2, threads=1)
    sky = scene_path("env/spruit_sunrise_1k.hdr")
    scene = tessera.Scene(BOX)
    plain = scene.render(**options)
    lit = scene.render(envmap=sky, envmap_rotate=90.0, **options)
    assert np.array_equal(lit["RGBA"], tessera.Scene(BOX).render(envmap=sky, envmap_rotate=90.0, **options)["RGBA"])
    assert not np.array_equal(lit["RGBA"], plain["RGBA"])
    assert np.array_equal(scene.render(**options)["RGBA"], plain["RGBA"])  # and back


def test_an_orbit_places_the_camera_on_its_sphere_around_the_centre():
    # Box.glb is the unit cube about the origin: the orbit's centre is (0, 0, 0).
    azimuth, elevation, distance = 60.0, 25.0, 4.0
    layers = tessera.Scene(BOX).render(width=16, height=16, spp=1, orbit=(azimuth, elevation, distance))
    # worldToCamera as OpenEXR's M44f multiplies row vectors: the camera's position is the
    # translation row of its inverse.
    eye = np.linalg.inv(layers.metadata["worldToCamera"].astype(np.float64))[3, :3]
    a, e = np.radians(azimuth), np.radians(elevation)
    expected = distance * np.array([np.cos(e) * np.sin(a), np.sin(e), np.cos(e) * np.cos(a)])
    assert np.allclose(eye, expected, atol=1e-5)
    assert layers.metadata["camera"] == "orbit"


def run_python(code, isa, *args):
    return subprocess.run([sys.executable, "-c", code, *map(str, args)], env={**os.environ, "TESSERA_ISA": isa},
                          capture_output=True, text=True, timeout=120)


def test_the_generic_and_the_avx2_builds_give_the_same_pixels(tmp_path):
    code = ("import sys, numpy, tessera; numpy.save(sys.argv[2], tessera.Scene(sys.argv[1]).render("
            "width=32, height=24, spp=4, seed=2, aovs=['normal'])['RGBA']); print(tessera.isa())")
    generic = run_python(code, "x86-64", BOX, tmp_path / "generic.npy")
    chosen = run_python(code, "auto", BOX, tmp_path / "auto.npy")
    assert generic.returncode == 0 and chosen.returncode == 0, generic.stderr + chosen.stderr
    assert generic.stdout.strip() == "x86-64"
    if chosen.stdout.strip() == "x86-64":
        pytest.skip("this CPU (or build) has only the generic build")
    assert chosen.stdout.strip() == "x86-64-v3"
    assert np.array_equal(np.load(tmp_path / "generic.npy"), np.load(tmp_path / "auto.npy"))


def test_an_unknown_instruction_set_is_refused_as_the_program_refuses_it(tessera_exe):
    imported = run_python("import tessera", "pentium")
    assert imported.returncode != 0
    program = subprocess.run([tessera_exe, "--version"], env={**os.environ, "TESSERA_ISA": "pentium"},
                             capture_output=True, text=True)
    message = program.stderr.splitlines()[0].removeprefix("tessera: error: ")
    assert imported.stderr.strip().splitlines()[-1] == "ImportError: " + message
