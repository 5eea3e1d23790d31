// make-assets.mjs - writes the comparison's test assets into a directory:
// small .glb files for the glTF cases issue 35 names (the material model's
// tell-tale cases) and a Radiance .hdr sky to light them.
//
//   node make-assets.mjs OUTDIR
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

// --- Geometry: positions, normals and 16-bit indices, counter-clockwise
// seen from outside (glTF's front face).

function cube(half) {
    const faces = [
        // normal, then the two axes spanning the face (u x v = normal)
        [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
        [[-1, 0, 0], [0, 0, 1], [0, 1, 0]],
        [[0, 1, 0], [0, 0, 1], [1, 0, 0]],
        [[0, -1, 0], [1, 0, 0], [0, 0, 1]],
        [[0, 0, 1], [1, 0, 0], [0, 1, 0]],
        [[0, 0, -1], [0, 1, 0], [1, 0, 0]],
    ];
    const pos = [], nrm = [], idx = [];
    for (const [n, u, v] of faces) {
        const base = pos.length / 3;
        for (const [su, sv] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
            for (let k = 0; k < 3; k++) {
                pos.push(half * (n[k] + su * u[k] + sv * v[k]));
                nrm.push(n[k]);
            }
        }
        idx.push(base, base + 1, base + 2, base, base + 2, base + 3);
    }
    return { pos, nrm, idx };
}

// With `uv`: texture coordinates (u around +Y, v from the north pole down,
// as glTF's v runs down the image) and tangents along u, (cos phi, 0,
// -sin phi), handedness 1.
function sphere(radius, slices, stacks, uv = false) {
    const pos = [], nrm = [], idx = [], uvs = [], tan = [];
    for (let i = 0; i <= stacks; i++) {
        const theta = (Math.PI * i) / stacks;   // from the north pole
        for (let j = 0; j <= slices; j++) {
            const phi = (2 * Math.PI * j) / slices;
            const n = [Math.sin(theta) * Math.sin(phi), Math.cos(theta), Math.sin(theta) * Math.cos(phi)];
            nrm.push(...n);
            pos.push(...n.map((c) => c * radius));
            uvs.push(j / slices, i / stacks);
            tan.push(Math.cos(phi), 0, -Math.sin(phi), 1);
        }
    }
    const row = slices + 1;
    for (let i = 0; i < stacks; i++) {
        for (let j = 0; j < slices; j++) {
            const a = i * row + j, b = a + row;
            if (i > 0) idx.push(a, b, a + 1);
            if (i < stacks - 1) idx.push(a + 1, b, b + 1);
        }
    }
    return uv ? { pos, nrm, idx, uvs, tan } : { pos, nrm, idx };
}

// A square of side 2 * half in the plane y = 0, facing +y.
function plane(half) {
    const pos = [-half, 0, half, half, 0, half, half, 0, -half, -half, 0, -half];
    return { pos, nrm: [0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0], idx: [0, 1, 2, 0, 2, 3] };
}

// Shapes as one, each moved by its offset.
function merge(...parts) {
    const out = { pos: [], nrm: [], idx: [] };
    for (const [shape, offset] of parts) {
        const base = out.pos.length / 3;
        shape.pos.forEach((c, i) => out.pos.push(c + offset[i % 3]));
        out.nrm.push(...shape.nrm);
        out.idx.push(...shape.idx.map((i) => i + base));
    }
    return out;
}

// The unit quaternion [x, y, z, w] turning a node's -Z to the direction d.
function aimQuaternion(d) {
    const len = Math.hypot(...d), b = d.map((c) => c / len);
    // a = (0, 0, -1): a x b = (b.y, -b.x, 0), a . b = -b.z
    const q = [b[1], -b[0], 0, 1 - b[2]];
    const ql = Math.hypot(...q);
    return q.map((c) => c / ql);
}

// --- A .glb holding one mesh (one primitive) used by several nodes, each
// node naming its material through its own mesh entry; `lights` adds a
// node for each KHR_lights_punctual light ({ light, translation, aim }).

function glb(shape, nodes, materials, extensionsUsed = [], lights = []) {
    const posBytes = Buffer.from(new Float32Array(shape.pos).buffer);
    const nrmBytes = Buffer.from(new Float32Array(shape.nrm).buffer);
    const idxRaw = Buffer.from(new Uint16Array(shape.idx).buffer);
    const idxBytes = Buffer.concat([idxRaw, Buffer.alloc((4 - (idxRaw.length % 4)) % 4)]);
    // Optional TEXCOORD_0 and TANGENT after the indices (accessors 3, 4).
    const uvBytes = Buffer.from(new Float32Array(shape.uvs || []).buffer);
    const tanBytes = Buffer.from(new Float32Array(shape.tan || []).buffer);
    const bin = Buffer.concat([posBytes, nrmBytes, idxBytes, uvBytes, tanBytes]);
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < shape.pos.length; i++) {
        lo[i % 3] = Math.min(lo[i % 3], Math.fround(shape.pos[i]));
        hi[i % 3] = Math.max(hi[i % 3], Math.fround(shape.pos[i]));
    }
    const count = shape.pos.length / 3;
    const json = {
        asset: { version: '2.0', generator: 'softrast tools/threejs-compare/make-assets.mjs' },
        scene: 0,
        scenes: [{ nodes: [...nodes, ...lights].map((_, i) => i) }],
        nodes: [
            ...nodes.map((n, i) => ({ mesh: i, ...(n.translation ? { translation: n.translation } : {}) })),
            ...lights.map((l, i) => ({ translation: l.translation, rotation: aimQuaternion(l.aim),
                                       extensions: { KHR_lights_punctual: { light: i } } })),
        ],
        meshes: nodes.map((n) => ({
            primitives: [{ attributes: { POSITION: 0, NORMAL: 1,
                                         ...(shape.uvs ? { TEXCOORD_0: 3, TANGENT: 4 } : {}) },
                           indices: 2, material: n.material }],
        })),
        materials,
        accessors: [
            { bufferView: 0, componentType: 5126, count, type: 'VEC3', min: lo, max: hi },
            { bufferView: 1, componentType: 5126, count, type: 'VEC3' },
            { bufferView: 2, componentType: 5123, count: shape.idx.length, type: 'SCALAR' },
        ],
        bufferViews: [
            { buffer: 0, byteOffset: 0, byteLength: posBytes.length, target: 34962 },
            { buffer: 0, byteOffset: posBytes.length, byteLength: nrmBytes.length, target: 34962 },
            { buffer: 0, byteOffset: posBytes.length + nrmBytes.length, byteLength: idxRaw.length,
              target: 34963 },
        ],
        buffers: [{ byteLength: bin.length }],
    };
    if (shape.uvs) {
        const at = posBytes.length + nrmBytes.length + idxBytes.length;
        json.accessors.push({ bufferView: 3, componentType: 5126, count, type: 'VEC2' },
                            { bufferView: 4, componentType: 5126, count, type: 'VEC4' });
        json.bufferViews.push({ buffer: 0, byteOffset: at, byteLength: uvBytes.length, target: 34962 },
                              { buffer: 0, byteOffset: at + uvBytes.length, byteLength: tanBytes.length,
                                target: 34962 });
    }
    if (lights.length) {
        json.extensions = { KHR_lights_punctual: { lights: lights.map((l) => l.light) } };
        extensionsUsed = [...extensionsUsed, 'KHR_lights_punctual'];
    }
    if (extensionsUsed.length) json.extensionsUsed = extensionsUsed;
    return glbBytes(json, bin);
}

