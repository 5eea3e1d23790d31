#!/usr/bin/env python3
"""Writes corpus/fuzz_gltf/seed_pointer.gltf: KHR_animation_pointer and
KHR_node_visibility for fuzz_gltf to start from.  Two quads and a camera
and a spot light; one animation whose channels point at a base color
(LINEAR), a roughness (normalized unsigned bytes), an emissive strength
(CUBICSPLINE), a texture transform's rotation and offset, the camera's
yfov, the light's intensity and outer cone, a node's translation, and a
hidden node's `visible` (STEP, unsigned bytes).  Then
corpus/fuzz_gltf/seed_spec_gloss.gltf: the same with a material of
KHR_materials_pbrSpecularGlossiness (below)."""
import base64, json, os, struct

def pad(b):
    return b + b'\0' * (-len(b) % 4)

data, views, accessors = b'', [], []

def add(raw, ctype, kind, count, normalized=False):
    """raw (bytes) as bufferView i and accessor i; returns i."""
    global data
    views.append({'buffer': 0, 'byteOffset': len(data), 'byteLength': len(raw)})
    a = {'bufferView': len(views) - 1, 'componentType': ctype, 'count': count, 'type': kind}
    if normalized:
        a['normalized'] = True
    accessors.append(a)
    data += pad(raw)
    return len(accessors) - 1

def floats(*v):
    return struct.pack('<%df' % len(v), *v)

pos = add(floats(-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0), 5126, 'VEC3', 4)
accessors[pos].update({'min': [-1, -1, 0], 'max': [1, 1, 0]})
uv = add(floats(0, 0, 1, 0, 1, 1, 0, 1), 5126, 'VEC2', 4)
idx = add(struct.pack('<6H', 0, 1, 2, 0, 2, 3), 5123, 'SCALAR', 6)
t2 = add(floats(0, 2), 5126, 'SCALAR', 2)
t1 = add(floats(0, 1), 5126, 'SCALAR', 2)
color = add(floats(1, 0, 0, 1, 0, 0, 1, 1), 5126, 'VEC4', 2)
rough = add(bytes([0, 255]), 5121, 'SCALAR', 2, normalized=True)
strength = add(floats(0, 0.5, 2, -1, 4, 0), 5126, 'SCALAR', 6)   # in, value, out a key
turn = add(floats(0, 1.5), 5126, 'SCALAR', 2)
offset = add(floats(0, 0, 0.25, 0.5), 5126, 'VEC2', 2)
fov = add(floats(0.6, 1.0), 5126, 'SCALAR', 2)
power = add(floats(5, 0), 5126, 'SCALAR', 2)
cone = add(floats(0.5, 1.2), 5126, 'SCALAR', 2)
move = add(floats(0, 0, 0, 1, 1, 0), 5126, 'VEC3', 2)
shown = add(bytes([0, 1]), 5121, 'SCALAR', 2)

def pointer(sampler, target):
    return {'sampler': sampler, 'target': {'path': 'pointer', 'extensions': {
        'KHR_animation_pointer': {'pointer': target}}}}

samplers = [{'input': t2, 'output': color}, {'input': t2, 'output': rough},
            {'input': t2, 'output': strength, 'interpolation': 'CUBICSPLINE'},
            {'input': t2, 'output': turn}, {'input': t2, 'output': offset},
            {'input': t2, 'output': fov}, {'input': t2, 'output': power},
            {'input': t2, 'output': cone}, {'input': t2, 'output': move},
            {'input': t1, 'output': shown, 'interpolation': 'STEP'}]
transform = '/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform'
channels = [pointer(0, '/materials/0/pbrMetallicRoughness/baseColorFactor'),
            pointer(1, '/materials/0/pbrMetallicRoughness/roughnessFactor'),
            pointer(2, '/materials/1/extensions/KHR_materials_emissive_strength/emissiveStrength'),
            pointer(3, transform + '/rotation'), pointer(4, transform + '/offset'),
            pointer(5, '/cameras/0/perspective/yfov'),
            pointer(6, '/extensions/KHR_lights_punctual/lights/0/intensity'),
            pointer(7, '/extensions/KHR_lights_punctual/lights/0/spot/outerConeAngle'),
            pointer(8, '/nodes/0/translation'),
            pointer(9, '/nodes/1/extensions/KHR_node_visibility/visible')]
