#!/usr/bin/python3
"""Image metrics for tessera's measurement scripts (Debian's python3: numpy and OpenImageIO).

  image_metrics.py noise A.exr B.exr [--channels C,..] [--ref-channels C,..] [--mask MASK.exr]
                   [--normalized | --relative | --scale-free]
      noise variance: mean over pixels and channels of (a - b)^2 / 2, for two renders of the
      same image with different seeds (their difference has twice the variance of either);
      --normalized divides it by the square of the two images' mean value, so that an image
      that is darker overall does not count as less noisy for that alone; --relative divides
      each pixel's by its own squared value ((a + b)^2 / 4) plus 0.01, as relmse does, so that
      a region one renderer shows darker (light it loses) does not count as less noisy either
      --scale-free weighs each pixel as --relative does, with the 0.01 times the image's squared
      mean: the same for an image scaled by any factor (renderers that read light units differently)
  image_metrics.py relmse IMG.exr REF.exr [--channels C,..] [--ref-channels C,..] [--mask MASK.exr]
      relative MSE: mean of (img - ref)^2 / (ref^2 + 0.01) over pixels and channels
  image_metrics.py edge-mask REF.exr -o MASK.exr [--albedo-threshold T] [--normal-threshold T]
      1 where the reference's Albedo.* or N.* features change between neighbours, dilated by a pixel
  image_metrics.py error-map IMG.exr REF.exr -o MAP.png [--channels ..] [--ref-channels ..] [--range LO,HI]
      per-pixel relative squared error as a viridis colour map, log scale, with a legend
  image_metrics.py render-time IMG.exr
      the render seconds in the EXR header (tessera's renderTimeSeconds, Cycles' render_time)
  image_metrics.py selftest

Channels default to R,G,B (--ref-channels defaults to --channels). A mask is its first channel,
> 0.5 inside. Numbers go to stdout; bad input is one line on stderr and exit status 2.
"""
import argparse
import contextlib
import io
import os
import shutil
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

EPS = 0.01  # relMSE's regulariser: keeps dark pixels from dominating


class Bad(Exception):
    """Bad input: reported as one line, exit status 2."""


def read(path, channels=None):
    """Pixels of `path` as a float64 array (height, width, channels), the named channels in order."""
    if not os.path.isfile(path):
        raise Bad(f"{path}: no such file")
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise Bad(f"{path}: cannot read: {oiio.geterror()}")
    try:
        names = list(inp.spec().channelnames)
        channels = channels or names
        missing = [c for c in channels if c not in names]
        if missing:
            raise Bad(f"{path}: no channel {','.join(missing)} (it has {','.join(names)})")
        px = inp.read_image("float")
        if px is None:
            raise Bad(f"{path}: cannot read pixels: {inp.geterror()}")
    finally:
        inp.close()
    px = np.asarray(px, dtype=np.float64).reshape(px.shape[0], px.shape[1], len(names))
    px = px[:, :, [names.index(c) for c in channels]]
    if not np.isfinite(px).all():
        raise Bad(f"{path}: {np.count_nonzero(~np.isfinite(px))} values are NaN or infinite")
    return px


def write(path, px, channels):
    """Writes float pixels (h, w, c): as float to .exr, else clamped to 8 bits (already display-encoded)."""
    h, w, c = px.shape
    exr = path.lower().endswith(".exr")
    spec = oiio.ImageSpec(w, h, c, "float" if exr else "uint8")
    spec.channelnames = tuple(channels)
    data = px.astype(np.float32) if exr else np.clip(np.rint(px * 255), 0, 255).astype(np.uint8)
    data = np.ascontiguousarray(data)  # OpenImageIO writes a strided view (a transpose) as garbage
    out = oiio.ImageOutput.create(path)
    if out is None or not out.open(path, spec) or not out.write_image(data) or not out.close():
        raise Bad(f"{path}: cannot write: {oiio.geterror()}")


def read_mask(path, shape):
    m = read(path)[:, :, 0] > 0.5
    if m.shape != shape:
        raise Bad(f"{path}: mask is {m.shape[1]}x{m.shape[0]}, the images {shape[1]}x{shape[0]}")
    if not m.any():
        raise Bad(f"{path}: the mask is empty")
    return m


def pair(a_path, b_path, a_channels, b_channels):
    a, b = read(a_path, a_channels), read(b_path, b_channels)
    if a.shape != b.shape:
        raise Bad(f"{a_path} is {a.shape[1]}x{a.shape[0]}x{a.shape[2]}, {b_path} {b.shape[1]}x{b.shape[0]}x{b.shape[2]}")
    return a, b


