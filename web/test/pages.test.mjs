// pages.test.mjs - the interactive pages in a real browser: Debian's
// chromium, headless, driven by playwright-core.  For every page of the
// built site: it loads without console errors, scripted drags of its
// first and last handles change the canvas, and every step's canvas
// equals, pixel for pixel, the PNG frame the native `softrast explain`
// writes for the same arguments (the page shows them as its command
// line), after the drags and again with each option the page offers
// switched.
//
//   node test/pages.test.mjs SITE_DIR SOFTRAST [CHROMIUM]
//
// SITE_DIR is the built site (scripts/wasm.sh web), SOFTRAST the native
// tool.  Exit status 0 when every page passes.
import { execFileSync, spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';

const [site, softrast, browserPath = '/usr/bin/chromium'] = process.argv.slice(2);
if (!site || !softrast) {
    console.error('usage: node test/pages.test.mjs SITE_DIR SOFTRAST [CHROMIUM]');
    process.exit(2);
}
const pages = fs.readdirSync(site).filter((f) => f.endsWith('.html') && f !== 'index.html');

// python3 -m http.server, as the README serves the site.
const port = 20000 + (process.pid % 20000);
const server = spawn('/usr/bin/python3', ['-m', 'http.server', String(port), '--bind', '127.0.0.1',
                                          '--directory', site], { stdio: 'ignore' });
const base = `http://127.0.0.1:${port}`;
for (let i = 0; ; i++) {
    try {
        await fetch(`${base}/index.html`);
        break;
    } catch (e) {
        if (i === 100) {
            throw e;
        }
        await new Promise((r) => setTimeout(r, 100));
    }
}

const browser = await chromium.launch({ executablePath: browserPath, headless: true,
                                        args: ['--no-sandbox'] });
let failures = 0;
const fail = (page, why) => {
    console.log(`FAIL ${page}: ${why}`);
    failures++;
};

// The canvas's RGBA bytes as base64.
const canvasPixels = (page) => page.evaluate(() => {
    const c = document.getElementById('frame');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let s = '';
    for (let i = 0; i < d.length; i += 0x8000) {
        s += String.fromCharCode.apply(null, d.subarray(i, i + 0x8000));
    }
    return btoa(s);
});

// A PNG decoded by the browser into RGBA bytes as base64, with its size.
const pngPixels = (page, file) => page.evaluate(async (url) => {
    const img = new Image();
    img.src = url;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width;
    c.height = img.height;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    let s = '';
    for (let i = 0; i < d.length; i += 0x8000) {
        s += String.fromCharCode.apply(null, d.subarray(i, i + 0x8000));
    }
    return btoa(s);
}, `data:image/png;base64,${fs.readFileSync(file).toString('base64')}`);

for (const file of pages) {
    const page = await browser.newPage({ viewport: { width: 1400, height: 1400 } });
    const errors = [];
    page.on('console', (m) => {
        if (m.type() === 'error') {
            errors.push(m.text());
        }
    });
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.goto(`${base}/${file}`);
    try {
        await page.waitForFunction(() => window.explainReady === true, null, { timeout: 30000 });
    } catch (e) {
        fail(file, `never ready: ${errors.join('; ') || e.message}`);
        await page.close();
        continue;
    }
    const failed = failures;
    // Drag a handle three cells right and two down, as a user would: the
    // first (a vertex, the circle's centre) and the last (the seed, the
    // span's row, a clip window's corner, the circle's rim; on clip4d
    // another vertex), where they differ.  Each drag must change the
    // arguments and the canvas.
    const at = await page.evaluate(() => {
        const c = document.getElementById('frame').getBoundingClientRect();
        return { left: c.left, top: c.top };
    });
    const handles = await page.evaluate(() => window.explainHandles());
    if (handles.length === 0) {
        fail(file, 'the page has no handle to drag');
    }
    const zoomOf = (a) => Number(a[a.indexOf('--zoom') + 1]);
    const margin = 16;
    for (const k of new Set([0, handles.length - 1].filter((k) => k >= 0 && k < handles.length))) {
        const before = await canvasPixels(page);
        const argsBefore = await page.evaluate(() => window.explainArgs.join(' '));
        const zoom = zoomOf(await page.evaluate(() => window.explainArgs));
        const h = (await page.evaluate(() => window.explainHandles()))[k];
        const x0 = at.left + margin + h[0] * zoom, y0 = at.top + margin + h[1] * zoom;
        await page.mouse.move(x0, y0);
        await page.mouse.down();
        for (let i = 1; i <= 4; i++) {
            await page.mouse.move(x0 + 0.75 * i * zoom, y0 + 0.5 * i * zoom);
        }
        await page.mouse.up();
        await page.waitForFunction((a) => window.explainArgs.join(' ') !== a, argsBefore,
                                   { timeout: 10000 }).catch(() => {});
        if (await page.evaluate(() => window.explainArgs.join(' ')) === argsBefore) {
            fail(file, `the drag did not move handle ${k}`);
        } else if (await canvasPixels(page) === before) {
            fail(file, `the drag of handle ${k} did not change the canvas`);
        }
    }

    // Every step against the native tool's frames for the same arguments:
    // after the drags, then with each option the page offers switched to
    // each of its other values in turn.
    const compare = async (when) => {
        const args = await page.evaluate(() => window.explainArgs);
        const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'softrast-web-'));
        execFileSync(softrast, ['explain', ...args, '-o', dir]);
        const frames = fs.readdirSync(dir).filter((f) => f.endsWith('.png')).sort();
        const steps = await page.evaluate(() => Number(document.getElementById('step').max) + 1);
        if (steps !== frames.length) {
            fail(file, `${when}: ${steps} steps in the page, ${frames.length} frames from softrast`);
        }
        await page.click('#first');
        let differ = 0;
        for (let i = 0; i < Math.min(steps, frames.length); i++) {
            if (i > 0) {
                await page.click('#next');
            }
            const shown = await canvasPixels(page);
            if (shown !== await pngPixels(page, path.join(dir, frames[i]))) {
                differ++;
            }
        }
        fs.rmSync(dir, { recursive: true });
        if (differ) {
            fail(file, `${when}: ${differ} of ${frames.length} steps differ from ` +
                       `softrast explain ${args.join(' ')}`);
        }
        return differ ? 0 : frames.length;
    };
    let checked = [await compare('after the drags')];
    const options = await page.evaluate(() => [...document.querySelectorAll('#options select')]
        .flatMap((s) => [...s.options].slice(1).map((o) => ({ name: s.name, value: o.value }))));
    for (const o of options) {
        const argsBefore = await page.evaluate(() => window.explainArgs.join(' '));
        await page.selectOption(`select[name="${o.name}"]`, o.value);
        await page.waitForFunction((a) => window.explainArgs.join(' ') !== a, argsBefore,
                                   { timeout: 10000 }).catch(() => {});
        const args = await page.evaluate(() => window.explainArgs);
        if (args[args.indexOf(o.name) + 1] !== o.value) {
            fail(file, `choosing ${o.name} ${o.value} did not reach the arguments`);
        }
        checked.push(await compare(`${o.name} ${o.value}`));
    }
    if (errors.length) {
        fail(file, `console errors: ${errors.join('; ')}`);
    }
    if (failures === failed && !errors.length) {
        const then = options.map((o) => `${o.name} ${o.value}`).join(', ');
        console.log(`ok   ${file}: ${handles.length} handles, first and last dragged; ` +
                    `${checked.join(' + ')} steps equal the native frames${then ? `, after the drags and with ${then}` : ''}`);
    }
    await page.close();
}
await browser.close();
server.kill();
console.log(failures ? `${failures} failures` : `all ${pages.length} pages pass`);
process.exit(failures ? 1 : 0);
