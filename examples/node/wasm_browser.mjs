// wqmesh: wasm in headless Chromium against the native command line, cold and
// warm, through the package's worker (issue 15). A measurement, not a test;
// Linux only (/proc, /usr/bin/time). For each run: the native command line
// (user + system CPU, stats.time_s), then for each package a fresh browser
// (a new profile: nothing cached) and in it two page loads; in each load the
// page imports the package's index.mjs and calls mesh() --calls times (a
// new document: a new package instance and a new worker). Load 1 is a first
// visit; load 2 a later visit: the HTTP cache holds the files and, with a
// separate wqmesh.wasm compiled by compileStreaming, Chromium's wasm code
// cache the code V8 optimized in load 1. The server lets the HTTP cache keep
// the files (Cache-Control: max-age=3600). Per call it records the mesh()
// call as the page sees it, the run's time_s, INITIALIZE and CONFORM, and
// the CPU seconds (user + system) of all the browser's processes during the
// call, from /proc (the renderer that runs the worker and V8's compiler
// threads included).
// Usage: node examples/node/wasm_browser.mjs [--runs N] [--calls N] [--cli BIN] [--pkg DIR]... MODEL...
//   defaults: --runs 3, --calls 2, --cli build/native/bin/wqmesh, --pkg wasm
// SPDX-License-Identifier: GPL-3.0-or-later
import { mkdtempSync, readFileSync, rmSync, symlinkSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

import { browserSkipReason, launchBrowser, CHROMIUM } from '../../tests/browser/lib/browser.mjs';
import { serve } from '../../scripts/serve.mjs';
import { descendantPids, median, nativeRun, pairArgs, spread } from './wasm_pairs.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const { runs, calls, cli, pkgs, models } = pairArgs(process.argv.slice(2), {
  root, calls: 2, usage: 'usage: node examples/node/wasm_browser.mjs [--runs N] [--calls N] [--cli BIN] [--pkg DIR]... MODEL...' });
const reason = browserSkipReason();
if (reason) {
  console.error(`wasm_browser: cannot run: ${reason}`);
  process.exit(1);
}

// utime + stime (s) of every process below this one: the browser's.
function browserCpu() {
  let ticks = 0;
  for (const pid of descendantPids()) {
    try {
      const s = readFileSync(`/proc/${pid}/stat`, 'utf8');
      const f = s.slice(s.lastIndexOf(')') + 2).split(' ');
      ticks += Number(f[11]) + Number(f[12]);
    } catch {
      // the process ended meanwhile
    }
  }
  return ticks / 100;
}

// The site: pkg/J -> the J-th package folder, and a page that imports it.
const site = mkdtempSync(join(tmpdir(), 'wqmesh-browser-'));
pkgs.forEach((p, j) => symlinkSync(p, join(site, `pkg${j}`)));
const server = await serve({ root: site, cacheControl: 'max-age=3600' });
const work = mkdtempSync(join(tmpdir(), 'wqmesh-browser-work-'));

const native = (model) => nativeRun(cli, model, work, true);

/** Two page loads in a fresh browser, `calls` mesh() calls in each: [load][call] of figures. */
async function browserRuns(j, bytes) {
  const b = await launchBrowser({ timeout: 3600000 });
  try {
    const { page } = b;
    await page.route(`${server.url}__b/**`, (route) => route.fulfill({
      status: 200, contentType: route.request().url().endsWith('.html') ? 'text/html' : 'text/javascript',
      body: route.request().url().endsWith('.html') ? '<!doctype html><script type="module" src="/__b/m.mjs"></script>'
        : `import * as w from '/pkg${j}/index.mjs'; window.wqmesh = w;`,
    }));
    const loads = [];
    for (let load = 0; load < 2; ++load) {
      await page.goto(`${server.url}__b/index.html`);
      await page.waitForFunction(() => window.wqmesh !== undefined);
      const out = [];
      for (let c = 0; c < calls; ++c) {
        const c0 = browserCpu();
        const r = await page.evaluate(async (b64) => {
          const bin = Uint8Array.from(atob(b64), (ch) => ch.charCodeAt(0));
          const t = performance.now();
          const m = await window.wqmesh.mesh(bin);
          return { call: (performance.now() - t) / 1000, core: m.stats.time_s, tets: m.stats.tets,
                   init: m.stats.phases[0].time_s, conform: m.stats.phases[1].time_s };
        }, bytes.toString('base64'));
        out.push({ ...r, cpu: browserCpu() - c0 });
      }
      loads.push(out);
      // Chromium writes its code cache after V8's tier-up, in the background.
      await new Promise((ok) => setTimeout(ok, 2000));
    }
    return loads;
  } finally {
    await b.close();
  }
}

console.log(`runs ${runs}, paired; figures: median [min-max] in s; ratios: median of the pairs' ratios; ` +
            `Chromium ${CHROMIUM}`);
for (const model of models) {
  const bytes = readFileSync(model);
  const n = [];
  const w = pkgs.map(() => []);
  for (let k = 0; k < runs; ++k) {
    n.push(native(model));
    for (let j = 0; j < pkgs.length; ++j) w[j].push(await browserRuns(j, bytes));
  }
  console.log(`\n${basename(model)}: ${n[0].tets} tets; native cpu ${spread(n.map((x) => x.cpu))}, time_s ${spread(n.map((x) => x.core))}`);
  pkgs.forEach((p, j) => {
    console.log(`  ${p}: ${w[j][0][0][0].tets} tets`);
    for (let load = 0; load < 2; ++load) {
      for (let c = 0; c < calls; ++c) {
        const xs = w[j].map((x) => x[load][c]);
        const ratio = (f, g) => median(xs.map((x, k) => f(x) / g(n[k]))).toFixed(3);
        console.log(`    load ${load + 1} call ${c + 1}: time_s ${spread(xs.map((x) => x.core))} /native ${ratio((x) => x.core, (y) => y.core)}; ` +
                    `browser cpu ${spread(xs.map((x) => x.cpu))} /native cpu ${ratio((x) => x.cpu, (y) => y.cpu)}; ` +
                    `mesh() ${spread(xs.map((x) => x.call))}; initialize ${spread(xs.map((x) => x.init))}, ` +
                    `conform ${spread(xs.map((x) => x.conform))}`);
      }
    }
  });
}
await server.close();
rmSync(site, { recursive: true, force: true });
rmSync(work, { recursive: true, force: true });
