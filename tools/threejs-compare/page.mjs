// page.mjs - runs in Chromium: renders one glTF asset with three.js the way
// `softrast render` frames it, and hands back the canvas as a PNG data URL.
// render-three.mjs serves this file, three.js and the inputs.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { RGBELoader } from 'three/addons/loaders/RGBELoader.js';
import { RoomEnvironment } from 'three/addons/environments/RoomEnvironment.js';

// The view direction of softrast's default camera (src/geometry/framing.c,
// sr_framing_direction) and its margin on the limiting side.
const VIEW_DIR = new THREE.Vector3(0.62, 0.48, 1.0).normalize();
const MARGIN = 0.05;

// softrast's sr_fit_fovy: the field of view is across the smaller side.
function fitFovy(fov, w, h) {
    return w >= h ? fov : 2 * Math.atan(Math.tan(fov / 2) / (w / h));
}

// The camera basis of sr_camera_frame: w towards the eye, u across, v up.
function basis(dir) {
    const w = dir.clone().normalize();
    const u = new THREE.Vector3(0, 1, 0).cross(w).normalize();
    const v = w.clone().cross(u);
    return { u, v, w };
}

// sr_fit_camera (perspective) on world-space points: the eye that frames the
// points to MARGIN on the limiting side, centred on the other.
function frame(points, fovRad, width, height) {
    const tanY = Math.tan(fitFovy(fovRad, width, height) / 2);
    const tanX = tanY * (width / height);
    const { u, v, w } = basis(VIEW_DIR);
    const q = points.map((p) => [p.dot(u), p.dot(v), p.dot(w)]);
    const fill = 1 - 2 * MARGIN;
    const t = [tanX * fill, tanY * fill];
    const plus = [-Infinity, -Infinity], minus = [-Infinity, -Infinity];
    for (const p of q) {
        for (let k = 0; k < 2; k++) {
            plus[k] = Math.max(plus[k], p[k] + t[k] * p[2]);
            minus[k] = Math.max(minus[k], t[k] * p[2] - p[k]);
        }
    }
    const ezk = [(plus[0] + minus[0]) / (2 * t[0]), (plus[1] + minus[1]) / (2 * t[1])];
    const limit = ezk[0] >= ezk[1] ? 0 : 1, other = 1 - limit;
    const ez = ezk[limit];
    const e = [0, 0];
    e[limit] = (plus[limit] - minus[limit]) / 2;
    // centre_offset: put the eye between the two points projecting farthest out.
    let c = (plus[other] - minus[other]) / 2;
    for (let step = 0; step < 16; step++) {
        let hi = -Infinity, lo = Infinity, hq = null, lq = null;
        for (const p of q) {
            const s = (p[other] - c) / (ez - p[2]);
            if (s > hi) { hi = s; hq = p; }
            if (s < lo) { lo = s; lq = p; }
        }
        const dh = ez - hq[2], dl = ez - lq[2];
        const next = (hq[other] * dl + lq[other] * dh) / (dh + dl);
        if (next === c || !Number.isFinite(next)) break;
        c = next;
    }
    e[other] = c;
    return u.clone().multiplyScalar(e[0]).add(v.clone().multiplyScalar(e[1])).add(w.clone().multiplyScalar(ez));
}

function worldPoints(root) {
    const pts = [];
    root.updateMatrixWorld(true);
    root.traverse((o) => {
        if (!o.isMesh) return;
        // getVertexPosition applies morph targets and skinning, as drawn;
        // an InstancedMesh (EXT_mesh_gpu_instancing) is drawn once per
        // instance matrix, each after the node's.
        const a = o.geometry.attributes.position;
        const instances = o.isInstancedMesh ? o.count : 1;
        const m = new THREE.Matrix4();
        for (let k = 0; k < instances; k++) {
            if (o.isInstancedMesh) o.getMatrixAt(k, m);
            for (let i = 0; i < a.count; i++) {
                const p = o.getVertexPosition(i, new THREE.Vector3());
                if (o.isInstancedMesh) p.applyMatrix4(m);
                pts.push(p.applyMatrix4(o.matrixWorld));
            }
        }
    });
    return pts;
}

const TONEMAPS = { neutral: THREE.NeutralToneMapping, aces: THREE.ACESFilmicToneMapping,
                   none: THREE.NoToneMapping };

