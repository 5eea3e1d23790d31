#!/usr/bin/env node
// Render SVGs with resvg for compare.py, all in one process: each line of
// standard input is "IN<TAB>OUT<TAB>WIDTH"; the drawing is scaled to WIDTH
// pixels (its proportions kept) and written as an RGBA PNG.  One line of
// output per input: "ok" or "error: ...".  Needs `npm ci --prefix
// tools/svg-compare` (the @resvg/resvg-js package and its prebuilt binary).
'use strict';
const fs = require('fs');
const path = require('path');
const readline = require('readline');
const { Resvg } = require('@resvg/resvg-js');

const start = process.cwd();
const lines = readline.createInterface({ input: process.stdin });
lines.on('line', (line) => {
  const [input, output, width] = line.split('\t');
  try {
    // relative image paths resolve from the current directory (the
    // resourcesDir option is not used: with it, fitTo is ignored)
    const data = fs.readFileSync(path.resolve(start, input));
    process.chdir(path.dirname(path.resolve(start, input)));
    const resvg = new Resvg(data, {
      fitTo: { mode: 'width', value: Number(width) },
      font: { loadSystemFonts: false },
    });
    fs.writeFileSync(path.resolve(start, output), resvg.render().asPng());
    console.log('ok');
  } catch (e) {
    console.log('error: ' + String(e.message || e).split('\n')[0]);
  }
});