// The GLB container of a document and its BIN chunk.
function glbBytes(json, bin) {
    let text = Buffer.from(JSON.stringify(json));
    text = Buffer.concat([text, Buffer.alloc((4 - (text.length % 4)) % 4, 0x20)]);
    const header = Buffer.alloc(12), jsonHead = Buffer.alloc(8), binHead = Buffer.alloc(8);
    header.write('glTF', 0);
    header.writeUInt32LE(2, 4);
    header.writeUInt32LE(12 + 8 + text.length + 8 + bin.length, 8);
    jsonHead.writeUInt32LE(text.length, 0);
    jsonHead.write('JSON', 4);
    binHead.writeUInt32LE(bin.length, 0);
    binHead.write('BIN\0', 4);
    return Buffer.concat([header, jsonHead, text, binHead, bin]);
}

// --- A .glb of any accessors: `arrays` are [typed array, accessor fields]
// pairs, each becoming bufferView and accessor i; json is the rest.

function glbOf(json, arrays) {
    const chunks = [];
    let at = 0;
    json.bufferViews = [];
    json.accessors = [];
    arrays.forEach(([data, fields], i) => {
        const raw = Buffer.from(data.buffer, data.byteOffset, data.byteLength);
        const padded = Buffer.concat([raw, Buffer.alloc((4 - (raw.length % 4)) % 4)]);
        json.bufferViews.push({ buffer: 0, byteOffset: at, byteLength: raw.length });
        json.accessors.push({ bufferView: i, ...fields });
        chunks.push(padded);
        at += padded.length;
    });
    const bin = Buffer.concat(chunks);
    json.buffers = [{ byteLength: bin.length }];
    return glbBytes(json, bin);
}

const smoothstep = (a, b, x) => { const t = Math.min(1, Math.max(0, (x - a) / (b - a))); return t * t * (3 - 2 * t); };
const rotZ = (deg) => [0, 0, Math.sin((deg * Math.PI) / 360), Math.cos((deg * Math.PI) / 360)];

