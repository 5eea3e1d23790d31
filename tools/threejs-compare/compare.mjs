// compare.mjs - image-difference figures between two PNGs of the same size
// (softrast's and three.js's renders of one asset), and a difference image.
//
//   node compare.mjs A.png B.png [--threshold T] [--background #rrggbb]
//        [--diff DIFF.png] [--sheet SHEET.png]
//
// Prints one JSON object: the mean absolute difference per channel (0..255
// codes), the PSNR over R, G and B, and the share of pixels whose largest
// channel difference exceeds T codes - over the whole image, and over the
// object's pixels (those where either image is not the background colour).
// DIFF.png is |A - B| times 4; SHEET.png is A, B and DIFF side by side.
import { readFileSync, writeFileSync } from 'node:fs';
import { deflateSync, inflateSync } from 'node:zlib';

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    return c >>> 0;
});

function crc32(buf) {
    let c = 0xffffffff;
    for (const b of buf) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
    return (c ^ 0xffffffff) >>> 0;
}

// 8-bit, non-interlaced grey, grey-alpha, RGB or RGBA PNGs, read to RGB
// (alpha dropped: both renderers write opaque images).
function readPng(file) {
    const d = readFileSync(file);
    if (d.toString('latin1', 1, 4) !== 'PNG') throw new Error(`${file}: not a PNG`);
    let pos = 8, w = 0, h = 0, type = 0;
    const idat = [];
    while (pos < d.length) {
        const len = d.readUInt32BE(pos), name = d.toString('latin1', pos + 4, pos + 8);
        const body = d.subarray(pos + 8, pos + 8 + len);
        if (name === 'IHDR') {
            w = body.readUInt32BE(0);
            h = body.readUInt32BE(4);
            type = body[9];
            if (body[8] !== 8 || body[12] !== 0 || ![0, 2, 4, 6].includes(type)) {
                throw new Error(`${file}: only 8-bit non-interlaced grey/RGB(A) PNGs are read`);
            }
        } else if (name === 'IDAT') idat.push(body);
        pos += 12 + len;
    }
    const bpp = { 0: 1, 2: 3, 4: 2, 6: 4 }[type], stride = w * bpp;
    const raw = inflateSync(Buffer.concat(idat)), px = Buffer.alloc(stride * h);
    for (let y = 0; y < h; y++) {
        const f = raw[y * (stride + 1)], src = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
        for (let x = 0; x < stride; x++) {
            const a = x >= bpp ? px[y * stride + x - bpp] : 0;
            const b = y > 0 ? px[(y - 1) * stride + x] : 0;
            const c = x >= bpp && y > 0 ? px[(y - 1) * stride + x - bpp] : 0;
            let p = 0;
            if (f === 1) p = a;
            else if (f === 2) p = b;
            else if (f === 3) p = (a + b) >> 1;
            else if (f === 4) {
                const e = a + b - c, pa = Math.abs(e - a), pb = Math.abs(e - b), pc = Math.abs(e - c);
                p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
            }
            px[y * stride + x] = (src[x] + p) & 0xff;
        }
    }
    const rgb = Buffer.alloc(w * h * 3);
    for (let i = 0; i < w * h; i++) {
        for (let k = 0; k < 3; k++) rgb[i * 3 + k] = px[i * bpp + (bpp < 3 ? 0 : k)];
    }
    return { w, h, rgb };
}

function writePng(file, w, h, rgb) {
    const chunk = (name, body) => {
        const head = Buffer.alloc(8), tail = Buffer.alloc(4);
        head.writeUInt32BE(body.length, 0);
        head.write(name, 4, 'latin1');
        tail.writeUInt32BE(crc32(Buffer.concat([head.subarray(4), body])), 0);
        return Buffer.concat([head, body, tail]);
    };
    const ihdr = Buffer.alloc(13);
    ihdr.writeUInt32BE(w, 0);
    ihdr.writeUInt32BE(h, 4);
    ihdr.set([8, 2, 0, 0, 0], 8);
    const raw = Buffer.alloc(h * (w * 3 + 1));
    for (let y = 0; y < h; y++) rgb.copy(raw, y * (w * 3 + 1) + 1, y * w * 3, (y + 1) * w * 3);
    writeFileSync(file, Buffer.concat([Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
        chunk('IHDR', ihdr), chunk('IDAT', deflateSync(raw, { level: 9 })), chunk('IEND', Buffer.alloc(0))]));
}

