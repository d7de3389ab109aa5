#!/usr/bin/env python3
"""Makes the compressed test files in this folder from the Khronos samples in scenes/khronos/
(and the Draco RiggedSimple there for the corrupt Draco cases). Needs Debian's gltfpack and
webp (cwebp). The files are committed, so tests never run this; see README.md."""
import base64, json, os, shutil, struct, subprocess

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.normpath(os.path.join(here, "..", "..", ".."))
khronos = os.path.join(root, "scenes", "khronos")
malformed = os.path.join(root, "tests", "data", "malformed")


def out(name):
    return os.path.join(here, name)


def gltfpack(model, name, *options):
    folder = "glTF" if model in ("MeshPrimitiveModes", "SimpleMorph") else "glTF-Binary"
    src = os.path.join(khronos, model, folder, model + (".gltf" if folder == "glTF" else ".glb"))
    subprocess.run(["gltfpack", "-i", src, "-o", out(name), *options], check=True, stdout=subprocess.DEVNULL)


def read_glb(path):
    b = open(path, "rb").read()
    n = struct.unpack("<I", b[12:16])[0]
    j = json.loads(b[20:20 + n])
    rest = b[20 + n:]
    return j, rest[8:8 + struct.unpack("<I", rest[:4])[0]] if rest else b""


def write_glb(path, j, bin_chunk):
    js = json.dumps(j, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    bin_chunk += b"\0" * (-len(bin_chunk) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(bin_chunk), 0x004E4942) + bin_chunk
    open(path, "wb").write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


def write_json(path, j):
    with open(path, "w") as f:
        json.dump(j, f, indent=1)
        f.write("\n")


def meshopt_files():
    gltfpack("BoxAnimated", "boxanimated_meshopt.glb", "-cc")  # OCTAHEDRAL, QUATERNION, EXPONENTIAL, TRIANGLES
    gltfpack("MeshPrimitiveModes", "meshprimitivemodes_meshopt.glb", "-cc")  # INDICES (lines)
    gltfpack("RiggedSimple", "riggedsimple_quantized.glb")  # KHR_mesh_quantization alone
    gltfpack("SimpleMorph", "simplemorph_quantized.glb")  # quantized morph targets and weight keys
    # A bad header: the first compressed vertex stream's header byte (0xa0: version 0) zeroed.
    j, data = read_glb(out("boxanimated_meshopt.glb"))
    view = next(v for v in j["bufferViews"] if v.get("extensions", {}).get("EXT_meshopt_compression", {}).get("mode") == "ATTRIBUTES")
    at = view["extensions"]["EXT_meshopt_compression"].get("byteOffset", 0)
    data = bytearray(data)
    assert data[at] == 0xA0
    data[at] = 0
    write_glb(os.path.join(malformed, "meshopt_bad_header.glb"), j, bytes(data))
    # Properties meshoptimizer would assert on: an ATTRIBUTES stride not a multiple of 4, and a
    # count far more than the compressed bytes can hold.
    j, data = read_glb(out("boxanimated_meshopt.glb"))
    j["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 6
    write_glb(os.path.join(malformed, "meshopt_bad_stride.glb"), j, data)
    j, data = read_glb(out("boxanimated_meshopt.glb"))
    j["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 100000000
    j["bufferViews"][0]["byteLength"] = 400000000
    write_glb(os.path.join(malformed, "meshopt_huge_count.glb"), j, data)


def texture_files():
    """BoxTextured with its PNG beside a lossless WebP and a stub KTX2 image."""
    j, data = read_glb(os.path.join(khronos, "BoxTextured", "glTF-Binary", "BoxTextured.glb"))
    png_view = j["bufferViews"][j["images"][0]["bufferView"]]
    png = data[png_view.get("byteOffset", 0):png_view.get("byteOffset", 0) + png_view["byteLength"]]
    open(out("boxtextured.png"), "wb").write(png)
    subprocess.run(["cwebp", "-quiet", "-lossless", "-exact", out("boxtextured.png"), "-o", out("boxtextured.webp")], check=True)
    os.remove(out("boxtextured.png"))
    open(out("boxtextured.bin"), "wb").write(data)
    j["buffers"] = [{"byteLength": len(data), "uri": "boxtextured.bin"}]
    png_image = j["images"][0]
    # A KTX2 identifier and header (BasisLZ, 4x4, one level) without data: tessera never
    # decodes KTX2, it only recognises it and uses the texture's fallback.
    header = struct.pack("<9I", 0, 1, 4, 4, 0, 0, 1, 1, 1)
    open(out("stub.ktx2"), "wb").write(bytes([0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A]) + header + bytes(48))

    def variant(name, extension, uri, fallback, required):
        k = json.loads(json.dumps(j))
        k["images"] = [png_image, {"uri": uri}]  # image 1: the extension's
        k["textures"][0]["extensions"] = {extension: {"source": 1}}
        if not fallback:
            del k["textures"][0]["source"]
        k["extensionsUsed"] = [extension]
        if required:
            k["extensionsRequired"] = [extension]
        write_json(out(name), k)

    variant("boxtextured_webp.gltf", "EXT_texture_webp", "boxtextured.webp", True, False)
    variant("boxtextured_webp_only.gltf", "EXT_texture_webp", "boxtextured.webp", False, True)
    variant("boxtextured_basisu_fallback.gltf", "KHR_texture_basisu", "stub.ktx2", True, False)
    variant("boxtextured_basisu_only.gltf", "KHR_texture_basisu", "stub.ktx2", False, True)


def draco_files():
    """Corrupt copies of Khronos' Draco RiggedSimple, with the buffer as a data URI."""
    src = os.path.join(khronos, "RiggedSimple", "glTF-Draco")
    j = json.load(open(os.path.join(src, "RiggedSimple.gltf")))
    data = open(os.path.join(src, "RiggedSimple0.bin"), "rb").read()
    view = j["bufferViews"][j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"]]

    def save(name, k, d):
        k["buffers"] = [{"byteLength": len(d), "uri": "data:application/octet-stream;base64," + base64.b64encode(d).decode()}]
        write_json(os.path.join(malformed, name), k)

    truncated = json.loads(json.dumps(j))
    truncated["bufferViews"][j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"]]["byteLength"] = view["byteLength"] // 2
    save("draco_truncated.gltf", truncated, data)
    corrupt = bytearray(data)
    start = view.get("byteOffset", 0)
    corrupt[start:start + 5] = b"DRACX"  # the stream's magic
    save("draco_corrupt.gltf", json.loads(json.dumps(j)), bytes(corrupt))


if __name__ == "__main__":
    meshopt_files()
    texture_files()
    draco_files()
