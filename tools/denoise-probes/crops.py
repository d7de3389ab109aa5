# Side by side, the same crop of several frames (display-referred, 2x enlarged) above their
# relative-squared-error maps against the reference (tools/image_metrics.py's error map).
#   crops.py OUT.png X0,Y0,X1,Y1 REFERENCE.exr LABEL=FRAME.exr[:CHANNELS] ...
# CHANNELS: the frame's colour channels (default R,G,B; e.g. noisy.R,noisy.G,noisy.B).
import os, sys
import numpy as np
import OpenImageIO as oiio
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import image_metrics as im

def display(rgb):
    """Linear RGB (h, w, 3) to sRGB display values in [0, 1], by OpenImageIO's colorconvert."""
    h, w, _ = rgb.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, 3, "float"))
    if not buf.set_pixels(oiio.ROI(0, w, 0, h), np.ascontiguousarray(np.clip(rgb, 0, None), dtype=np.float32)):
        sys.exit(f"cannot convert for display: {buf.geterror()}")
    return np.clip(oiio.ImageBufAlgo.colorconvert(buf, "linear", "sRGB").get_pixels(oiio.FLOAT), 0, 1)

def main(out, box, ref_path, frames):
    x0, y0, x1, y1 = (int(v) for v in box.split(","))
    ref = im.read(ref_path, ["R", "G", "B"])[y0:y1, x0:x1]
    columns = []
    for spec in frames:
        label, _, rest = spec.partition("=")
        path, _, channels = rest.partition(":")
        img = im.read(path, (channels or "R,G,B").split(","))[y0:y1, x0:x1]
        shown = display(img).repeat(2, 0).repeat(2, 1)
        err = im.error_map(img.repeat(2, 0).repeat(2, 1), ref.repeat(2, 0).repeat(2, 1))
        w = max(shown.shape[1], err.shape[1])
        col = np.zeros((24 + shown.shape[0] + err.shape[0], w, 3), np.float32)
        col[24:24 + shown.shape[0], :shown.shape[1]] = shown
        col[24 + shown.shape[0]:, :err.shape[1]] = err
        buf = oiio.ImageBuf(oiio.ImageSpec(w, col.shape[0], 3, "float"))
        buf.set_pixels(oiio.ROI(0, w, 0, col.shape[0]), col)
        oiio.ImageBufAlgo.render_text(buf, 4, 17, label, im.FONT_SIZE, im.FONT, (1, 1, 1))
        columns.append(buf.get_pixels(oiio.FLOAT))
    h = max(c.shape[0] for c in columns)
    mosaic = np.concatenate([np.pad(c, ((0, h - c.shape[0]), (0, 4), (0, 0))) for c in columns], 1)
    im.write(out, mosaic, ["R", "G", "B"])

if __name__ == "__main__":
    if len(sys.argv) < 5:
        sys.exit("usage: crops.py OUT.png X0,Y0,X1,Y1 REFERENCE.exr LABEL=FRAME.exr[:CHANNELS] ...")
    main(sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:])
