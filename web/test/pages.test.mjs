// pages.test.mjs - the interactive pages in a real browser: Debian's
// chromium, headless, driven by playwright-core.  For every page of the
// built site: it loads without console errors, a scripted drag of the
// first handle changes the canvas, and every step's canvas equals, pixel
// for pixel, the PNG frame the native `softrast explain` writes for the
// same arguments (the page shows them as its command line).
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
    const before = await canvasPixels(page);
    const argsBefore = await page.evaluate(() => window.explainArgs.join(' '));

    // Drag the first vertex three cells right and two down, as a user would.
    const at = await page.evaluate(() => {
        const c = document.getElementById('frame').getBoundingClientRect();
        return { left: c.left, top: c.top };
    });
    const alg = JSON.parse(await page.evaluate(() => {
        const mod = document.body.dataset.algorithm;
        return JSON.stringify({ name: mod, args: window.explainArgs });
    }));
    // Pages of algorithms whose primitive has no handles yet (kind 'none':
    // zbuffer, circle, ... step through their example only) skip the drag.
    const draggable = ['--triangle', '--polygon', '--line'].includes(alg.args[1]);
    const first = draggable ? alg.args[2].split(',').map(Number) : [0, 0];
    const zoom = Number(alg.args[alg.args.indexOf('--zoom') + 1]);
    const margin = 16;
    const x0 = at.left + margin + first[0] * zoom, y0 = at.top + margin + first[1] * zoom;
    if (draggable) {
        await page.mouse.move(x0, y0);
        await page.mouse.down();
        for (let k = 1; k <= 4; k++) {
            await page.mouse.move(x0 + 0.75 * k * zoom, y0 + 0.5 * k * zoom);
        }
        await page.mouse.up();
        await page.waitForFunction((a) => window.explainArgs.join(' ') !== a, argsBefore,
                                   { timeout: 10000 }).catch(() => {});
    }
    const after = await canvasPixels(page);
    const args = await page.evaluate(() => window.explainArgs);
    if (draggable && args.join(' ') === argsBefore) {
        fail(file, 'the drag did not move the vertex');
    } else if (draggable && after === before) {
        fail(file, 'the drag did not change the canvas');
    }

    // Every step against the native tool's frames for the same arguments.
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'softrast-web-'));
    execFileSync(softrast, ['explain', ...args, '-o', dir]);
    const frames = fs.readdirSync(dir).filter((f) => f.endsWith('.png')).sort();
    const steps = await page.evaluate(() => Number(document.getElementById('step').max) + 1);
    if (steps !== frames.length) {
        fail(file, `${steps} steps in the page, ${frames.length} frames from softrast`);
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
        fail(file, `${differ} of ${frames.length} steps differ from softrast explain ${args.join(' ')}`);
    }
    if (errors.length) {
        fail(file, `console errors: ${errors.join('; ')}`);
    }
    if (!differ && !errors.length) {
        console.log(`ok   ${file}: ${frames.length} steps equal the native frames${draggable ? " after the drag" : " (no handles)"}`);
    }
    await page.close();
}
await browser.close();
server.kill();
console.log(failures ? `${failures} failures` : `all ${pages.length} pages pass`);
process.exit(failures ? 1 : 0);