// A figure posed by a skin and morph targets: a body and an arm,
// ellipsoids standing along +Y in their bind pose, skinned to four joints
// (hips, chest bent 15 degrees, shoulder swung out, elbow bent up); a head
// under the chest joint whose two morph targets (taller, a nose) its node
// weighs 0.5 and 1 (the mesh's weights say 0.3 and 0).  The skinned nodes
// are moved, turned and scaled, which skinning ignores: drawn unskinned,
// the body lies on its back and the arm floats twice its size.
function figure() {
    const arrays = [];
    const add = (data, fields) => { arrays.push([data, fields]); return arrays.length - 1; };
    const ellipsoid = (cy, rx, ry, jointOf) => {
        const s = sphere(1, 24, 16), n = s.pos.length / 3;
        const pos = new Float32Array(3 * n), nrm = new Float32Array(3 * n);
        const joints = new Uint8Array(4 * n), weights = new Float32Array(4 * n);
        for (let i = 0; i < n; i++) {
            const [x, y, z] = s.pos.slice(3 * i, 3 * i + 3);
            pos.set([x * rx, cy + y * ry, z * rx], 3 * i);
            const m = [x / rx, y / ry, z / rx], l = Math.hypot(...m);
            nrm.set(m.map((c) => c / l), 3 * i);
            const [j0, j1, w1] = jointOf(cy + y * ry);
            joints.set([j0, j1, 0, 0], 4 * i);
            weights.set([1 - w1, w1, 0, 0], 4 * i);
        }
        const lo = [-rx, cy - ry, -rx].map(Math.fround), hi = [rx, cy + ry, rx].map(Math.fround);
        return {
            POSITION: add(pos, { componentType: 5126, count: n, type: 'VEC3', min: lo, max: hi }),
            NORMAL: add(nrm, { componentType: 5126, count: n, type: 'VEC3' }),
            JOINTS_0: add(joints, { componentType: 5121, count: n, type: 'VEC4' }),
            WEIGHTS_0: add(weights, { componentType: 5126, count: n, type: 'VEC4' }),
            indices: add(new Uint16Array(s.idx), { componentType: 5123, count: s.idx.length, type: 'SCALAR' }),
        };
    };
    const body = ellipsoid(1, 0.35, 1, (y) => [0, 1, smoothstep(0.8, 1.3, y)]);
    const arm = ellipsoid(2.4, 0.12, 0.65, (y) => [2, 3, smoothstep(2.25, 2.55, y)]);
    const head = sphere(0.32, 24, 16), hn = head.pos.length / 3;
    const tall = new Float32Array(3 * hn), nose = new Float32Array(3 * hn);
    for (let i = 0; i < hn; i++) {
        const ny = head.nrm[3 * i + 1], nz = head.nrm[3 * i + 2];
        tall[3 * i + 1] = 0.5 * 0.32 * ny;
        nose[3 * i + 2] = nz > 0.85 ? (0.25 * (nz - 0.85)) / 0.15 : 0;
    }
    const h = {
        POSITION: add(new Float32Array(head.pos), { componentType: 5126, count: hn, type: 'VEC3',
                                                    min: [-0.32, -0.32, -0.32], max: [0.32, 0.32, 0.32] }),
        NORMAL: add(new Float32Array(head.nrm), { componentType: 5126, count: hn, type: 'VEC3' }),
        indices: add(new Uint16Array(head.idx), { componentType: 5123, count: head.idx.length, type: 'SCALAR' }),
        tall: add(tall, { componentType: 5126, count: hn, type: 'VEC3', min: [0, -0.16, 0], max: [0, 0.16, 0] }),
        nose: add(nose, { componentType: 5126, count: hn, type: 'VEC3', min: [0, 0, 0], max: [0, 0, 0.25] }),
    };
    const ibm = new Float32Array(64);
    [0, -1, -1.75, -2.4].forEach((y, j) => ibm.set([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, y, 0, 1], 16 * j));
    const ibmAccessor = add(ibm, { componentType: 5126, count: 4, type: 'MAT4' });
    const prim = (a, material) => ({ attributes: { POSITION: a.POSITION, NORMAL: a.NORMAL, JOINTS_0: a.JOINTS_0,
                                                    WEIGHTS_0: a.WEIGHTS_0 }, indices: a.indices, material });
    const json = {
        asset: { version: '2.0', generator: 'softrast tools/threejs-compare/make-assets.mjs' },
        scene: 0,
        scenes: [{ nodes: [0, 4, 5] }],
        nodes: [
            { name: 'hips', children: [1] },
            { name: 'chest', translation: [0, 1, 0], rotation: rotZ(15), children: [2, 6] },
            { name: 'shoulder', translation: [0, 0.75, 0], rotation: rotZ(-110), children: [3] },
            { name: 'elbow', translation: [0, 0.65, 0], rotation: rotZ(60) },
            { name: 'body', mesh: 0, skin: 0, translation: [3, 0, 0], rotation: [Math.SQRT1_2, 0, 0, Math.SQRT1_2] },
            { name: 'arm', mesh: 1, skin: 0, scale: [2, 2, 2] },
            { name: 'head', mesh: 2, translation: [0, 1.3, 0], weights: [0.5, 1] },
        ],
        skins: [{ joints: [0, 1, 2, 3], inverseBindMatrices: ibmAccessor, skeleton: 0 }],
        meshes: [
            { primitives: [prim(body, 0)] },
            { primitives: [prim(arm, 1)] },
            { primitives: [{ attributes: { POSITION: h.POSITION, NORMAL: h.NORMAL }, indices: h.indices,
                             material: 2, targets: [{ POSITION: h.tall }, { POSITION: h.nose }] }],
              weights: [0.3, 0] },
        ],
        materials: [
            { name: 'blue', pbrMetallicRoughness: pbr([0.15, 0.3, 0.8], 0, 0.6) },
            { name: 'orange', pbrMetallicRoughness: pbr([0.9, 0.45, 0.15], 0, 0.5) },
            { name: 'skin', pbrMetallicRoughness: pbr([0.95, 0.72, 0.58], 0, 0.7) },
        ],
    };
    return glbOf(json, arrays);
}

