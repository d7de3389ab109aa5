"""Errors are the command line's: the same message, as a Python exception, and the scene stays
usable after one (and after Ctrl-C)."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import tessera
from conftest import scene_path

BOX = scene_path("khronos/Box/glTF-Binary/Box.glb")


def cli_error(run_cli, *args):
    done = run_cli(*args)
    assert done.returncode == 2
    first = done.stderr.splitlines()[0]
    assert first.startswith("tessera: error: ")
    return first[len("tessera: error: "):]


def test_a_missing_file_raises_scene_load_error_with_the_command_lines_message(run_cli, tmp_path):
    missing = str(tmp_path / "missing.glb")
    with pytest.raises(tessera.SceneLoadError) as e:
        tessera.Scene(missing)
    assert str(e.value) == cli_error(run_cli, "render", missing, "-o", tmp_path / "x.exr")
    assert missing in str(e.value)


@pytest.mark.parametrize(
    "options, args",
    [
        (dict(spp=0), ["--spp", "0"]),
        (dict(width=-3), ["--width", "-3"]),
        (dict(spp="many"), ["--spp", "many"]),
        (dict(sampler="halton"), ["--sampler", "halton"]),
        (dict(orbit=(10, 95)), ["--orbit", "10,95"]),
        (dict(camera="nowhere"), ["--camera", "nowhere"]),
        (dict(widht=64), ["--widht", "64"]),
    ],
)
def test_a_bad_option_raises_usage_error_with_the_command_lines_message(run_cli, tmp_path, options, args):
    scene = tessera.Scene(BOX)
    with pytest.raises(tessera.UsageError) as e:
        scene.render(**options)
    assert str(e.value) == cli_error(run_cli, "render", BOX, "-o", tmp_path / "x.exr", *args)
    assert isinstance(e.value, ValueError)
    assert scene.render(width=8, height=8, spp=1)["RGBA"].shape == (8, 8, 4)  # still usable


def test_options_that_write_files_are_refused():
    with pytest.raises(tessera.UsageError, match="--output: a render in memory writes and reads no file"):
        tessera.Scene(BOX).render(output="x.exr")


def test_an_option_without_effect_warns_as_the_command_line_does():
    with pytest.warns(tessera.TesseraWarning, match="--focus-distance"):
        tessera.Scene(BOX).render(width=8, height=8, spp=1, focus_distance=2.0)


def test_ctrl_c_stops_a_render_and_leaves_the_scene_usable():
    scene = tessera.Scene(BOX)
    options = dict(width=32, height=32, spp=2, seed=5)
    before = scene.render(**options)
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        scene.render(width=512, height=512, spp=1 << 20, threads=1)  # hours, were it not stopped
    assert time.monotonic() - start < 10.0
    timer.join()
    assert np.array_equal(scene.render(**options)["RGBA"], before["RGBA"])


def test_progress_is_reported_and_an_exception_in_it_stops_the_render():
    calls = []
    tessera.Scene(BOX).render(width=64, height=64, spp=64, progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (64 * 64 * 64, 64 * 64 * 64)
    assert all(d0 <= d1 for (d0, _), (d1, _) in zip(calls, calls[1:]))

    def give_up(done, total):
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        tessera.Scene(BOX).render(width=256, height=256, spp=1 << 16, threads=1, progress=give_up)


def test_rendering_releases_the_gil():
    scene = tessera.Scene(BOX)
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.monotonic()
    scene.render(width=128, height=128, spp=256, threads=1)
    elapsed = time.monotonic() - start
    stop.set()
    counter.join()
    # The other thread ran all along: at least one tick per 20 ms of rendering (it ticks every
    # millisecond or so; with the GIL held by the render it would not tick at all).
    assert len(ticks) > elapsed / 0.020


def vm_rss_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])


def test_a_hundred_renders_do_not_grow_the_process():
    scene = tessera.Scene(BOX)
    for _ in range(20):  # allocators and caches settle
        scene.render(width=64, height=64, spp=1, threads=1, aovs=["albedo", "normal", "depth"])
    settled = vm_rss_kib()
    for i in range(100):
        scene.render(width=64, height=64, spp=1, seed=i, threads=1, aovs=["albedo", "normal", "depth"])
    # A frame's layers are 64 x 64 x 11 floats (180 KiB): a leak of one per render would add 18 MiB.
    assert vm_rss_kib() - settled < 4096
