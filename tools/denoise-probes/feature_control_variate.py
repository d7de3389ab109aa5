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
import sys, numpy as np, OpenImageIO as oiio
def load(path):
    inp = oiio.ImageInput.open(path); spec = inp.spec(); px = inp.read_image(format="float"); inp.close()
    names = list(spec.channelnames)
    return {n: px[:, :, i] for i, n in enumerate(names)}
def get(d, prefix, chans): return np.stack([d[prefix + c] for c in chans], -1)
noisy, ref = load(sys.argv[1]), load(sys.argv[2])
edges = load(sys.argv[3]) if len(sys.argv) > 3 else None
R = get(ref, '', 'RGB')
def relmse(x, mask=None):
    e = ((x - R) ** 2 / (R ** 2 + 1e-2)).mean(-1)
    return e.mean() if mask is None else e[mask].mean()
m = edges['Y'] > 0.5 if edges else None
feat = lambda pre: np.concatenate([get(noisy, pre + 'Albedo.', 'RGB'), get(noisy, pre + 'N.', 'XYZ')], -1)
fe, fo = feat('even.'), feat('odd.')
fref = np.concatenate([get(ref, 'Albedo.', 'RGB'), get(ref, 'N.', 'XYZ')], -1)
ce, co = get(noisy, 'even.', 'RGB'), get(noisy, 'odd.', 'RGB')
c = 0.5 * (ce + co)
print('16spp', relmse(c), relmse(c, m))
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
        print(f'cv r={r} lam={lam}', relmse(cv), relmse(cv, m))