function parseArgs(argv) {
    const o = { files: [], threshold: 16, background: '#1d2230', diff: null, sheet: null };
    for (let i = 0; i < argv.length; i++) {
        const a = argv[i];
        if (a === '--threshold') o.threshold = Number(argv[++i]);
        else if (a === '--background') o.background = argv[++i];
        else if (a === '--diff') o.diff = argv[++i];
        else if (a === '--sheet') o.sheet = argv[++i];
        else o.files.push(a);
    }
    const m = /^#([0-9a-f]{2})([0-9a-f]{2})([0-9a-f]{2})$/i.exec(o.background || '');
    if (o.files.length !== 2 || !m || !(o.threshold >= 0)) {
        console.error('usage: node compare.mjs A.png B.png [--threshold T] [--background #rrggbb] ' +
                      '[--diff DIFF.png] [--sheet SHEET.png]');
        process.exit(2);
    }
    o.bg = [1, 2, 3].map((k) => parseInt(m[k], 16));
    return o;
}

const o = parseArgs(process.argv.slice(2));
const [a, b] = o.files.map(readPng);
if (a.w !== b.w || a.h !== b.h) {
    console.error(`compare.mjs: ${o.files[0]} is ${a.w}x${a.h}, ${o.files[1]} is ${b.w}x${b.h}`);
    process.exit(2);
}
const n = a.w * a.h, diff = Buffer.alloc(n * 3);
const sum = [0, 0, 0];
let sq = 0, over = 0, object = 0, objectOver = 0, objectSq = 0;
for (let i = 0; i < n; i++) {
    let worst = 0, isBgA = true, isBgB = true, s = 0;
    for (let k = 0; k < 3; k++) {
        const d = Math.abs(a.rgb[i * 3 + k] - b.rgb[i * 3 + k]);
        sum[k] += d;
        s += d * d;
        worst = Math.max(worst, d);
        diff[i * 3 + k] = Math.min(255, d * 4);
        isBgA &&= a.rgb[i * 3 + k] === o.bg[k];
        isBgB &&= b.rgb[i * 3 + k] === o.bg[k];
    }
    sq += s;
    over += worst > o.threshold;
    if (!(isBgA && isBgB)) {
        object++;
        objectSq += s;
        objectOver += worst > o.threshold;
    }
}
// Identical pixels have no finite PSNR: "inf".
const psnr = (s, count) => (s === 0 ? 'inf' : r2(10 * Math.log10((255 * 255 * 3 * count) / s)));
function r2(x) {
    return Math.round(x * 100) / 100;
}
console.log(JSON.stringify({
    width: a.w, height: a.h, threshold: o.threshold,
    mad: sum.map((s) => r2(s / n)), psnr: psnr(sq, n), over_pct: r2((100 * over) / n),
    object_px: object, object_psnr: psnr(objectSq, object),
    object_over_pct: object ? r2((100 * objectOver) / object) : 0,
}));
if (o.diff) writePng(o.diff, a.w, a.h, diff);
if (o.sheet) {
    const w = a.w * 3, sheet = Buffer.alloc(w * a.h * 3);
    for (let y = 0; y < a.h; y++) {
        [a.rgb, b.rgb, diff].forEach((img, j) =>
            img.copy(sheet, (y * w + j * a.w) * 3, y * a.w * 3, (y + 1) * a.w * 3));
    }
    writePng(o.sheet, w, a.h, sheet);
}