// --- A Radiance RGBE picture, flat scanlines (every reader takes them).

function rgbe(r, g, b) {
    const m = Math.max(r, g, b);
    if (m < 1e-32) return [0, 0, 0, 0];
    const e = Math.floor(Math.log2(m)) + 1;   // frexp's exponent: m / 2^e in [0.5, 1)
    const s = 256 / 2 ** e;
    return [Math.min(255, Math.floor(r * s)), Math.min(255, Math.floor(g * s)),
            Math.min(255, Math.floor(b * s)), e + 128];
}

// A studio-like sky, equirectangular as three.js maps it: +Y up, the top
// row straight up, and column u facing (cos p, 0, sin p) with p = 2 pi (u - 0.5).
// A bright overhead softbox, a warm key box to the upper left of the
// default view, a cool horizon and a dark floor.
function sky(width, height) {
    const px = Buffer.alloc(width * height * 4);
    const box = (d, c, size) => {
        const dot = d[0] * c[0] + d[1] * c[1] + d[2] * c[2];
        return Math.max(0, Math.min(1, (dot - Math.cos(size)) / 0.02));
    };
    const norm = (v) => { const l = Math.hypot(...v); return v.map((x) => x / l); };
    const top = [0, 1, 0], key = norm([-1, 0.8, 0.6]);
    for (let y = 0; y < height; y++) {
        const theta = (Math.PI * (y + 0.5)) / height;
        for (let x = 0; x < width; x++) {
            const phi = 2 * Math.PI * ((x + 0.5) / width - 0.5);
            const d = [Math.sin(theta) * Math.cos(phi), Math.cos(theta), Math.sin(theta) * Math.sin(phi)];
            const up = d[1];
            let c = up >= 0
                ? [0.3 + 0.1 * up, 0.33 + 0.15 * up, 0.38 + 0.25 * up]
                : [0.1 + 0.06 * (1 + up), 0.09 + 0.06 * (1 + up), 0.08 + 0.06 * (1 + up)];
            const t = box(d, top, 0.35) * 2.5, k = box(d, key, 0.25) * 5;
            c = [c[0] + t + k * 1.0, c[1] + t + k * 0.9, c[2] + t + k * 0.75];
            px.set(rgbe(...c), (y * width + x) * 4);
        }
    }
    const head = `#?RADIANCE\n# softrast tools/threejs-compare/make-assets.mjs\nFORMAT=32-bit_rle_rgbe\n\n-Y ${height} +X ${width}\n`;
    return Buffer.concat([Buffer.from(head), px]);
}

// --- The assets.

const out = process.argv[2];
if (!out) {
    console.error('usage: node make-assets.mjs OUTDIR');
    process.exit(2);
}
mkdirSync(out, { recursive: true });

const pbr = (base, metallic, roughness) => ({ baseColorFactor: [...base, 1], metallicFactor: metallic,
                                              roughnessFactor: roughness });

writeFileSync(join(out, 'emissive-cube.glb'), glb(cube(0.5), [{ material: 0 }], [
    { name: 'black, orange emissive', pbrMetallicRoughness: pbr([0, 0, 0], 0, 1),
      emissiveFactor: [1, 0.5, 0] },
]));
writeFileSync(join(out, 'red-metal-sphere.glb'), glb(sphere(0.5, 64, 32), [{ material: 0 }], [
    { name: 'red metal', pbrMetallicRoughness: pbr([1, 0, 0], 1, 0.2) },
]));
writeFileSync(join(out, 'unlit-green-cube.glb'), glb(cube(0.5), [{ material: 0 }], [
    { name: 'unlit green', pbrMetallicRoughness: pbr([0, 1, 0], 0, 1),
      extensions: { KHR_materials_unlit: {} } },
], ['KHR_materials_unlit']));

