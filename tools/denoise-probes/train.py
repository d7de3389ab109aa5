# The learned-denoiser probe: does a kernel-predicting network (after Bako et al. 2017, "Kernel-
# Predicting Convolutional Networks for Denoising Monte Carlo Renderings"), trained here on
# tessera's own renders, denoise the paper's grid of spheres better than tessera's NFOR-family
# denoiser? Not part of tessera: an experiment, with python3-torch (Debian 12's 1.13), numpy and
# OpenImageIO's Python module. A CNN of 7 dilated 3x3 layers (CH channels, group norm; receptive
# field 45 px) predicts per pixel a softmax kernel of KS x KS weights over the noisy colour
# (NSRC=1) or over the noisy colour and tessera's denoised image (NSRC=2, 2 KS^2 weights), from
# log colour, log denoised colour, albedo, normal, log depth and the half buffers' relative
# variance. Loss: squared error relative to the denoised image's square (plus 0.01), against
# 64 spp targets of another seed (render_pairs.sh; clipped at 50), clamped at 4 per pixel;
# Adam, learning rate LR, cut to 0.3x at 70% of the steps. Every 50 steps it
# prints the relative MSE on the test frame against its reference and writes the network's
# output on it as DATA_DIR/test-output.exr (and the network as DATA_DIR/net.pt).
#   train.py DATA_DIR TEST_16SPP_DENOISED.exr REFERENCE.exr EDGE_MASK.exr
# (the test files as tools/denoise-quality.sh writes them); STEPS, LR, NSRC, KS, CH, THREADS from
# the environment (also P, the patch size, 64, and LCLAMP, the loss clamp, 4); LOAD=NET.pt
# STEPS=0 evaluates a trained network on other test frames.
import glob, os, sys, time, numpy as np, torch, torch.nn as nn, torch.nn.functional as F
import OpenImageIO as oiio
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
import image_metrics as im
torch.set_num_threads(int(os.environ.get('THREADS', '2'))); torch.manual_seed(0); np.random.seed(0)
NSRC = int(os.environ.get('NSRC', '1')); K = int(os.environ.get('KS', '9')); CH = int(os.environ.get('CH', '32'))
def load(path):
    inp = oiio.ImageInput.open(path); spec = inp.spec(); px = inp.read_image(format="float"); inp.close()
    return {n: px[:, :, i] for i, n in enumerate(spec.channelnames)}
def stack(d, names): return np.stack([np.nan_to_num(d[n], nan=0.0, posinf=0.0, neginf=0.0) for n in names], 0)
def features(d):
    c = stack(d, ['noisy.R', 'noisy.G', 'noisy.B']); nf = stack(d, ['R', 'G', 'B'])
    a = stack(d, ['Albedo.R', 'Albedo.G', 'Albedo.B']); n = stack(d, ['N.X', 'N.Y', 'N.Z'])
    z = stack(d, ['Z'])[0]; zf = z[np.isfinite(z) & (z > 0) & (z < 1e9)]
    med = np.median(zf) if zf.size else 1.0
    z = np.log(np.clip(np.where((z > 0) & (z < 1e9), z, 1e9) / med, 1e-3, 1e3))[None]
    e = stack(d, ['even.R', 'even.G', 'even.B']); o = stack(d, ['odd.R', 'odd.G', 'odd.B'])
    var = ((e - o) ** 2 / 4).mean(0, keepdims=True)
    lum = c.mean(0, keepdims=True)
    rv = np.log1p(var / (lum ** 2 + 1e-2))
    x = np.concatenate([np.log1p(np.maximum(c, 0)), np.log1p(np.maximum(nf, 0)), a, n, z / 3, rv], 0).astype(np.float32)
    return x, np.maximum(c, 0).astype(np.float32), np.maximum(nf, 0).astype(np.float32)