def noise(a, b, mask=None, normalized=False, relative=False, scale_free=False):
    if mask is not None:
        a, b = a[mask], b[mask]
    if scale_free:  # each pixel's over its squared value + 0.01 x the image's squared mean
        m = (a + b) / 2
        return float(((a - b) ** 2 / 2 / (m ** 2 + EPS * float(m.mean()) ** 2)).mean())
    if relative:  # (a - b)^2 / 2 = 2 (a - mean)^2, weighed as relMSE weighs an error against its reference
        return float((2 * rel_sq_error(a, (a + b) / 2)).mean())
    v = float(((a - b) ** 2 / 2).mean())
    return v / float((a + b).mean() / 2) ** 2 if normalized else v


def rel_sq_error(img, ref):
    return (img - ref) ** 2 / (ref ** 2 + EPS)


def relmse(img, ref, mask=None):
    e = rel_sq_error(img, ref)
    return float(e[mask].mean() if mask is not None else e.mean())


def feature_edges(f, threshold, metric):
    """True at both pixels of every horizontal or vertical neighbour pair whose features differ by
    more than `threshold`: per channel (`max`) for albedo, as a vector length (`norm`) for normals."""
    def differs(d):
        return (np.abs(d).max(axis=2) if metric == "max" else np.sqrt((d ** 2).sum(axis=2))) > threshold
    e = np.zeros(f.shape[:2], dtype=bool)
    dx, dy = differs(np.diff(f, axis=1)), differs(np.diff(f, axis=0))
    e[:, :-1] |= dx
    e[:, 1:] |= dx
    e[:-1, :] |= dy
    e[1:, :] |= dy
    return e


def dilate(m):
    h, w = m.shape
    p = np.pad(m, 1)
    out = np.zeros_like(m)
    for y in range(3):
        for x in range(3):
            out |= p[y:y + h, x:x + w]
    return out


def edge_mask(ref_path, albedo_threshold=0.1, normal_threshold=0.25):
    albedo = read(ref_path, ["Albedo.R", "Albedo.G", "Albedo.B"])
    normal = read(ref_path, ["N.X", "N.Y", "N.Z"])
    # |n1 - n2| = 2 sin(angle / 2): 0.25 is about 14 degrees between neighbouring pixels.
    return dilate(feature_edges(albedo, albedo_threshold, "max") | feature_edges(normal, normal_threshold, "norm"))


# --- error-map: drawn with OpenImageIO (color_map's viridis, render_text in DejaVu Sans), as tessera's heat map ---

FONT, FONT_SIZE = "DejaVuSans", 12  # fonts-dejavu-core


def viridis(t):
    """sRGB display values of viridis at each t (any shape, clamped to [0, 1])."""
    t = np.clip(np.asarray(t, dtype=np.float32), 0, 1)
    n = t.size
    buf = oiio.ImageBuf(oiio.ImageSpec(n, 1, 1, "float"))
    buf.set_pixels(oiio.ROI(0, n, 0, 1), t.reshape(1, n, 1))
    # OpenImageIO's maps are linear light, like its images; a PNG wants sRGB.
    srgb = oiio.ImageBufAlgo.colorconvert(oiio.ImageBufAlgo.color_map(buf, 0, "viridis"), "linear", "sRGB")
    return srgb.get_pixels(oiio.FLOAT).reshape(t.shape + (3,))


def text_width(s):
    return oiio.ImageBufAlgo.text_size(s, FONT_SIZE, FONT).width


def error_map(img, ref, lo=-4.0, hi=0.0):
    """RGB picture (display values in [0, 1]) of log10 of the per-pixel relative squared error
    (mean over channels) from 10^lo (dark) to 10^hi (bright), a colour bar and its labels below."""
    e = rel_sq_error(img, ref).mean(axis=2)
    t = (np.log10(np.maximum(e, 1e-30)) - lo) / (hi - lo)
    h, w = e.shape
    low, high, title = f"1e{lo:+.0f}", f"1e{hi:+.0f}", f"relative squared error, mean {e.mean():.2e}"
    width = max(w, text_width(title) + 8)
    out = np.zeros((h + LEGEND_ROWS, width, 3), dtype=np.float32)
    out[:h, :w] = viridis(t)
    out[h + 4:h + 14, 4:width - 4] = viridis(np.linspace(0, 1, width - 8))[None, :, :]
    buf = oiio.ImageBuf(oiio.ImageSpec(width, h + LEGEND_ROWS, 3, "float"))
    buf.set_pixels(oiio.ROI(0, width, 0, h + LEGEND_ROWS), out)
    for x, y, label, align in ((4, h + 28, low, "left"), (width - 4, h + 28, high, "right"), (4, h + 46, title, "left")):
        if not oiio.ImageBufAlgo.render_text(buf, x, y, label, FONT_SIZE, FONT, (1, 1, 1), align):
            raise Bad(f"cannot draw the legend: {buf.geterror()} (is fonts-dejavu-core installed?)")
    return buf.get_pixels(oiio.FLOAT)