// Metallic 0..1 left to right, roughness 0..1 bottom to top.
const n = 5, nodes = [], materials = [];
for (let row = 0; row < n; row++) {
    for (let col = 0; col < n; col++) {
        const metallic = col / (n - 1), roughness = row / (n - 1);
        materials.push({ name: `metallic ${metallic} roughness ${roughness}`,
                         pbrMetallicRoughness: pbr([0.95, 0.64, 0.54], metallic, roughness) });
        nodes.push({ material: materials.length - 1, translation: [(col - (n - 1) / 2) * 1.1,
                                                                  (row - (n - 1) / 2) * 1.1, 0] });
    }
}
writeFileSync(join(out, 'metal-rough-spheres.glb'), glb(sphere(0.5, 48, 24), nodes, materials));

// A sphere on a plane under the file's own lights (KHR_lights_punctual):
// a spot with a soft edge, a point light whose range ends on the plane
// and a dim directional light; compare with --environment-intensity
// 0.001 so that they alone light it.
writeFileSync(join(out, 'punctual-lights.glb'), glb(
    merge([plane(2), [0, 0, 0]], [sphere(0.5, 48, 24), [0, 0.5, 0]]), [{ material: 0 }],
    [{ name: 'white dielectric', pbrMetallicRoughness: pbr([0.8, 0.8, 0.8], 0, 0.5) }], [], [
        { light: { type: 'spot', intensity: 14, color: [1, 0.95, 0.85],
                   spot: { innerConeAngle: 0.3, outerConeAngle: 0.55 } },
          translation: [-0.9, 2.5, 0.9], aim: [0.5, -2.5, -0.6] },
        { light: { type: 'point', intensity: 2.5, color: [1, 0.55, 0.25], range: 1.8 },
          translation: [1.1, 0.6, 0.7], aim: [0, 0, -1] },
        { light: { type: 'directional', intensity: 0.6, color: [0.7, 0.8, 1] },
          translation: [0, 3, 0], aim: [-0.4, -1, -0.5] },
    ]));

// The physically based layers, left to right: top row ior 1.5 and 2.4,
// specular 0.3, a yellow specular color; bottom row a sharp and a rough
// clear coat, blue velvet (sheen) and coated velvet.
const red = pbr([0.8, 0.08, 0.05], 0, 0.5), velvet = pbr([0.02, 0.02, 0.15], 0, 0.9);
const sheen = { sheenColorFactor: [0.4, 0.5, 1], sheenRoughnessFactor: 0.5 };
const layers = [
    { name: 'ior 1.5', pbrMetallicRoughness: red },
    { name: 'ior 2.4', pbrMetallicRoughness: red, extensions: { KHR_materials_ior: { ior: 2.4 } } },
    { name: 'specular 0.3', pbrMetallicRoughness: red,
      extensions: { KHR_materials_specular: { specularFactor: 0.3 } } },
    { name: 'yellow specular', pbrMetallicRoughness: red,
      extensions: { KHR_materials_specular: { specularColorFactor: [2, 2, 1] } } },
    { name: 'sharp coat', pbrMetallicRoughness: red,
      extensions: { KHR_materials_clearcoat: { clearcoatFactor: 1,
                                               clearcoatRoughnessFactor: 0.05 } } },
    { name: 'rough coat', pbrMetallicRoughness: red,
      extensions: { KHR_materials_clearcoat: { clearcoatFactor: 1,
                                               clearcoatRoughnessFactor: 0.4 } } },
    { name: 'velvet', pbrMetallicRoughness: velvet, extensions: { KHR_materials_sheen: sheen } },
    { name: 'coated velvet', pbrMetallicRoughness: velvet,
      extensions: { KHR_materials_sheen: sheen,
                    KHR_materials_clearcoat: { clearcoatFactor: 0.8,
                                               clearcoatRoughnessFactor: 0.1 } } },
];
writeFileSync(join(out, 'layer-spheres.glb'), glb(sphere(0.5, 48, 24), layers.map((m, i) => ({
    material: i, translation: [(i % 4 - 1.5) * 1.1, i < 4 ? 0.55 : -0.55, 0] })), layers,
    ['KHR_materials_ior', 'KHR_materials_specular', 'KHR_materials_clearcoat',
     'KHR_materials_sheen']));