// Renders with the options o (see render-three.mjs) and returns a PNG data URL.
window.renderAsset = async (o) => {
    const renderer = new THREE.WebGLRenderer({ antialias: o.antialias, preserveDrawingBuffer: true });
    renderer.setPixelRatio(1);
    renderer.setSize(o.width, o.height);
    renderer.outputColorSpace = THREE.SRGBColorSpace;
    renderer.toneMapping = TONEMAPS[o.tonemap];
    renderer.toneMappingExposure = 2 ** o.exposure;
    document.body.appendChild(renderer.domElement);

    const scene = new THREE.Scene();
    scene.background = new THREE.Color(o.background);
    const pmrem = new THREE.PMREMGenerator(renderer);
    if (o.environment) {
        const hdr = await new RGBELoader().loadAsync(o.environment);
        hdr.mapping = THREE.EquirectangularReflectionMapping;
        scene.environment = pmrem.fromEquirectangular(hdr).texture;
    } else {
        scene.environment = pmrem.fromScene(new RoomEnvironment(), 0.04).texture;
    }
    scene.environmentIntensity = o.envIntensity;

    const gltf = await new GLTFLoader().loadAsync(o.model);
    scene.add(gltf.scene);
    if (o.animation !== null) {
        // The pose at o.time: played once and held at the end, as
        // softrast clamps; before the first key three.js's interpolants
        // hold the first.
        const clip = gltf.animations[o.animation];
        if (!clip) throw new Error(`no animation ${o.animation}`);
        const mixer = new THREE.AnimationMixer(gltf.scene);
        const action = mixer.clipAction(clip);
        action.setLoop(THREE.LoopOnce, 1);
        action.clampWhenFinished = true;
        action.play();
        mixer.setTime(o.time);
    }
    const pts = worldPoints(gltf.scene);
    const box = new THREE.Box3().setFromPoints(pts);
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    const fov = (o.fov * Math.PI) / 180;
    const eye = o.eye ? new THREE.Vector3(...o.eye) : frame(pts, fov, o.width, o.height);
    const target = o.target ? new THREE.Vector3(...o.target)
        : o.eye ? sphere.center.clone()
        : eye.clone().sub(VIEW_DIR.clone().multiplyScalar(VIEW_DIR.dot(eye.clone().sub(sphere.center))));
    // framing_near_far: planes holding the bounding sphere.
    const dc = eye.distanceTo(sphere.center);
    const far = (dc + sphere.radius) * 1.01;
    const near = Math.max(dc - sphere.radius, far * 1e-3) * 0.99;
    const camera = new THREE.PerspectiveCamera((fitFovy(fov, o.width, o.height) * 180) / Math.PI,
                                               o.width / o.height, near, far);
    camera.position.copy(eye);
    camera.up.set(0, 1, 0);
    camera.lookAt(target);

    // softrast's camera-relative lights (sr_default_lights): its key
    // light alone (what it adds to an environment) or all three, in
    // radiance units where a white Lambertian surface reflects 1/pi, as
    // three.js's lights are.
    const rig = [[-0.55, 0.7, 0.45, 0.95], [0.8, 0.05, 0.6, 0.35], [0.1, 0.55, -0.85, 0.45]];
    // A file with lights of its own (KHR_lights_punctual, which
    // GLTFLoader adds to the scene) is lit by them alone, as softrast's
    // `--lights auto` does.
    const ownLights = (gltf.parser.json.extensions?.KHR_lights_punctual?.lights ?? []).length > 0;
    const count = ownLights ? 0 : { none: 0, key: 1, rig: 3 }[o.lights];
    const { u, v, w } = basis(eye.clone().sub(target));
    for (const [a, b, c, intensity] of rig.slice(0, count)) {
        const l = new THREE.DirectionalLight(new THREE.Color().setRGB(1, 0.98, 0.95, THREE.LinearSRGBColorSpace),
                                             intensity * o.lightScale);
        l.position.copy(u.clone().multiplyScalar(a).add(v.clone().multiplyScalar(b))
            .add(w.clone().multiplyScalar(c)).normalize());
        scene.add(l);
    }

    renderer.render(scene, camera);
    return { png: renderer.domElement.toDataURL('image/png'),
             eye: eye.toArray(), target: target.toArray(), near, far };
};
window.pageReady = true;