class Net(nn.Module):
    def __init__(self):
        super().__init__()
        dil = [1, 2, 4, 8, 4, 2]
        self.inp = nn.Conv2d(14, CH, 3, padding=1)
        self.mid = nn.ModuleList([nn.Conv2d(CH, CH, 3, padding=d, dilation=d) for d in dil])
        self.out = nn.Conv2d(CH, NSRC * K * K, 1); nn.init.zeros_(self.out.weight); nn.init.zeros_(self.out.bias)
    def forward(self, x, c, nf):
        h = F.relu(F.group_norm(self.inp(x), 4))
        for m in self.mid: h = F.relu(F.group_norm(m(h), 4))
        w = torch.softmax(4.0 * torch.tanh(self.out(h) / 4.0), 1)  # B, NSRC K^2, H, W
        B, _, H, W = c.shape
        pc = F.unfold(F.pad(c, [K // 2] * 4, mode='replicate'), K).view(B, 3, K * K, H, W)
        pn = F.unfold(F.pad(nf, [K // 2] * 4, mode='replicate'), K).view(B, 3, K * K, H, W)
        p = torch.cat([pc, pn], 2) if NSRC == 2 else pc
        return (p * w[:, None]).sum(2)
def relmse(x, ref, mask=None):  # on channels-first arrays
    return im.relmse(x.transpose(1, 2, 0), ref.transpose(1, 2, 0), mask)
# test: the grid, 16 spp seed 1 (noisy + NFOR + features), against the 1024 spp reference
tx, tc, tn = features(load(sys.argv[2]))
tref = stack(load(sys.argv[3]), ['R', 'G', 'B'])
tmask = im.read_mask(sys.argv[4], tref.shape[1:])
print('test: noisy %.3e nfor %.3e (edges %.3e)' % (relmse(tc, tref), relmse(tn, tref), relmse(tn, tref, tmask)), flush=True)
data = {}
def refresh():
    for f in sorted(glob.glob(os.path.join(sys.argv[1], '*-target.exr'))):
        name = f[:-len('-target.exr')]
        if name in data: continue
        try:
            x, c, nf = features(load(name + '-input.exr'))
            t = np.minimum(stack(load(f), ['R', 'G', 'B']), 50.0).astype(np.float32)
            data[name] = (x, c, nf, t)
        except Exception as ex: print('skip', name, ex)
net = Net()
if os.environ.get('LOAD'): net.load_state_dict(torch.load(os.environ['LOAD']))  # with STEPS=0: evaluate a trained network
opt = torch.optim.Adam(net.parameters(), lr=float(os.environ.get('LR', '1e-3')))
P = int(os.environ.get('P', '64')); BATCH = 8; steps = int(os.environ.get('STEPS', '1500'))
def evaluate():
    with torch.no_grad():
        out = net(torch.from_numpy(tx)[None], torch.from_numpy(tc)[None], torch.from_numpy(tn)[None])[0].numpy()
    return relmse(out, tref), relmse(out, tref, tmask), out
t0 = time.time(); run = 0
for step in range(steps + 1):
    if step % 50 == 0:
        refresh()
        r, re, out = evaluate()
        print('step %d images %d loss %.4e test %.3e edges %.3e  %.0fs' % (step, len(data), run / 50, r, re, time.time() - t0), flush=True)
        run = 0
        im.write(os.path.join(sys.argv[1], 'test-output.exr'), out.transpose(1, 2, 0), ['R', 'G', 'B'])
        if steps > 0: torch.save(net.state_dict(), os.path.join(sys.argv[1], 'net.pt'))
    if step == steps: break
    names = list(data); xs, cs, ns, ts = [], [], [], []
    for b in range(BATCH):
        x, c, nf, t = data[names[np.random.randint(len(names))]]
        y0 = np.random.randint(0, x.shape[1] - P); x0 = np.random.randint(0, x.shape[2] - P)
        sl = (slice(None), slice(y0, y0 + P), slice(x0, x0 + P))
        xs.append(x[sl]); cs.append(c[sl]); ns.append(nf[sl]); ts.append(t[sl])
    X, C, N, T = (torch.from_numpy(np.stack(v)) for v in (xs, cs, ns, ts))
    out = net(X, C, N)
    loss = ((out - T) ** 2 / (N ** 2 + 1e-2)).clamp(max=float(os.environ.get('LCLAMP', '4'))).mean()
    opt.zero_grad(); loss.backward(); torch.nn.utils.clip_grad_norm_(net.parameters(), 1.0); opt.step(); run += float(loss)
    if step == int(steps * 0.7):
        for g in opt.param_groups: g['lr'] *= 0.3