// The base lobe's extensions, left to right: top row brushed steel along
// the tangent (around the sphere), turned a quarter (along the meridians),
// and red plastic stretched at 0.8 rad; bottom row a soap film on a dark
// dielectric, an oil film on grey metal, and a film on brushed steel.
const steel = pbr([0.9, 0.9, 0.92], 1, 0.35);
const surface = [
    { name: 'brushed along u', pbrMetallicRoughness: steel,
      extensions: { KHR_materials_anisotropy: { anisotropyStrength: 0.8 } } },
    { name: 'brushed along v', pbrMetallicRoughness: steel,
      extensions: { KHR_materials_anisotropy: { anisotropyStrength: 0.8,
                                                anisotropyRotation: Math.PI / 2 } } },
    { name: 'stretched plastic', pbrMetallicRoughness: pbr([0.7, 0.1, 0.08], 0, 0.3),
      extensions: { KHR_materials_anisotropy: { anisotropyStrength: 0.6,
                                                anisotropyRotation: 0.8 } } },
    { name: 'soap film', pbrMetallicRoughness: pbr([0.05, 0.05, 0.08], 0, 0.15),
      extensions: { KHR_materials_iridescence: { iridescenceFactor: 1, iridescenceIor: 1.33,
                                                 iridescenceThicknessMaximum: 380 } } },
    { name: 'oil on metal', pbrMetallicRoughness: pbr([0.6, 0.6, 0.6], 1, 0.25),
      extensions: { KHR_materials_iridescence: { iridescenceFactor: 1, iridescenceIor: 1.5,
                                                 iridescenceThicknessMaximum: 520 } } },
    { name: 'film on brushed steel', pbrMetallicRoughness: steel,
      extensions: { KHR_materials_anisotropy: { anisotropyStrength: 0.6, anisotropyRotation: 0.5 },
                    KHR_materials_iridescence: { iridescenceFactor: 0.8,
                                                 iridescenceThicknessMaximum: 450 } } },
];
writeFileSync(join(out, 'surface-spheres.glb'), glb(sphere(0.5, 64, 32, true),
    surface.map((m, i) => ({ material: i, translation: [(i % 3 - 1) * 1.1, i < 3 ? 0.55 : -0.55, 0] })),
    surface, ['KHR_materials_anisotropy', 'KHR_materials_iridescence']));

// KHR_materials_iridescence over a half-metal: the same film (ior 1.8,
// 450 nm) on a copper-coloured base at metallic 0, 0.5 and 1, left to
// right.  The extension replaces the Fresnel term of the dielectric's
// and of the metal's BRDF, which glTF mixes by metallic, so the middle
// sphere's film is the mean of its neighbours', not a film over the mean
// F0.
const filmed = (metallic) => ({
    name: `film at metallic ${metallic}`, pbrMetallicRoughness: pbr([0.9, 0.6, 0.3], metallic, 0.3),
    extensions: { KHR_materials_iridescence: { iridescenceFactor: 1, iridescenceIor: 1.8,
                                               iridescenceThicknessMaximum: 450 } } });
const halfMetal = [filmed(0), filmed(0.5), filmed(1)];
writeFileSync(join(out, 'iridescence-metallic.glb'), glb(sphere(0.5, 64, 32, true),
    halfMetal.map((m, i) => ({ material: i, translation: [(i - 1) * 1.1, 0, 0] })),
    halfMetal, ['KHR_materials_iridescence']));

// KHR_materials_iridescence's thickness: no film, a film 0 nm thick
// (factor 1: the extension says 0 nm is no film) and one 400 nm thick,
// on a dark dielectric, left to right.
const thickness = [null, 0, 400].map((nm) => ({
    name: nm === null ? 'no film' : `film ${nm} nm`, pbrMetallicRoughness: pbr([0.1, 0.1, 0.12], 0, 0.3),
    ...(nm === null ? {} : { extensions: { KHR_materials_iridescence: {
        iridescenceFactor: 1, iridescenceThicknessMaximum: nm } } }) }));
writeFileSync(join(out, 'iridescence-thickness.glb'), glb(sphere(0.5, 64, 32, true),
    thickness.map((m, i) => ({ material: i, translation: [(i - 1) * 1.1, 0, 0] })),
    thickness, ['KHR_materials_iridescence']));
writeFileSync(join(out, 'skinned-figure.glb'), figure());