LEGEND_ROWS = 52  # the colour bar and two lines of labels below the map


def render_time(path):
    if not os.path.isfile(path):
        raise Bad(f"{path}: no such file")
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise Bad(f"{path}: cannot read: {oiio.geterror()}")
    spec = inp.spec()
    inp.close()
    t = spec.getattribute("renderTimeSeconds")  # tessera
    if t is not None:
        return float(t)
    t = spec.getattribute("cycles.ViewLayer.render_time")  # Cycles: "MM:SS.ss" or "HH:MM:SS.ss"
    if t is not None:
        secs = 0.0
        for part in str(t).split(":"):
            secs = secs * 60 + float(part)
        return secs
    raise Bad(f"{path}: no render time in the header (renderTimeSeconds or cycles.ViewLayer.render_time)")


# --- self test: exact values on synthetic images ---

def selftest():
    tmp = tempfile.mkdtemp(prefix="image_metrics_")
    rgb = ["R", "G", "B"]

    def const(name, value, h=4, w=6, channels=rgb):
        p = os.path.join(tmp, name)
        write(p, np.full((h, w, len(channels)), value), channels)
        return p

    # noise of two constant images differing by d is d^2 / 2 (0.25 and 0.5: exact in float32)
    a, b = const("a.exr", 0.25), const("b.exr", 0.5)
    assert noise(*pair(a, b, rgb, rgb)) == 0.25 ** 2 / 2
    assert noise(*pair(a, b, rgb, rgb), normalized=True) == 0.25 ** 2 / 2 / 0.375 ** 2
    assert abs(noise(*pair(a, b, rgb, rgb), relative=True) - 0.25 ** 2 / 2 / (0.375 ** 2 + 0.01)) < 1e-15
    assert abs(noise(*pair(a, b, rgb, rgb), scale_free=True) - 0.25 ** 2 / 2 / (1.01 * 0.375 ** 2)) < 1e-15
    # relMSE: ref 0.5, image 0.25: 0.0625 / 0.26 in every pixel; of ref against itself, 0
    assert abs(relmse(*pair(a, b, rgb, rgb)) - 0.0625 / 0.26) < 1e-15
    assert relmse(*pair(b, b, rgb, rgb)) == 0.0
    # a mask selects pixels: error only in the left half, mask on the left half -> all of it
    img = np.full((4, 6, 3), 0.5)
    img[:, :3] = 1.0
    write(os.path.join(tmp, "half.exr"), img, rgb)
    m = np.zeros((4, 6, 1))
    m[:, :3] = 1
    write(os.path.join(tmp, "mask.exr"), m, ["Y"])
    x, r = pair(os.path.join(tmp, "half.exr"), b, rgb, rgb)
    mask = read_mask(os.path.join(tmp, "mask.exr"), x.shape[:2])
    assert abs(relmse(x, r, mask) - 0.25 / 0.26) < 1e-15 and abs(relmse(x, r) - 0.25 / 0.26 / 2) < 1e-15
    # channel subsets, in the order asked: noisy.* against R,G,B of the same file
    layered = np.concatenate([np.full((4, 6, 3), 0.5), np.full((4, 6, 3), 0.25)], axis=2)
    p = os.path.join(tmp, "layers.exr")
    write(p, layered, rgb + ["noisy.R", "noisy.G", "noisy.B"])
    assert noise(*pair(p, p, ["noisy.R", "noisy.G", "noisy.B"], rgb)) == 0.25 ** 2 / 2
    assert read(p, ["noisy.B", "R"]).shape == (4, 6, 2)
    # edge mask: an albedo step between columns 7 and 8 marks 7 and 8, dilated: columns 6 to 9
    f = np.zeros((10, 16, 6))
    f[:, 8:, 0] = 0.8
    f[:, :, 5] = 1.0  # N = +Z everywhere
    p = os.path.join(tmp, "features.exr")
    write(p, f, ["Albedo.R", "Albedo.G", "Albedo.B", "N.X", "N.Y", "N.Z"])
    e = edge_mask(p)
    assert (np.flatnonzero(e.any(axis=0)) == [6, 7, 8, 9]).all() and e[:, 6:10].all()
    # a normal turning by 90 degrees on one row marks rows 4 and 5, dilated: rows 3 to 6
    f[:, :, 0] = 0
    f[5:, :, 5], f[5:, :, 3] = 0.0, 1.0
    write(p, f, ["Albedo.R", "Albedo.G", "Albedo.B", "N.X", "N.Y", "N.Z"])
    assert (np.flatnonzero(edge_mask(p).any(axis=1)) == [3, 4, 5, 6]).all()
    # error map: zero error is viridis(0), matplotlib's (0.267, 0.005, 0.329); the legend adds rows below
    em = error_map(np.full((4, 6, 3), 0.5), np.full((4, 6, 3), 0.5))
    assert em.shape[0] == 4 + LEGEND_ROWS and np.allclose(em[0, 0], viridis(np.array(0.0)))
    assert np.allclose(viridis(np.array([0.0, 1.0])), [[0.267, 0.005, 0.329], [0.993, 0.906, 0.144]], atol=0.01)
    # bad input: one clear message
    for call, words in [(lambda: read(a, ["noisy.R"]), "no channel noisy.R"),
                        (lambda: read(os.path.join(tmp, "none.exr")), "no such file"),
                        (lambda: pair(a, os.path.join(tmp, "features.exr"), rgb, ["N.X", "N.Y", "N.Z"]), "is 6x4x3")]:
        try:
            call()
            raise AssertionError(f"expected an error with '{words}'")
        except Bad as err:
            assert words in str(err), str(err)
    with contextlib.redirect_stderr(io.StringIO()) as err:
        assert main(["relmse", a, os.path.join(tmp, "none.exr")]) == 2
    assert err.getvalue().startswith("image_metrics.py: ") and err.getvalue().count("\n") == 1
    shutil.rmtree(tmp)
    print("image_metrics selftest: all checks passed")
    return 0


