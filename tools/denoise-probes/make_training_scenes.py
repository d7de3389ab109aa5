# Random scenes after RTOW's cover (its own random layout, other seeds), written as glTF with
# scenes/paper/make_paper_scenes.py's writer: training content for the learned-denoiser probe that
# is not the scene it is measured on (grid-of-spheres.gltf).
#   make_training_scenes.py OUT_DIR FIRST_SEED END_SEED
import os, random, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "paper"))
import make_paper_scenes as m

def random_cover(seed):
    rng = random.Random(seed)
    spheres = []
    for a in range(-11, 11):
        for b in range(-11, 11):
            choose = rng.random()
            c = (a + 0.9 * rng.random(), 0.2, b + 0.9 * rng.random())
            if ((c[0] - 4) ** 2 + c[2] ** 2) ** 0.5 <= 0.9:
                continue
            i = len(spheres)
            if choose < 0.8:
                rgb = tuple(round(rng.random() * rng.random(), 3) for _ in range(3))
                name, key = "Diffuse %03d" % i, m.diffuse(rgb)
            elif choose < 0.95:
                rgb = tuple(round(0.5 + 0.5 * rng.random(), 3) for _ in range(3))
                name, key = "Metal %03d" % i, m.metal(rgb, round(0.5 * rng.random(), 3))
            else:
                name, key = "Glass ior 1.5", m.glass(1.5, 2.0)
            spheres.append(("Sphere %03d" % i, c, 0.2, name, key, False))
    spheres.append(("Big glass", (0.0, 1.0, 0.0), 1.0, "Glass ior 1.5", m.glass(1.5, 2.0), False))
    spheres.append(("Big diffuse", (-4.0, 1.0, 0.0), 1.0, "Diffuse big", m.diffuse((0.4, 0.2, 0.1)), False))
    spheres.append(("Big metal", (4.0, 1.0, 0.0), 1.0, "Metal big", m.metal((0.7, 0.6, 0.5), 0.0), False))
    ground = tuple(round(0.3 + 0.4 * rng.random(), 3) for _ in range(3))
    return m.make_scene("cover-%d" % seed, "Random cover %d" % seed, m.GRID_CAMERA, spheres,
                        (m.BIG_GROUND_CENTRE, m.BIG_GROUND_RADIUS, "Ground", m.diffuse(ground)), "training scene")

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
for seed in range(int(sys.argv[2]), int(sys.argv[3])):
    for name, data in random_cover(seed).items():
        with open(os.path.join(out, name), "wb" if isinstance(data, bytes) else "w") as f:
            f.write(data)
    print("cover-%d" % seed)
