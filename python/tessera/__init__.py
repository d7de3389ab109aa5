"""tessera from Python: load a glTF scene once, render it in memory as often as you like, and
get its layers back as numpy arrays.

    import tessera
    scene = tessera.Scene("DamagedHelmet.glb")
    layers = scene.render(width=256, height=256, spp=16, orbit=(30, 15), aovs=["depth", "normal"])
    layers["RGBA"]   # float32, 256 x 256 x 4
    tessera.write_exr("helmet.exr", layers)

Every keyword of render() is an option of `tessera render` (docs/usage.md), with underscores
for dashes: spp=16 is --spp 16, max_bounces=4 is --max-bounces 4, look_at=(eye, target, up)
is --look-at with nine numbers, aovs=[...] is --aov, True is a flag. The same options give
the same pixels as the command line, bit for bit. docs/python.md has the whole story.
"""

import importlib
import numbers
import os
import threading
import warnings


def _native_for_this_cpu():
    """The native part built for the instruction set TESSERA_ISA asks for, as the tessera program
    chooses its build: auto (or unset) the fastest this CPU runs, x86-64 or x86-64-v3."""
    from . import _native as generic
    wanted = os.environ.get("TESSERA_ISA") or "auto"
    if wanted not in ("auto", "x86-64", "x86-64-v3"):
        raise ImportError(f"TESSERA_ISA={wanted}: expected auto, x86-64 or x86-64-v3")
    if wanted == "x86-64":
        return generic
    if not generic.cpu_runs_x86_64_v3():
        if wanted == "x86-64-v3":
            raise ImportError("TESSERA_ISA=x86-64-v3, but this CPU lacks AVX2, FMA or BMI2")
        return generic
    try:
        return importlib.import_module("._native_x86_64_v3", __name__)
    except ImportError:
        if wanted == "x86-64-v3":
            raise
        return generic  # a build without it


_native = _native_for_this_cpu()
Error, FileError, SceneLoadError, UsageError = _native.Error, _native.FileError, _native.SceneLoadError, _native.UsageError
isa, version = _native.isa, _native.version

__all__ = ["Scene", "Layers", "read_exr", "write_exr", "Error", "UsageError", "SceneLoadError", "FileError",
           "TesseraWarning", "version", "isa"]

__version__ = version()


class TesseraWarning(UserWarning):
    """An option that has no effect with the others given (the command line's warning)."""


class Layers(dict):
    """Layer name -> numpy array of float32, height x width x channels, named as in the EXR:
    'RGBA' for the beauty (A: coverage with film_transparent, else 1), 'Albedo', 'N', 'Z',
    'even', 'odd', 'variance', 'spp', ... The EXR header's attributes are in .metadata
    (tessera's render metadata for a render: seed, samplesPerPixel, worldToCamera, ...)."""

    def __init__(self, layers=(), metadata=None, stats=None):
        super().__init__(layers)
        self.metadata = dict(metadata or {})
        # For a render: seconds (rendering), load_seconds (posing the scene from the file read
        # once), build_seconds and updated (the last render's scene updated, not built anew),
        # session_seconds (all the native side did), samples, rays, threads.
        self.stats = dict(stats or {})


# Options that are not `--name` with underscores turned to dashes.
_OPTION_NAMES = {"aovs": "--aov"}


def _text(value):
    """A value as the command line would type it; floats exactly (repr round-trips)."""
    if isinstance(value, bool):
        raise TypeError("a flag takes True or False, not a number")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    return ",".join(_text(v) for v in value)  # a sequence: look_at, orbit, aovs, background


def _arguments(options):
    """Keyword options -> the render command's arguments, in a fixed order."""
    args = []
    for name, value in options.items():
        if value is None or value is False:
            continue
        flag = _OPTION_NAMES.get(name, "--" + name.replace("_", "-"))
        if value is True:
            args.append(flag)
        else:
            args += [flag, _text(value)]
    return args


class Scene:
    """A glTF file read once. render() renders it with any options; between renders the camera,
    size, variant, time, environment and samples may change without reading the file again
    (what did not change is kept: textures, the environment, the BVHs of what did not move).

    `scene` and `variant` (and any other keyword) are defaults for every render()."""

    def __init__(self, path, scene=None, variant=None, **defaults):
        self._session = _native.Session(os.fspath(path))
        self._defaults = dict(scene=scene, variant=variant, **defaults)
        self._lock = threading.Lock()  # one render at a time: they share the scene

    @property
    def path(self):
        return self._session.path

    def render(self, camera=None, width=None, height=None, spp=None, seed=None, time=None, aovs=None,
               denoise=False, threads=None, look_at=None, orbit=None, progress=None, **options):
        """Renders and returns Layers. `camera`: a camera of the file by name or index; `look_at`:
        (eye, target, up); `orbit`: (azimuth, elevation[, distance]) in degrees around the
        scene's centre. `progress(done, total)`, if given, is called with camera samples as the
        render goes (every 50 ms). Ctrl-C stops the render and raises KeyboardInterrupt; the
        scene stays usable. Bad options raise UsageError with the command line's message."""
        given = dict(camera=camera, width=width, height=height, spp=spp, seed=seed, time=time, aovs=aovs,
                     denoise=denoise, threads=threads, look_at=look_at, orbit=orbit)
        merged = {**self._defaults, **{k: v for k, v in given.items() if v is not None}, **options}
        with self._lock:
            layers, metadata, notes, stats = self._session.render(_arguments(merged), progress)
        for note in notes:
            warnings.warn(note, TesseraWarning, stacklevel=2)
        return Layers(layers, metadata, stats)


def read_exr(path):
    """Every channel of an OpenEXR file's first part, grouped into Layers (as render() returns
    them), with the header's attributes in .metadata: str, int, float (double),
    numpy.float32 (float) and 4x4 float32 matrices."""
    layers, metadata = _native.read_exr(os.fspath(path))
    return Layers(layers, metadata)


def write_exr(path, layers, metadata=None, half=False):
    """Writes layers (a dict of arrays, height x width x channels or height x width) to an
    OpenEXR file, ZIP-compressed, atomically (never a truncated file). Channel names: R, G, B[,
    A] for 'RGBA' or 'RGB'; tessera's own for its layers ('N' -> N.X, N.Y, N.Z); else NAME for
    one channel, NAME.X/Y for two, NAME.R/G/B[/A] for three or four. `metadata` (default:
    layers.metadata when it has one) becomes header attributes, each of its Python type;
    tessera adds software, chromaticities and capDate. `half`: colour channels as half floats."""
    if metadata is None:
        metadata = getattr(layers, "metadata", {})
    _native.write_exr(os.fspath(path), dict(layers), dict(metadata), bool(half))
