// make_pages.cjs SITE SRC - one page per algorithm of `softrast explain`,
// as the WebAssembly module in SITE lists them, from SRC's templates
// (page.html.in, index.html.in), and the index linking them.
'use strict';
const fs = require('fs');
const path = require('path');

const [site, src] = process.argv.slice(2);
const escape = (s) => s.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');

require(path.resolve(site, 'softrast-explain.js'))().then((mod) => {
    const algorithms = [];
    for (let i = 0; ; i++) {
        const json = mod.ccall('web_algorithm', 'string', ['number'], [i]);
        if (!json) {
            break;
        }
        algorithms.push(JSON.parse(json));
    }
    const page = fs.readFileSync(path.join(src, 'page.html.in'), 'utf8');
    const nav = algorithms.map((a) => `<a href="${a.name}.html">${a.name}</a>`).join('\n');
    for (const a of algorithms) {
        const html = page.replaceAll('@NAME@', a.name).replaceAll('@SUMMARY@', escape(a.summary))
            .replaceAll('@NAV@', nav);
        fs.writeFileSync(path.join(site, `${a.name}.html`), html);
    }
    const items = algorithms
        .map((a) => `<li><a href="${a.name}.html">${a.name}</a>: ${escape(a.summary)}</li>`)
        .join('\n');
    const index = fs.readFileSync(path.join(src, 'index.html.in'), 'utf8');
    fs.writeFileSync(path.join(site, 'index.html'), index.replaceAll('@ITEMS@', items));
    console.log(`${algorithms.length} pages in ${site}`);
});