// An animated asset (glTF animations): a hub turning about +y (LINEAR
// rotations, slerped) carries a cube squashed and stretched by STEP
// scales and a sphere lifted along a CUBICSPLINE path.  ASSET.pose
// beside it says which animation and time run.sh poses it at.
function animatedGlb() {
    const arrays = [];
    const add = (data, fields) => { arrays.push([data, fields]); return arrays.length - 1; };
    const f32 = (values, type, count, extra = {}) =>
        add(new Float32Array(values), { componentType: 5126, count, type, ...extra });
    const meshes = [cube(0.4), sphere(0.3, 32, 16)].map((sh, i) => {
        const lo = [0, 1, 2].map((k) => Math.min(...sh.pos.filter((_, j) => j % 3 === k)));
        const hi = [0, 1, 2].map((k) => Math.max(...sh.pos.filter((_, j) => j % 3 === k)));
        const n = sh.pos.length / 3;
        const attributes = { POSITION: f32(sh.pos, 'VEC3', n, { min: lo, max: hi }),
                             NORMAL: f32(sh.nrm, 'VEC3', n) };
        const indices = add(new Uint16Array(sh.idx),
                            { componentType: 5123, count: sh.idx.length, type: 'SCALAR' });
        return { primitives: [{ attributes, indices, material: i }] };
    });
    const key = (times) => f32(times, 'SCALAR', times.length,
                               { min: [times[0]], max: [times[times.length - 1]] });
    const turn = (deg) => [0, Math.sin((deg * Math.PI) / 360), 0, Math.cos((deg * Math.PI) / 360)];
    const spinIn = key([0, 1, 2]);
    const spinOut = f32([...turn(0), ...turn(90), ...turn(200)], 'VEC4', 3);
    const squashIn = key([0, 0.5, 1.5]);
    const squashOut = f32([1, 1, 1, 0.7, 1.5, 0.7, 1.3, 0.6, 1.3], 'VEC3', 3);
    const liftIn = key([0, 2]);
    // in-tangent, value, out-tangent a key (units a second)
    const liftOut = f32([0, 0, 0, 1.1, 0, 0, 0, 1.5, 0, 0, -1, 0, 1.1, 0.9, 0, 0, 0, 0], 'VEC3', 6);
    return glbOf({
        asset: { version: '2.0', generator: 'softrast tools/threejs-compare/make-assets.mjs' },
        scene: 0,
        scenes: [{ nodes: [0] }],
        nodes: [{ name: 'hub', children: [1, 2] }, { name: 'block', mesh: 0 },
                { name: 'ball', mesh: 1, translation: [1.1, 0, 0] }],
        meshes,
        materials: [{ name: 'blue', pbrMetallicRoughness: pbr([0.1, 0.3, 0.9], 0, 0.4) },
                    { name: 'gold', pbrMetallicRoughness: pbr([1, 0.75, 0.3], 1, 0.3) }],
        animations: [{
            name: 'spin',
            samplers: [{ input: spinIn, output: spinOut },
                       { input: squashIn, output: squashOut, interpolation: 'STEP' },
                       { input: liftIn, output: liftOut, interpolation: 'CUBICSPLINE' }],
            channels: [{ sampler: 0, target: { node: 0, path: 'rotation' } },
                       { sampler: 1, target: { node: 1, path: 'scale' } },
                       { sampler: 2, target: { node: 2, path: 'translation' } }],
        }],
    }, arrays);
}
writeFileSync(join(out, 'animated-hub.glb'), animatedGlb());
writeFileSync(join(out, 'animated-hub.glb.pose'), '0 1.25\n');

// KHR_materials_dispersion: a clear glass sphere (left) and one of the
// same glass with dispersion 3 (right), 1 thick (their diameter), in front
// of a checker of white and blue squares facing +Z, whose edges the right
// one splits into red, green and blue fringes.
function dispersionGlb() {
    const arrays = [];
    const add = (data, fields) => { arrays.push([data, fields]); return arrays.length - 1; };
    const shapeOf = (sh) => {
        const n = sh.pos.length / 3;
        const lo = [0, 1, 2].map((k) => Math.min(...sh.pos.filter((_, j) => j % 3 === k)));
        const hi = [0, 1, 2].map((k) => Math.max(...sh.pos.filter((_, j) => j % 3 === k)));
        return { POSITION: add(new Float32Array(sh.pos), { componentType: 5126, count: n,
                                                           type: 'VEC3', min: lo, max: hi }),
                 NORMAL: add(new Float32Array(sh.nrm), { componentType: 5126, count: n, type: 'VEC3' }) };
    };
    const indices = (idx) => add(new Uint16Array(idx),
                                 { componentType: 5123, count: idx.length, type: 'SCALAR' });
    const squares = [[], []];
    const side = 0.5, cols = 7, rows = 4;
    for (let y = 0; y < rows; y++) {
        for (let x = 0; x < cols; x++) {
            const l = (x - cols / 2) * side, d = (y - rows / 2) * side;
            squares[(x + y) % 2].push([l, d]);
        }
    }
    const checker = squares.map((list) => ({
        pos: list.flatMap(([l, d]) => [l, d, -1, l + side, d, -1, l + side, d + side, -1, l, d + side, -1]),
        nrm: list.flatMap(() => [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1]),
        idx: list.flatMap((_, i) => [0, 1, 2, 0, 2, 3].map((k) => 4 * i + k)),
    }));
    const ball = sphere(0.5, 64, 32);
    const ballAttr = shapeOf(ball), ballIdx = indices(ball.idx);
    const glass = (extra) => ({
        pbrMetallicRoughness: pbr([1, 1, 1], 0, 0),
        extensions: { KHR_materials_transmission: { transmissionFactor: 1 },
                      KHR_materials_volume: { thicknessFactor: 1 }, ...extra },
    });
    return glbOf({
        asset: { version: '2.0', generator: 'softrast tools/threejs-compare/make-assets.mjs' },
        extensionsUsed: ['KHR_materials_transmission', 'KHR_materials_volume',
                         'KHR_materials_dispersion'],
        scene: 0,
        scenes: [{ nodes: [0, 1, 2] }],
        nodes: [{ mesh: 0 }, { mesh: 1, translation: [-0.6, 0, 0] },
                { mesh: 2, translation: [0.6, 0, 0] }],
        meshes: [
            { primitives: checker.map((sh, i) => ({ attributes: shapeOf(sh), indices: indices(sh.idx),
                                                   material: i })) },
            { primitives: [{ attributes: ballAttr, indices: ballIdx, material: 2 }] },
            { primitives: [{ attributes: ballAttr, indices: ballIdx, material: 3 }] },
        ],
        materials: [
            { name: 'white', pbrMetallicRoughness: pbr([0.8, 0.8, 0.8], 0, 0.8) },
            { name: 'blue', pbrMetallicRoughness: pbr([0.03, 0.1, 0.6], 0, 0.8) },
            { name: 'clear glass', ...glass({}) },
            { name: 'dispersive glass', ...glass({ KHR_materials_dispersion: { dispersion: 3 } }) },
        ],
    }, arrays);
}
writeFileSync(join(out, 'dispersion-spheres.glb'), dispersionGlb());

