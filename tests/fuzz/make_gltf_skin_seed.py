#!/usr/bin/env python3
"""Writes corpus/fuzz_gltf/seed_skin.glb: a small GLB with a skin and morph
targets for fuzz_gltf to start from.  A strip of six vertices skinned to
two joints (byte joints, normalized byte weights, a second influence set
of short joints and float weights), inverse bind matrices, a joint node
outside the scene, a quantized (normalized short) morph target and a
sparse one, mesh weights and node weights, and a node drawing the mesh
unskinned."""
import json, os, struct

def pad(b, fill=b'\0'):
    return b + fill * (-len(b) % 4)

views, accessors, chunks = [], [], []

def add(data, **fields):
    """data (bytes) as bufferView i and, unless fields is empty, accessor i."""
    offset = sum(len(c) for c in chunks)
    chunks.append(pad(data))
    views.append({'buffer': 0, 'byteOffset': offset, 'byteLength': len(data)})
    if fields:
        accessors.append({'bufferView': len(views) - 1, **fields})
    return len(accessors) - 1

pos = [(-0.5, 0, 0), (0.5, 0, 0), (-0.5, 1, 0), (0.5, 1, 0), (-0.5, 2, 0), (0.5, 2, 0)]
add(b''.join(struct.pack('<3f', *p) for p in pos), componentType=5126, count=6, type='VEC3',
    min=[-0.5, 0, 0], max=[0.5, 2, 0])
add(struct.pack('<18f', *([0, 0, 1] * 6)), componentType=5126, count=6, type='VEC3')
add(struct.pack('<24f', *([1, 0, 0, 1] * 6)), componentType=5126, count=6, type='VEC4')
add(struct.pack('<12H', 0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4), componentType=5123, count=12,
    type='SCALAR')
add(bytes([0, 1, 0, 0] * 2 + [0, 1, 0, 0] * 2 + [1, 0, 0, 0] * 2), componentType=5121, count=6,
    type='VEC4')
add(bytes([255, 0, 0, 0] * 2 + [128, 127, 0, 0] * 2 + [255, 0, 0, 0] * 2), componentType=5121,
    normalized=True, count=6, type='VEC4')
add(struct.pack('<24H', *([1, 0, 0, 0] * 6)), componentType=5123, count=6, type='VEC4')
add(struct.pack('<24f', *([0, 0, 0, 0] * 6)), componentType=5126, count=6, type='VEC4')
ibm = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1]
add(struct.pack('<32f', *ibm), componentType=5126, count=2, type='MAT4')
# Morph target 0: normalized shorts (KHR_mesh_quantization), every vertex up z.
add(struct.pack('<24h', *([0, 0, 16384, 0] * 6)), componentType=5122, normalized=True, count=6,
    type='VEC3', byteOffset=0)
views[-1]['byteStride'] = 8
# Morph target 1: sparse, vertex 4 moved along x.
add(struct.pack('<H', 4) + b'\0\0')
add(struct.pack('<3f', -1, 0, 0))
accessors.append({'componentType': 5126, 'count': 6, 'type': 'VEC3',
                  'sparse': {'count': 1, 'indices': {'bufferView': len(views) - 2,
                                                     'componentType': 5123},
                             'values': {'bufferView': len(views) - 1}}})
h = 0.7071067811865476
doc = {
    'asset': {'version': '2.0', 'generator': 'tests/fuzz/make_gltf_skin_seed.py'},
    'extensionsUsed': ['KHR_mesh_quantization'],
    'scene': 0,
    'scenes': [{'nodes': [0, 1, 4]}],
    'nodes': [
        {'mesh': 0, 'skin': 0, 'translation': [9, 0, 0], 'weights': [0.5, 1]},
        {'translation': [0, 0, -1], 'children': [2]},
        {'children': [3]},
        {'translation': [0, 1, 0], 'rotation': [0, 0, h, h]},
        {'mesh': 0, 'translation': [2, 0, 0]},
        {'translation': [0, 3, 0]},
    ],
    'skins': [{'joints': [2, 3, 5], 'inverseBindMatrices': 8, 'skeleton': 1}],
    'meshes': [{'primitives': [{'attributes': {'POSITION': 0, 'NORMAL': 1, 'TANGENT': 2,
                                               'JOINTS_0': 4, 'WEIGHTS_0': 5, 'JOINTS_1': 6,
                                               'WEIGHTS_1': 7},
                                'indices': 3, 'targets': [{'POSITION': 9, 'NORMAL': 1},
                                                          {'POSITION': 10}]}],
                'weights': [0.25, 0]}],
    'accessors': accessors,
    'bufferViews': views,
}
# The skin has three joints but two inverse bind matrices: give it three.
ibm3 = add(struct.pack('<48f', *(ibm + [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -3, 0, 1])),
           componentType=5126, count=3, type='MAT4')
doc['skins'][0]['inverseBindMatrices'] = ibm3
binary = b''.join(chunks)
doc['buffers'] = [{'byteLength': len(binary)}]
text = pad(json.dumps(doc, separators=(',', ':')).encode(), b' ')
glb = (struct.pack('<4sII', b'glTF', 2, 12 + 8 + len(text) + 8 + len(binary)) +
       struct.pack('<I4s', len(text), b'JSON') + text + struct.pack('<I4s', len(binary), b'BIN\0') +
       binary)
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'corpus', 'fuzz_gltf',
                   'seed_skin.glb')
with open(out, 'wb') as f:
    f.write(glb)