def main(argv):
    ap = argparse.ArgumentParser(prog="image_metrics.py", description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)

    def two(name):
        s = sub.add_parser(name)
        s.add_argument("img")
        s.add_argument("ref")
        s.add_argument("--channels", default="R,G,B", help="channels of the first image (default R,G,B)")
        s.add_argument("--ref-channels", help="channels of the second image (default: --channels)")
        return s

    for name in ("noise", "relmse"):
        two(name).add_argument("--mask", help="only pixels where this image's first channel > 0.5")
    scale = sub.choices["noise"].add_mutually_exclusive_group()
    scale.add_argument("--normalized", action="store_true", help="over the squared mean value")
    scale.add_argument("--relative", action="store_true", help="each pixel's over its squared value + 0.01")
    scale.add_argument("--scale-free", action="store_true",
                       help="each pixel's over its squared value + 0.01 x the image's squared mean: the same for an image scaled")
    s = sub.add_parser("edge-mask")
    s.add_argument("ref")
    s.add_argument("-o", "--output", required=True)
    s.add_argument("--albedo-threshold", type=float, default=0.1)
    s.add_argument("--normal-threshold", type=float, default=0.25)
    s = two("error-map")
    s.add_argument("-o", "--output", required=True)
    s.add_argument("--range", default="1e-4,1", help="errors mapped to the ends of the scale (default 1e-4,1)")
    sub.add_parser("render-time").add_argument("img")
    sub.add_parser("selftest")
    args = ap.parse_args(argv)
    try:
        if args.cmd == "selftest":
            return selftest()
        if args.cmd == "render-time":
            print(f"{render_time(args.img):.6g}")
            return 0
        if args.cmd == "edge-mask":
            m = edge_mask(args.ref, args.albedo_threshold, args.normal_threshold)
            write(args.output, m[:, :, None].astype(np.float64), ["Y"])
            print(f"{m.mean():.4f}")  # the fraction of the image inside the mask
            return 0
        chans = args.channels.split(",")
        img, ref = pair(args.img, args.ref, chans, (args.ref_channels or args.channels).split(","))
        if args.cmd == "error-map":
            lo, hi = (np.log10(float(v)) for v in args.range.split(","))
            write(args.output, error_map(img, ref, lo, hi), ["R", "G", "B"])
            return 0
        mask = read_mask(args.mask, img.shape[:2]) if args.mask else None
        value = (noise(img, ref, mask, args.normalized, args.relative, args.scale_free) if args.cmd == "noise"
                 else relmse(img, ref, mask))
        print(f"{value:.6e}")
        return 0
    except Bad as err:
        print(f"image_metrics.py: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
