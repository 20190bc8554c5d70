// wqmesh: one large run in headless Chromium through the package's worker
// (issue 15, item 5): a page served by scripts/serve.mjs imports
// wasm/index.mjs and calls mesh(bytes, { maxSize }), which runs in a module
// Worker; the page posts the input and receives the result's arrays
// (transferred). Prints the time of the mesh() call as the page sees it, the
// run's own time_s and phases, the tets, the wasm memory the module ended
// with (memoryStats().heapBytes: it only grows, so it is the run's peak), the
// peak of the live C++ allocations (stats.peak_memory_mb) and the peak
// resident memory of the browser's processes (sampled from /proc every
// 200 ms: the largest one, and the sum at its largest). A measurement, not a
// test. The default model and bound are those of the growth series of
// examples/node/benchmark.mjs (spike.off) at about a million tets.
// Usage: node examples/node/browser_million.mjs [--model FILE] [--max-size H]
// SPDX-License-Identifier: GPL-3.0-or-later
import { readFileSync, readdirSync } from 'node:fs';
import { basename, dirname, join, resolve } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath } from 'node:url';

import { browserSkipReason, launchBrowser, CHROMIUM } from '../../tests/browser/lib/browser.mjs';
import { serve } from '../../scripts/serve.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const args = process.argv.slice(2);
let model = join(root, 'examples/models/spike.off');
let maxSize = 0.022;
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--model') model = resolve(args[++i]);
  else if (args[i] === '--max-size') maxSize = Number(args[++i]);
  else {
    console.error('usage: node examples/node/browser_million.mjs [--model FILE] [--max-size H]');
    process.exit(1);
  }
}
const reason = browserSkipReason();
if (reason) {
  console.error(`browser_million: cannot run: ${reason}`);
  process.exit(1);
}

// The resident memory (kB) of every process whose command line names the
// browser binary, read from /proc.
function browserRss() {
  const out = [];
  for (const pid of readdirSync('/proc').filter((d) => /^\d+$/.test(d))) {
    try {
      const cmd = readFileSync(`/proc/${pid}/cmdline`, 'utf8');
      if (!cmd.startsWith(CHROMIUM) && !cmd.includes('/chromium/chromium')) continue;
      const m = /VmRSS:\s+(\d+) kB/.exec(readFileSync(`/proc/${pid}/status`, 'utf8'));
      if (m) out.push(Number(m[1]));
    } catch {
      // the process ended meanwhile
    }
  }
  return out;
}

const server = await serve({ root });
const b = await launchBrowser({ timeout: 3600000 });
let peakOne = 0;
let peakSum = 0;
const sampler = setInterval(() => {
  const rss = browserRss();
  peakOne = Math.max(peakOne, ...rss);
  peakSum = Math.max(peakSum, rss.reduce((a, x) => a + x, 0));
}, 200);
try {
  const page = b.page;
  await page.route(`${server.url}__million/**`, (route) => route.fulfill({
    status: 200, contentType: route.request().url().endsWith('.html') ? 'text/html' : 'text/javascript',
    body: route.request().url().endsWith('.html') ? '<!doctype html><script type="module" src="/__million/m.mjs"></script>'
      : "import * as w from '/wasm/index.mjs'; window.wqmesh = w;",
  }));
  await page.goto(`${server.url}__million/index.html`);
  await page.waitForFunction(() => window.wqmesh !== undefined);
  const bytes = readFileSync(model);
  console.log(`${basename(model)}, maxSize ${maxSize}, Chromium ${b.context.browser()?.version() ?? ''}`);
  const t0 = performance.now();
  const r = await page.evaluate(async ({ b64, maxSize }) => {
    const bin = Uint8Array.from(atob(b64), (ch) => ch.charCodeAt(0));
    const t = performance.now();
    const res = await window.wqmesh.mesh(bin, { maxSize });
    return {
      page_s: (performance.now() - t) / 1000, stats: res.stats, memory: res.memory, tets: res.tets.length / 4,
      js_heap_mb: performance.memory ? performance.memory.usedJSHeapSize / 1048576 : null,
    };
  }, { b64: bytes.toString('base64'), maxSize });
  const total = (performance.now() - t0) / 1000;
  const s = r.stats;
  const peakMb = s.peak_memory_mb ?? s.memory?.peak_mb;
  console.log(`tets ${r.tets}, vertices ${s.vertices}, conforming ${s.conforming}, stopped '${s.stopped}'`);
  console.log(`mesh() in the page: ${r.page_s.toFixed(2)} s (with posting the input: ${total.toFixed(2)} s); ` +
              `time_s ${s.time_s.toFixed(2)} s; phases: ${s.phases.map((p) => `${p.name} ${p.time_s.toFixed(2)}`).join(', ')}`);
  console.log(`wasm memory at the end (= its peak) ${(r.memory.heapBytes / 1048576).toFixed(0)} MB; ` +
              `peak live C++ allocations ${peakMb?.toFixed(0)} MB ` +
              `(${Math.round(peakMb * 1048576 / r.tets)} bytes per tet); page JS heap ${r.js_heap_mb?.toFixed(0)} MB`);
  console.log(`browser processes' peak RSS: largest process ${(peakOne / 1024).toFixed(0)} MB, ` +
              `all together ${(peakSum / 1024).toFixed(0)} MB`);
} finally {
  clearInterval(sampler);
  await b.close();
  await server.close();
}
