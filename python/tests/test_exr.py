"""tessera.write_exr and tessera.read_exr: layers and header attributes come back as written,
and other readers see the channels under their compositing names."""

import subprocess

import numpy as np
import pytest

import tessera
from conftest import scene_path


def test_layers_and_metadata_round_trip(tmp_path):
    rng = np.random.default_rng(7)
    layers = {
        "RGBA": rng.random((6, 5, 4), dtype=np.float32),
        "N": rng.standard_normal((6, 5, 3)).astype(np.float32),
        "Z": rng.random((6, 5, 1), dtype=np.float32),
        "mask": rng.integers(0, 2, (6, 5)).astype(np.float32),
        "uv": rng.random((6, 5, 2), dtype=np.float32),
    }
    metadata = {"shot": "010", "take": 3, "exposure": np.float32(0.5), "focal": 35.25,
                "matrix": np.arange(16, dtype=np.float32).reshape(4, 4)}
    path = tmp_path / "l.exr"
    tessera.write_exr(path, layers, metadata)
    back = tessera.read_exr(path)
    assert list(back) == ["RGBA", "N", "Z", "mask", "uv"]
    for name, value in layers.items():
        assert np.array_equal(back[name], value.reshape(6, 5, -1)), name
    for key, value in metadata.items():
        assert type(back.metadata[key]) is type(value), key
        assert np.array_equal(back.metadata[key], value), key
    assert back.metadata["software"] == "tessera " + tessera.version()


def test_channels_are_named_as_compositors_expect(tmp_path):
    layers = {"RGBA": np.zeros((2, 2, 4), np.float32), "N": np.zeros((2, 2, 3), np.float32),
              "cost": np.zeros((2, 2), np.float32), "mask": np.zeros((2, 2, 3), np.float32)}
    path = tmp_path / "c.exr"
    tessera.write_exr(path, layers)
    # OpenImageIO (openimageio-tools), as Nuke and Blender list them.
    listed = subprocess.run(["oiiotool", "--info", "-v", str(path)], capture_output=True, text=True, check=True)
    assert "channel list: R, G, B, A, N.X, N.Y, N.Z, cost.time, mask.R, mask.G, mask.B" in listed.stdout


def test_a_render_written_from_python_reads_back_equal(tmp_path):
    layers = tessera.Scene(scene_path("khronos/Box/glTF-Binary/Box.glb")).render(width=16, height=12, spp=2,
                                                                                   aovs=["depth"])
    tessera.write_exr(tmp_path / "r.exr", layers)
    back = tessera.read_exr(tmp_path / "r.exr")
    for name in layers:
        assert np.array_equal(back[name], layers[name]), name
    assert back.metadata["seed"] == layers.metadata["seed"]
    assert back.metadata["samplesPerPixel"] == 2


def test_half_stores_colour_as_half_floats(tmp_path):
    colour = np.full((2, 2, 4), 1.0 / 3.0, np.float32)
    tessera.write_exr(tmp_path / "h.exr", {"RGBA": colour, "Z": np.full((2, 2), 1.0 / 3.0, np.float32)}, half=True)
    back = tessera.read_exr(tmp_path / "h.exr")
    assert np.array_equal(back["RGBA"], colour.astype(np.float16).astype(np.float32))
    assert np.array_equal(back["Z"][..., 0], np.full((2, 2), 1.0 / 3.0, np.float32))  # depth stays 32-bit


@pytest.mark.parametrize(
    "layers, message",
    [
        ({"RGBA": np.zeros((2, 2, 5), np.float32)}, "layer 'RGBA' has 5 channels"),
        ({"RGBA": np.zeros((2, 2, 4), np.float32), "Z": np.zeros((3, 2), np.float32)}, "layer 'Z' is 2x3"),
        ({"N": np.zeros((2, 2, 7), np.float32)}, "layer 'N' has 7 channels"),
        ({}, "no layers to write"),
    ],
)
def test_layers_that_cannot_be_written_raise_usage_error(tmp_path, layers, message):
    with pytest.raises(tessera.UsageError, match=message):
        tessera.write_exr(tmp_path / "x.exr", layers)
    assert not (tmp_path / "x.exr").exists()


def test_unreadable_and_unwritable_paths_raise_file_error(tmp_path):
    with pytest.raises(tessera.FileError, match="missing.exr"):
        tessera.read_exr(tmp_path / "missing.exr")
    with pytest.raises(tessera.FileError, match="no-such-dir"):
        tessera.write_exr(tmp_path / "no-such-dir" / "x.exr", {"RGBA": np.zeros((1, 1, 4), np.float32)})
    assert isinstance(tessera.FileError("x"), OSError)
