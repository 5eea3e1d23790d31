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
      applies: (a) => a.kind === 'polygon' },
    { option: '--samples', label: 'samples per pixel', values: ['4', '2', '8', '16'],
      applies: (a) => a.name === 'msaa' },
    { option: '--connectivity', label: 'connectivity', values: ['4', '8'],
      applies: (a) => a.name === 'floodfill' },
];
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
    document.querySelectorAll('.window-hint').forEach((e) => { e.hidden = !hasWindow; });

    const canvas = document.getElementById('frame');
    const ctx2d = canvas.getContext('2d');
    const stepInput = document.getElementById('step');
    const message = document.getElementById('message');
    const choices = {};
    const state = { points: [], window: [], step: 0, frames: [], width: 0, height: 0 };

    function reset() {
        state.points = alg.points.map((p) => p.slice());
        state.window = alg.window.slice();
        for (const o of OPTIONS.filter((o) => o.applies(alg))) {
            choices[o.option] = o.values[0];
        }
        document.querySelectorAll('#options select').forEach((s) => {
            s.value = choices[s.name];
        });
    }

    // The arguments after `softrast explain NAME` for what the page shows.
    function args() {
        const a = alg.kind === 'none' ? []
            : [`--${alg.kind}`, state.points.map((p) => p.map(number).join(',')).join(',')];
        if (hasWindow) {
            a.push('--window', state.window.map(number).join(','));
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

    // The draggable points in grid coordinates: the primitive's vertices,
    // then the clip window's two corners.
    function handles() {
        const h = alg.kind === 'none' ? [] : state.points.map((p) => p.slice());
        if (hasWindow) {
            h.push(state.window.slice(0, 2), state.window.slice(2, 4));
        }
        return h;
    }

    function moveHandle(k, x, y) {
        if (k < state.points.length) {
            state.points[k] = [x, y];
        } else {
            state.window.splice(2 * (k - state.points.length), 2, x, y);
        }
    }

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
        handles().forEach((p, k) => {
            const d = Math.hypot(p[0] - g[0], p[1] - g[1]);
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
            const before = { points: state.points.map((p) => p.slice()), window: state.window.slice() };
            moveHandle(dragging, pending[0], pending[1]);
            pending = null;
            if (!render()) {
                const why = message.textContent;
                state.points = before.points;
                state.window = before.window;
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
