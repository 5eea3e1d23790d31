// explain.js - one algorithm's page: the primitive's handles, the step
// buttons and the options, around frames that softrast's explain code
// draws in WebAssembly (softrast-explain.js, web/wasm/explain_web.c).
// Nothing here rasterizes: the page only builds the arguments of
// `softrast explain` and shows the RGBA frames it returns.
'use strict';

// Options a page offers when they mean something for its algorithm: the
// command-line option, its values (the first is the tool's default) and
// which algorithms take it.
const OPTIONS = [
    { option: '--fill-rule', label: 'fill rule', values: ['evenodd', 'nonzero'],
      applies: (a) => ['scanline', 'clip'].includes(a.name) },
    { option: '--rasterizer', label: 'rasterizer', values: ['halfspace', 'scanline', 'barycentric'],
      applies: (a) => a.name === 'triangle' },
    { option: '--interpolation', label: 'interpolation',
      values: ['perspective', 'affine', 'fillspan'],
      applies: (a) => a.name === 'perspective' },
    { option: '--method', label: 'method', values: ['all', 'bilinear', 'plane', 'barycentric'],
      applies: (a) => a.name === 'interpolation' },
    { option: '--samples', label: 'samples per pixel', values: ['4', '2', '8', '16'],
      applies: (a) => a.name === 'msaa' },
    { option: '--connectivity', label: 'connectivity', values: ['4', '8'],
      applies: (a) => a.name === 'floodfill' },
    { option: '--projection', label: 'projection', values: ['perspective', 'orthographic'],
      applies: (a) => a.name === 'transform' },
    { option: '--aspect', label: 'aspect ratio', values: ['fit', 'stretch'],
      applies: (a) => a.name === 'transform' },
    { option: '--shininess', label: 'shininess n', values: ['40', '10', '120'],
      applies: (a) => a.name === 'gouraud' },
    { option: '--offset', label: 'polygon offset (factor, units)',
      values: ['-1,-1', '-1,0', '0,-1', '0,0'], applies: (a) => a.name === 'zfight' },
    { option: '--width', label: 'line width', values: ['1', '0.5', '2.5', '4'],
      applies: (a) => ['aaline', 'area'].includes(a.name) },
    { option: '--cap', label: 'line ends', values: ['butt', 'square', 'round'],
      applies: (a) => a.name === 'area' },
];
// Options that give a value at each vertex: the page keeps the example's.
const VALUES_OPTION = { perspective: '--w', fillpoly: '--intensity',
                        interpolation: '--intensity' };
// Lines whose ends the algorithm takes on pixel centres only.
const ENDS_ON_CENTRES = ['bresenham'];
const HANDLE_RADIUS = 12;   // frame pixels within which a handle is caught

const number = (v) => String(Math.round(v * 1000) / 1000);