doc = {
    'asset': {'version': '2.0'},
    'extensionsUsed': ['KHR_animation_pointer', 'KHR_node_visibility', 'KHR_lights_punctual',
                       'KHR_texture_transform', 'KHR_materials_emissive_strength'],
    'extensions': {'KHR_lights_punctual': {'lights': [
        {'type': 'spot', 'intensity': 5, 'spot': {'outerConeAngle': 0.5}}]}},
    'buffers': [{'byteLength': len(data), 'uri': 'data:application/octet-stream;base64,'
                 + base64.b64encode(data).decode()}],
    'bufferViews': views, 'accessors': accessors,
    'textures': [{}],
    'materials': [{'pbrMetallicRoughness': {'baseColorFactor': [1, 0, 0, 1], 'baseColorTexture': {
                       'index': 0, 'extensions': {'KHR_texture_transform': {'scale': [2, 1]}}}}},
                  {'emissiveFactor': [1, 1, 0], 'extensions': {
                      'KHR_materials_emissive_strength': {'emissiveStrength': 0.5}}}],
    'meshes': [{'primitives': [{'attributes': {'POSITION': pos, 'TEXCOORD_0': uv},
                                'indices': idx, 'material': m}]} for m in (0, 1)],
    'cameras': [{'type': 'perspective', 'perspective': {'yfov': 0.6, 'znear': 0.1}}],
    'nodes': [{'mesh': 0},
              {'mesh': 1, 'translation': [2.5, 0, 0], 'children': [2],
               'extensions': {'KHR_node_visibility': {'visible': False}}},
              {'mesh': 0, 'translation': [0, 2.5, 0]},
              {'camera': 0, 'translation': [0, 0, 6]},
              {'translation': [0, 0, 4], 'extensions': {'KHR_lights_punctual': {'light': 0}}}],
    'scenes': [{'nodes': [0, 1, 3, 4]}],
    'animations': [{'name': 'pointers', 'samplers': samplers, 'channels': channels}],
}
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'corpus', 'fuzz_gltf',
                   'seed_pointer.gltf')
with open(out, 'w') as f:
    json.dump(doc, f, separators=(',', ':'))

# seed_spec_gloss.gltf: the same with a third material of
# KHR_materials_pbrSpecularGlossiness (factors, a diffuse texture with a
# transform, a specular-glossiness texture, a metallic-roughness fallback
# the reader drops, MASK) on mesh 0, and the pointers of its base color
# (skipped with a warning) and of its diffuse texture's rotation (animated).
def png_2x2():
    """A 2 x 2 RGBA PNG, for the textures to be read rather than dropped."""
    import zlib
    def chunk(kind, body):
        return (struct.pack('>I', len(body)) + kind + body
                + struct.pack('>I', zlib.crc32(kind + body) & 0xffffffff))
    rows = b''.join(b'\0' + b''.join(bytes([255, 120 * y, 200 * x, 180 + 70 * x])
                                      for x in range(2)) for y in range(2))
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 2, 2, 8, 6, 0, 0, 0))
            + chunk(b'IDAT', zlib.compress(rows)) + chunk(b'IEND', b''))

doc['images'] = [{'uri': 'data:image/png;base64,' + base64.b64encode(png_2x2()).decode()}]
doc['textures'] = [{'source': 0}]
doc['extensionsUsed'].append('KHR_materials_pbrSpecularGlossiness')
doc['materials'].append({
    'extensions': {'KHR_materials_pbrSpecularGlossiness': {
        'diffuseFactor': [0.5, 1, 0.2, 1], 'specularFactor': [1, 0.8, 0.2],
        'glossinessFactor': 0.7,
        'diffuseTexture': {'index': 0, 'extensions': {'KHR_texture_transform': {
            'offset': [0.5, 0], 'scale': [2, 2], 'rotation': 0.3}}},
        'specularGlossinessTexture': {'index': 0, 'texCoord': 0}}},
    'pbrMetallicRoughness': {'baseColorFactor': [0, 0, 1, 1]},
    'alphaMode': 'MASK', 'alphaCutoff': 0.4})
doc['meshes'][0]['primitives'][0]['material'] = 2
channels[0] = pointer(0, '/materials/2/pbrMetallicRoughness/baseColorFactor')
channels[3] = pointer(3, '/materials/2/extensions/KHR_materials_pbrSpecularGlossiness/'
                         'diffuseTexture/extensions/KHR_texture_transform/rotation')
with open(os.path.join(os.path.dirname(out), 'seed_spec_gloss.gltf'), 'w') as f:
    json.dump(doc, f, separators=(',', ':'))
