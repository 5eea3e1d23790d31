// render-three.mjs - renders a glTF asset with three.js in Debian's headless
// Chromium (WebGL on SwiftShader), framed, lit and tone mapped as
// `softrast render` does, and writes the canvas to a PNG.
//
//   node render-three.mjs MODEL.glb -o OUT.png [--size WxH] [--fov DEG]
//        [--tonemap neutral|aces|none] [--exposure EV] [--environment FILE.hdr]
//        [--background #rrggbb] [--env-intensity K] [--lights none|key|rig]
//        [--light-scale S]
//        [--camera eye=X,Y,Z[,target=X,Y,Z]] [--aa on|off] [--chromium PATH]
//        [--animation N --time SECONDS]   (the file's animation N at that time,
//                                          AnimationMixer, clamped at its ends)
import { readFileSync, writeFileSync, existsSync } from 'node:fs';
import { dirname, extname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const here = dirname(fileURLToPath(import.meta.url));
const ORIGIN = 'http://compare.invalid';

function usage(msg) {
    console.error(`render-three.mjs: ${msg}`);
    process.exit(2);
}

function parseArgs(argv) {
    const o = { width: 256, height: 256, fov: 35, tonemap: 'neutral', exposure: 0, environment: null,
                background: '#1d2230', envIntensity: 1, lights: 'none', lightScale: 1.6, antialias: true, eye: null, target: null,
                chromium: process.env.CHROMIUM || '/usr/bin/chromium', model: null, output: null,
                animation: null, time: 0 };
    const num = (name, v) => {
        const x = Number(v);
        if (v === undefined || !Number.isFinite(x)) usage(`${name}: expected a number, got '${v}'`);
        return x;
    };
    const vec = (name, v) => {
        const p = v.split(',').map((x) => num(name, x));
        if (p.length !== 3) usage(`${name}: expected X,Y,Z`);
        return p;
    };
    for (let i = 0; i < argv.length; i++) {
        const a = argv[i], v = argv[i + 1];
        const take = () => { i++; if (v === undefined) usage(`${a}: missing value`); return v; };
        if (a === '-o' || a === '--output') o.output = take();
        else if (a === '--size') {
            const m = /^(\d+)x(\d+)$/.exec(take());
            if (!m) usage(`--size: expected WxH, got '${v}'`);
            o.width = Number(m[1]);
            o.height = Number(m[2]);
        } else if (a === '--fov') o.fov = num(a, take());
        else if (a === '--tonemap') {
            o.tonemap = take();
            if (!['neutral', 'aces', 'none'].includes(o.tonemap)) usage(`--tonemap: neutral|aces|none, got '${v}'`);
        } else if (a === '--exposure') o.exposure = num(a, take());
        else if (a === '--environment') o.environment = resolve(take());
        else if (a === '--background') {
            o.background = take();
            if (!/^#([0-9a-f]{3}|[0-9a-f]{6})$/i.test(o.background)) usage(`--background: expected #rrggbb, got '${v}'`);
        } else if (a === '--env-intensity') o.envIntensity = num(a, take());
        else if (a === '--lights') {
            o.lights = take();
            if (!['none', 'key', 'rig'].includes(o.lights)) usage(`--lights: none|key|rig, got '${v}'`);
        } else if (a === '--light-scale') o.lightScale = num(a, take());
        else if (a === '--aa') o.antialias = take() !== 'off';
        else if (a === '--chromium') o.chromium = take();
        else if (a === '--animation') o.animation = num(a, take());
        else if (a === '--time') o.time = num(a, take());
        else if (a === '--camera') {
            for (const kv of take().split(/,(?=[a-z]+=)/)) {
                const [k, val] = kv.split('=');
                if (k === 'eye') o.eye = vec('--camera eye', val);
                else if (k === 'target') o.target = vec('--camera target', val);
                else usage(`--camera: unknown key '${k}'`);
            }
        } else if (a.startsWith('-')) usage(`unknown option '${a}'`);
        else if (o.model) usage(`more than one model ('${o.model}', '${a}')`);
        else o.model = resolve(a);
    }
    if (!o.model || !o.output) usage('a model and -o OUT.png are required');
    for (const f of [o.model, o.environment, o.chromium]) {
        if (f && !existsSync(f)) usage(`${f}: no such file`);
    }
    return o;
}

const TYPES = { '.mjs': 'text/javascript', '.js': 'text/javascript', '.html': 'text/html',
                '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json' };

// Every request the page makes is answered from disk: /three/ from the npm
// package, /files/ from the absolute path that follows (the model, its
// buffers and textures, the environment).
function answer(route, o) {
    const url = new URL(route.request().url());
    const path = decodeURIComponent(url.pathname);
    let file = null;
    if (path === '/') {
        const map = { imports: { three: '/three/build/three.module.js', 'three/addons/': '/three/examples/jsm/' } };
        return route.fulfill({ contentType: 'text/html', body:
            `<!doctype html><html><body style="margin:0">` +
            `<script type="importmap">${JSON.stringify(map)}</script>` +
            `<script type="module" src="/page.mjs"></script></body></html>` });
    }
    if (path === '/page.mjs') file = join(here, 'page.mjs');
    else if (path.startsWith('/three/')) file = join(here, 'node_modules/three', path.slice(7));
    else if (path.startsWith('/files/')) file = path.slice(6);
    if (!file || !existsSync(file)) return route.fulfill({ status: 404, body: 'not found' });
    return route.fulfill({ body: readFileSync(file),
                           contentType: TYPES[extname(file)] || 'application/octet-stream' });
}

const o = parseArgs(process.argv.slice(2));
const browser = await chromium.launch({
    executablePath: o.chromium,
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--use-gl=angle',
           '--ignore-gpu-blocklist'],
});
try {
    const page = await browser.newPage({ viewport: { width: o.width, height: o.height }, deviceScaleFactor: 1 });
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    await page.route(`${ORIGIN}/**`, (route) => answer(route, o));
    await page.goto(`${ORIGIN}/`);
    await page.waitForFunction(() => window.pageReady === true || undefined, null, { timeout: 30000 })
        .catch(() => { throw new Error(`page did not load: ${errors.join('; ')}`); });
    const fileUrl = (f) => `${ORIGIN}/files${encodeURI(f)}`;
    const r = await page.evaluate((opts) => window.renderAsset(opts), {
        ...o, model: fileUrl(o.model), environment: o.environment ? fileUrl(o.environment) : null,
    });
    const renderer = await page.evaluate(() => {
        const gl = document.createElement('canvas').getContext('webgl2');
        const ext = gl && gl.getExtension('WEBGL_debug_renderer_info');
        return ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : 'unknown';
    });
    writeFileSync(o.output, Buffer.from(r.png.split(',')[1], 'base64'));
    const f = (v) => v.map((x) => x.toPrecision(6)).join(',');
    console.log(`${o.output}: eye=${f(r.eye)} target=${f(r.target)} near=${r.near.toPrecision(4)} ` +
                `far=${r.far.toPrecision(4)} webgl=${renderer}`);
} catch (e) {
    console.error(`render-three.mjs: ${o.model}: ${e.message}`);
    process.exitCode = 1;
} finally {
    await browser.close();
}