async function main() {
    const mod = await SoftrastExplain();
    const name = document.body.dataset.algorithm;
    let alg = null;
    for (let i = 0; ; i++) {
        const json = mod.ccall('web_algorithm', 'string', ['number'], [i]);
        if (!json) {
            break;
        }
        const a = JSON.parse(json);
        if (a.name === name) {
            alg = a;
        }
    }
    if (!alg) {
        throw new Error(`softrast explain has no algorithm '${name}'`);
    }
    const margin = mod.ccall('web_margin', 'number', [], []);
    const hasWindow = alg.window.some((v) => v !== 0);
    const hasSeed = alg.seed.some((v) => v !== 0);
    const hasRow = alg.row > 0;
    const hasHighlight = alg.highlight.some((v) => v !== 0);

    const canvas = document.getElementById('frame');
    const ctx2d = canvas.getContext('2d');
    const stepInput = document.getElementById('step');
    const message = document.getElementById('message');
    const choices = {};
    const state = { points: [], values: [], window: [], seed: [], row: 0, clip: [],
                    highlight: [], step: 0, frames: [], width: 0, height: 0 };
    // What the handles move, to put back when the tool refuses a position.
    const snapshot = () => JSON.stringify({ points: state.points, values: state.values,
                                            window: state.window, seed: state.seed,
                                            row: state.row, clip: state.clip,
                                            highlight: state.highlight });
    const restore = (s) => Object.assign(state, JSON.parse(s));

    function reset() {
        restore(JSON.stringify({ points: alg.points, values: alg.values, window: alg.window,
                                 seed: alg.seed, row: alg.row, clip: alg.clip,
                                 highlight: alg.highlight }));
        for (const o of OPTIONS.filter((o) => o.applies(alg))) {
            choices[o.option] = o.values[0];
        }
        document.querySelectorAll('#options select').forEach((s) => {
            s.value = choices[s.name];
        });
    }

    const list = (v) => v.map(number).join(',');

    // The primitive's option and its numbers.
    function primitive() {
        switch (alg.kind) {
        case 'none':
            return [];
        case 'circle':   // centre and radius
            return ['--circle', list([...state.points[0], state.values[0]])];
        case 'triangles':   // x, y and the depth of each vertex
        case 'object':      // x, y and z of each vertex in object coordinates
            return [`--${alg.kind}`,
                    state.points.map((p, k) => list([...p, state.values[k]])).join(',')];
        case 'clip-triangle':
            return ['--clip-triangle', list(state.clip)];
        default:
            return [`--${alg.kind}`, state.points.map(list).join(',')];
        }
    }

    // The arguments after `softrast explain NAME` for what the page shows.
    function args() {
        const a = primitive();
        if (VALUES_OPTION[alg.name]) {
            a.push(VALUES_OPTION[alg.name], list(state.values.slice(0, 3)));
        }
        if (hasSeed) {
            a.push('--seed', list(state.seed));
        }
        if (hasRow) {
            a.push('--row', String(state.row));
        }
        if (hasWindow) {
            a.push('--window', list(state.window));
        }
        if (hasHighlight) {
            a.push('--highlight', list(state.highlight));
        }
        for (const [option, value] of Object.entries(choices)) {
            a.push(option, value);
        }
        a.push('--grid', `${alg.grid[0]}x${alg.grid[1]}`, '--zoom', String(alg.zoom));
        return a;
    }

    // Run the explanation; false (and the tool's message) when it refuses.
    function render() {
        const a = args();
        const status = mod.ccall('web_explain', 'number', ['string'], [[alg.name, ...a].join('\n')]);
        if (status !== 0) {
            message.textContent = mod.ccall('web_message', 'string', [], []);
            return false;
        }
        message.textContent = '';
        const n = mod.ccall('web_frame_count', 'number', [], []);
        state.width = mod.ccall('web_frame_width', 'number', [], []);
        state.height = mod.ccall('web_frame_height', 'number', [], []);
        state.frames = [];
        for (let i = 0; i < n; i++) {
            const ptr = mod.ccall('web_frame', 'number', ['number'], [i]);
            const bytes = new Uint8ClampedArray(mod.HEAPU8.buffer, ptr, state.width * state.height * 4);
            state.frames.push(new ImageData(new Uint8ClampedArray(bytes), state.width, state.height));
        }
        state.step = Math.min(state.step, n - 1);
        stepInput.max = String(n - 1);
        document.getElementById('command').textContent =
            `softrast explain ${alg.name} ${a.join(' ')} --sheet ${alg.name}.png`;
        window.explainArgs = [alg.name, ...a];
        show();
        return true;
    }

    function show() {
        if (canvas.width !== state.width || canvas.height !== state.height) {
            canvas.width = state.width;
            canvas.height = state.height;
        }
        ctx2d.putImageData(state.frames[state.step], 0, 0);
        stepInput.value = String(state.step);
        document.getElementById('step-label').textContent =
            `step ${state.step + 1} of ${state.frames.length}`;
        window.explainStep = state.step;
    }

    function go(step) {
        state.step = Math.max(0, Math.min(state.frames.length - 1, step));
        show();
    }

    // clip4d's viewport in grid pixels: the grid less a fifth on each side.
    function clipViewport() {
        const x = Math.floor(alg.grid[0] / 5), y = Math.floor(alg.grid[1] / 5);
        return [x, y, alg.grid[0] - 2 * x, alg.grid[1] - 2 * y];
    }

    // transform's object coordinates on the grid of its first step: a unit
    // is min(grid)/4 cells from the grid's centre, y up.
    function objectPlot() {
        return [alg.grid[0] / 2, alg.grid[1] / 2, Math.min(alg.grid[0], alg.grid[1]) / 4];
    }

    // The pixel under a point, kept on the grid.
    const pixel = (v, size) => Math.max(0, Math.min(size - 1, Math.floor(v)));

    // The draggable points in grid coordinates, each with what dragging it
    // to (x, y) changes: the primitive's vertices (the circle's centre and a
    // point on it; of clip4d's triangle, where each vertex in front of the
    // eye projects), the seed pixel, the span's row (caught anywhere along
    // it) and the clip window's two corners.
    function handles() {
        const h = [];
        if (alg.kind === 'circle') {
            const c = state.points[0], r = state.values[0];
            h.push({ at: c, move: (x, y) => { state.points[0] = [x, y]; } });
            // the rim's right end, or its left one when that is off the grid
            h.push({ at: [c[0] + (c[0] + r <= alg.grid[0] ? r : -r), c[1]],
                     move: (x, y) => {
                         state.values[0] = Math.round(Math.hypot(x - c[0], y - c[1]) * 10) / 10;
                     } });
        } else if (alg.kind === 'clip-triangle') {
            const [vx, vy, vw, vh] = clipViewport();
            for (let k = 0; k < 3; k++) {
                const w = state.clip[4 * k + 3];
                if (w > 0) {   // behind the eye a vertex projects nowhere on the grid
                    h.push({ at: [vx + vw * 0.5 * (1 + state.clip[4 * k] / w),
                                  vy + vh * 0.5 * (1 - state.clip[4 * k + 1] / w)],
                             move: (x, y) => {
                                 state.clip[4 * k] = (2 * (x - vx) / vw - 1) * w;
                                 state.clip[4 * k + 1] = (1 - 2 * (y - vy) / vh) * w;
                             } });
                }
            }
        } else if (alg.kind === 'object') {
            const [ox, oy, s] = objectPlot();
            state.points.forEach((p, k) => {
                h.push({ at: [ox + s * p[0], oy - s * p[1]],
                         move: (x, y) => {
                             state.points[k] = [Math.round((x - ox) / s * 100) / 100,
                                                Math.round((oy - y) / s * 100) / 100];
                         } });
            });
        } else if (alg.kind !== 'none') {
            state.points.forEach((p, k) => {
                h.push({ at: p, move: (x, y) => { state.points[k] = [x, y]; } });
            });
        }
        if (hasSeed) {
            h.push({ at: [state.seed[0] + 0.5, state.seed[1] + 0.5],
                     move: (x, y) => {
                         state.seed = [pixel(x, alg.grid[0]), pixel(y, alg.grid[1])];
                     } });
        }
        if (hasRow) {
            h.push({ at: [0.5, state.row + 0.5],
                     dist: (g) => Math.abs(g[1] - state.row - 0.5),
                     move: (x, y) => { state.row = pixel(y, alg.grid[1]); } });
        }
        if (hasHighlight) {
            h.push({ at: state.highlight, move: (x, y) => { state.highlight = [x, y]; } });
        }
        if (hasWindow) {
            for (const k of [0, 2]) {
                h.push({ at: state.window.slice(k, k + 2),
                         move: (x, y) => state.window.splice(k, 2, x, y) });
            }
        }
        return h;
    }
    window.explainHandles = () => handles().map((h) => h.at);

    // A pointer event's position in grid coordinates (pixels of the
    // primitive), the canvas possibly scaled by the page's width.
    function gridPoint(e) {
        const r = canvas.getBoundingClientRect();
        const fx = (e.clientX - r.left) * canvas.width / r.width;
        const fy = (e.clientY - r.top) * canvas.height / r.height;
        return [(fx - margin) / alg.zoom, (fy - margin) / alg.zoom];
    }

    // The handle within reach of g, or -1.
    function nearest(g) {
        let best = -1, bestD = HANDLE_RADIUS / alg.zoom;
        handles().forEach((h, k) => {
            const d = h.dist ? h.dist(g) : Math.hypot(h.at[0] - g[0], h.at[1] - g[1]);
            if (d <= bestD) {
                best = k;
                bestD = d;
            }
        });
        return best;
    }

    function snap(v, size) {
        v = Math.max(0, Math.min(size, v));
        return ENDS_ON_CENTRES.includes(alg.name) ? Math.floor(v) + 0.5 : Math.round(v * 10) / 10;
    }

    let dragging = -1, pending = null;
    canvas.addEventListener('pointerdown', (e) => {
        dragging = nearest(gridPoint(e));
        if (dragging >= 0) {
            canvas.setPointerCapture(e.pointerId);
            canvas.classList.add('dragging');
        }
    });
    canvas.addEventListener('pointermove', (e) => {
        const g = gridPoint(e);
        canvas.classList.toggle('near', nearest(g) >= 0);
        if (dragging < 0) {
            return;
        }
        pending = [snap(g[0], alg.grid[0]), snap(g[1], alg.grid[1])];
        requestAnimationFrame(() => {
            if (!pending || dragging < 0) {
                return;
            }
            // A position the tool refuses (a clip window turned inside
            // out) keeps the last one it took; its message stays shown.
            const before = snapshot();
            handles()[dragging].move(pending[0], pending[1]);
            pending = null;
            if (!render()) {
                const why = message.textContent;
                restore(before);
                render();
                message.textContent = why;
            }
        });
    });
    const drop = () => {
        dragging = -1;
        canvas.classList.remove('dragging');
    };
    canvas.addEventListener('pointerup', drop);
    canvas.addEventListener('pointercancel', drop);

    document.getElementById('first').onclick = () => go(0);
    document.getElementById('prev').onclick = () => go(state.step - 1);
    document.getElementById('next').onclick = () => go(state.step + 1);
    document.getElementById('last').onclick = () => go(state.frames.length - 1);
    stepInput.oninput = () => go(Number(stepInput.value));
    document.addEventListener('keydown', (e) => {
        const to = { ArrowLeft: state.step - 1, ArrowRight: state.step + 1, Home: 0,
                     End: state.frames.length - 1 }[e.key];
        if (to !== undefined && e.target.tagName !== 'SELECT') {
            go(to);
            e.preventDefault();
        }
    });
    document.getElementById('reset').onclick = () => {
        reset();
        render();
    };

    const optionsBox = document.getElementById('options');
    for (const o of OPTIONS.filter((o) => o.applies(alg))) {
        const label = document.createElement('label');
        label.textContent = `${o.label} `;
        const select = document.createElement('select');
        select.name = o.option;
        for (const v of o.values) {
            select.add(new Option(v, v));
        }
        select.onchange = () => {
            choices[o.option] = select.value;
            render();
        };
        label.append(select);
        optionsBox.append(label);
    }
    reset();
    if (!render()) {
        throw new Error(message.textContent);
    }
    window.explainReady = true;
}

main().catch((e) => {
    document.getElementById('message').textContent = String(e);
    console.error(e);
});
