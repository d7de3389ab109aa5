#!/usr/bin/env python3
"""Runs tessera on a directory of glTF files and tabulates its verdicts against the Khronos
glTF-Validator's, by the policy in docs/reliability.md:

  valid (0 errors)        must load (`tessera info`, exit 0) and render (16x16, 1 spp, exit 0);
  invalid (1+ errors)     must be refused (exit 2, one line) or load with at least one warning
                          (the broken objects are ones the scene does not use).

Anything else is a disagreement: a valid file refused, an invalid file loaded in silence, or an
exit code other than 0 and 2 (a crash). Use: tools/conformance-corpus.py DIR [TESSERA]
(TESSERA defaults to build/tessera). The validator (tools/gltf-validate.js, npm package
gltf-validator) is installed into tools/node_modules on first use, as
tools/validate-generated-scenes.sh does. Exits 1 when there is a disagreement."""
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
TOOLS = ROOT / "tools"


def validator_errors(files):
    """The validator's error count for each file, by running it once over all of them."""
    if not (TOOLS / "node_modules" / "gltf-validator").is_dir():
        subprocess.run(["npm", "install", "--silent", "--no-audit", "--no-fund", "--prefix", str(TOOLS),
                        "gltf-validator@2.0.0-dev.3.10"], check=True, stdout=sys.stderr)
    env = dict(os.environ, NODE_PATH=str(TOOLS / "node_modules"))
    out = subprocess.run(["node", str(TOOLS / "gltf-validate.js")] + [str(f) for f in files], env=env,
                         capture_output=True, text=True).stdout
    counts = [int(line.split(" errors ")[1].split()[0]) for line in out.splitlines()
              if not line.startswith(" ") and " errors " in line]
    if len(counts) != len(files):
        sys.exit(f"conformance-corpus: the validator reported on {len(counts)} of {len(files)} files")
    return counts


def run(args):
    try:
        r = subprocess.run(args, capture_output=True, text=True, timeout=120)
        return r.returncode, r.stderr
    except subprocess.TimeoutExpired:
        return "timeout", ""


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    corpus = pathlib.Path(sys.argv[1])
    tessera = sys.argv[2] if len(sys.argv) > 2 else str(ROOT / "build" / "tessera")
    files = sorted(p for p in corpus.rglob("*") if p.suffix in (".gltf", ".glb"))
    if not files:
        sys.exit(f"conformance-corpus: no .gltf or .glb files under {corpus}")
    table = {}
    disagreements = []
    with tempfile.TemporaryDirectory() as tmp:
        for f, errors in zip(files, validator_errors(files)):
            info_rc, info_err = run([tessera, "info", str(f)])
            render_rc, render_err = run([tessera, "render", str(f), "--width", "16", "--height", "16", "--spp", "1",
                                         "-o", os.path.join(tmp, "out.exr")])
            warned = "tessera: warning:" in info_err
            refused = info_rc == 2 and len(info_err.strip().splitlines()) == 1
            if errors == 0:
                verdict = "valid, loads and renders" if info_rc == 0 and render_rc == 0 else "DISAGREE: valid, refused"
            elif refused and render_rc == 2:
                verdict = "invalid, refused"
            elif info_rc == 0 and render_rc == 0 and warned:
                verdict = "invalid, loads with warnings"
            elif info_rc == 0 and render_rc == 0:
                verdict = "DISAGREE: invalid, loads in silence"
            else:
                verdict = f"DISAGREE: exit {info_rc} (info) and {render_rc} (render)"
            table[verdict] = table.get(verdict, 0) + 1
            if verdict.startswith("DISAGREE"):
                first = (info_err or render_err).strip().splitlines()
                disagreements.append(f"{f}: {verdict} ({errors} validator errors) {first[0] if first else ''}")
    for line in disagreements:
        print(line)
    print(f"{len(files)} files")
    for verdict, n in sorted(table.items()):
        print(f"  {n:4d}  {verdict}")
    return 1 if disagreements else 0


if __name__ == "__main__":
    sys.exit(main())
