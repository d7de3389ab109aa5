#!/usr/bin/env python3
# Adds an animation 'bounce' to a .glb: node NODE rises by RISE (in its parent's units) and
# comes back over 2 seconds (keys at 0, 1, 2 s). For measuring frame sequences on a large
# still scene with one moving part (docs/performance.md). Keep RISE small against the scene:
# without a camera in the file, the automatic camera frames everything the animation reaches.
# Usage: tools/add-animation.py IN.glb OUT.glb NODE RISE
import json, struct, sys
if len(sys.argv) != 5:
    sys.exit("usage: add-animation.py IN.glb OUT.glb NODE RISE")
src, dst, node, rise = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
b = open(src, 'rb').read()
jl = struct.unpack('<I', b[12:16])[0]
j = json.loads(b[20:20 + jl])
bin_start = 20 + jl + 8
binl = struct.unpack('<I', b[20 + jl:24 + jl])[0]
bin_ = bytearray(b[bin_start:bin_start + binl])
while len(bin_) % 4: bin_.append(0)
off = len(bin_)
times = [0.0, 1.0, 2.0]
t0 = j['nodes'][node].get('translation', [0, 0, 0])
vals = [t0, [t0[0], t0[1] + rise, t0[2]], t0]
bin_ += struct.pack('<3f', *times) + struct.pack('<9f', *[x for v in vals for x in v])
j['buffers'][0]['byteLength'] = len(bin_)
bv = len(j['bufferViews'])
j['bufferViews'] += [{'buffer': 0, 'byteOffset': off, 'byteLength': 12}, {'buffer': 0, 'byteOffset': off + 12, 'byteLength': 36}]
ac = len(j['accessors'])
j['accessors'] += [{'bufferView': bv, 'componentType': 5126, 'count': 3, 'type': 'SCALAR', 'min': [0.0], 'max': [2.0]},
                   {'bufferView': bv + 1, 'componentType': 5126, 'count': 3, 'type': 'VEC3'}]
j['animations'] = [{'name': 'bounce', 'samplers': [{'input': ac, 'output': ac + 1}], 'channels': [{'sampler': 0, 'target': {'node': node, 'path': 'translation'}}]}]
js = json.dumps(j).encode()
while len(js) % 4: js += b' '
out = struct.pack('<4sII', b'glTF', 2, 12 + 8 + len(js) + 8 + len(bin_)) + struct.pack('<I4s', len(js), b'JSON') + js + struct.pack('<I4s', len(bin_), b'BIN\x00') + bytes(bin_)
open(dst, 'wb').write(out)