// A grid of cubes one node places by EXT_mesh_gpu_instancing (three.js
// reads it into an InstancedMesh): twelve instances, each moved, turned
// (rotations as normalized shorts) and scaled, under a node that is
// moved and turned itself.
function instancedGlb() {
    const arrays = [];
    const add = (data, fields) => { arrays.push([data, fields]); return arrays.length - 1; };
    const shape = cube(0.5);
    const lo = [0, 1, 2].map((k) => Math.min(...shape.pos.filter((_, j) => j % 3 === k)));
    const hi = [0, 1, 2].map((k) => Math.max(...shape.pos.filter((_, j) => j % 3 === k)));
    const n = shape.pos.length / 3;
    const POSITION = add(new Float32Array(shape.pos), { componentType: 5126, count: n, type: 'VEC3',
                                                        min: lo, max: hi });
    const NORMAL = add(new Float32Array(shape.nrm), { componentType: 5126, count: n, type: 'VEC3' });
    const indices = add(new Uint16Array(shape.idx),
                        { componentType: 5123, count: shape.idx.length, type: 'SCALAR' });
    const t = [], q = [], s = [];
    for (let i = 0; i < 12; i++) {
        const col = i % 4, row = Math.floor(i / 4);
        t.push(1.1 * col - 1.65, 1.1 * row - 1.1, 0.3 * (col - row));
        const axis = [1 + col, 2 - row, 0.5 * i], len = Math.hypot(...axis), a = 0.5 + 0.4 * i;
        q.push(...axis.map((c) => Math.round((c / len) * Math.sin(a / 2) * 32767)),
               Math.round(Math.cos(a / 2) * 32767));
        s.push(0.25 + 0.08 * col, 0.5 - 0.1 * row, 0.4);
    }
    const TRANSLATION = add(new Float32Array(t), { componentType: 5126, count: 12, type: 'VEC3' });
    const ROTATION = add(new Int16Array(q), { componentType: 5122, normalized: true, count: 12,
                                              type: 'VEC4' });
    const SCALE = add(new Float32Array(s), { componentType: 5126, count: 12, type: 'VEC3' });
    return glbOf({
        asset: { version: '2.0', generator: 'softrast tools/threejs-compare/make-assets.mjs' },
        extensionsUsed: ['EXT_mesh_gpu_instancing'],
        extensionsRequired: ['EXT_mesh_gpu_instancing'],
        scene: 0,
        scenes: [{ nodes: [0] }],
        nodes: [{ mesh: 0, translation: [0.1, 0.2, 0], rotation: rotZ(10),
                  extensions: { EXT_mesh_gpu_instancing: { attributes: { TRANSLATION, ROTATION,
                                                                         SCALE } } } }],
        meshes: [{ primitives: [{ attributes: { POSITION, NORMAL }, indices, material: 0 }] }],
        materials: [{ name: 'clay', pbrMetallicRoughness: pbr([0.9, 0.5, 0.2], 0, 0.6) }],
    }, arrays);
}
writeFileSync(join(out, 'instanced-cubes.glb'), instancedGlb());

writeFileSync(join(out, 'sky.hdr'), sky(256, 128));
