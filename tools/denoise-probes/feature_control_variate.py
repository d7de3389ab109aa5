# The features as a control variate at silhouettes: does a frame's colour noise at the spheres'
# edges follow its albedo and normal noise (which surface each sample saw), so that
# colour - B (feature - E[feature]) is less noisy, given an exact E[feature] (here the
# reference's features, the best that extra feature-only samples could give)? B per pixel: the
# least-squares slope of the colour halves' difference on the feature halves' difference over
# a (2 r + 1)^2 box, ridge lam. Prints the relative MSE, whole image and inside the edge mask,
# of the 16 spp colour and of the corrected colour.
#   feature_control_variate.py INPUT_16SPP.exr REFERENCE.exr EDGE_MASK.exr
# (INPUT with --aov albedo,normal,halves; the reference with --aov albedo,normal; the mask as
# tools/denoise-quality.sh writes it.)
import os, sys
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import image_metrics as im

noisy_path, ref_path, mask_path = sys.argv[1:4]
R = im.read(ref_path, ["R", "G", "B"])
m = im.read_mask(mask_path, R.shape[:2])
read3 = lambda path, prefix, chans: im.read(path, [prefix + c for c in chans])
feat = lambda path, pre: np.concatenate([read3(path, pre + 'Albedo.', 'RGB'), read3(path, pre + 'N.', 'XYZ')], -1)
fe, fo = feat(noisy_path, 'even.'), feat(noisy_path, 'odd.')
fref = feat(ref_path, '')
ce, co = read3(noisy_path, 'even.', 'RGB'), read3(noisy_path, 'odd.', 'RGB')
c = 0.5 * (ce + co)
print('16 spp: relMSE %.3e, in edges %.3e' % (im.relmse(c, R), im.relmse(c, R, m)))
dc, df = ce - co, fe - fo
H, W, F = df.shape
def box(a, r):
    # sum over (2r+1)^2 window, edge-padded
    p = np.pad(a, [(r, r), (r, r)] + [(0, 0)] * (a.ndim - 2), mode='edge')
    out = np.zeros_like(a)
    for y in range(2 * r + 1):
        for x in range(2 * r + 1):
            out += p[y:y + H, x:x + W]
    return out
for r in (1, 2, 3):
    for lam in (1e-3, 1e-2):
        XtX = box(df[..., :, None] * df[..., None, :], r)  # H W F F
        XtY = box(df[..., :, None] * dc[..., None, :], r)  # H W F 3
        XtX += lam * np.eye(F) * (np.trace(XtX, axis1=-2, axis2=-1)[..., None, None] / F + 1e-8)
        B = np.linalg.solve(XtX, XtY)  # H W F 3
        corr = lambda f: np.einsum('hwf,hwfc->hwc', f - fref, B)
        cv = 0.5 * ((ce - corr(fe)) + (co - corr(fo)))
        cv = np.maximum(cv, 0)
        print('corrected, box %dx%d, ridge %g: relMSE %.3e, in edges %.3e' % (2 * r + 1, 2 * r + 1, lam, im.relmse(cv, R), im.relmse(cv, R, m)))
