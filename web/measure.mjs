// wqmesh page: measures the viewer on big meshes in headless Chromium (the
// figures of the README's "Web page" section). Serves build/web, opens the
// page, views a structured test mesh of 6 n^3 tets (tetfaces.mjs gridMesh,
// through the page's measurement hook __wqmeshPage.loadSynthetic) and
// prints: time to the first picture (table build included), the face-table
// build, the median and worst of several clip-plane updates (request to the
// frame drawn), the main thread's longest timer gap and longest task
// meanwhile, and the resident memory of
// all Chromium processes.
// With --example NAME --max-size H it meshes that example in the page
// instead and prints the run's time and the time from its result to the
// first picture.
// Usage: node web/build.mjs && node web/measure.mjs [n ...]   (default: 37 55, i.e. 304k and 998k tets)
//        node web/measure.mjs --example box.off --max-size 0.03
// SPDX-License-Identifier: GPL-3.0-or-later
import { readFileSync, readdirSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

import { serve } from '../scripts/serve.mjs';
import { CHROMIUM, CHROMIUM_ARGS } from '../tests/browser/lib/browser.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const argv = process.argv.slice(2);
const flag = (name) => { const i = argv.indexOf(name); return i >= 0 ? argv.splice(i, 2)[1] : undefined; };
const example = flag('--example'), maxSize = flag('--max-size');
const sizes = argv.map(Number).filter((n) => n > 0);
if (!sizes.length && !example) sizes.push(37, 55);

/** Resident memory (MB) of the process whose command line holds `mark` and of all its descendants. */
function rssMb(mark) {
  const procs = [];
  for (const pid of readdirSync('/proc').filter((p) => /^\d+$/.test(p))) {
    try {
      const stat = readFileSync(`/proc/${pid}/stat`, 'utf8');
      const ppid = Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]);
      const rss = Number((readFileSync(`/proc/${pid}/status`, 'utf8').match(/VmRSS:\s+(\d+)/) || [0, 0])[1]);
      procs.push({ pid: Number(pid), ppid, rss, top: readFileSync(`/proc/${pid}/cmdline`, 'utf8').includes(mark) });
    } catch { /* gone */ }
  }
  const inTree = new Set(procs.filter((p) => p.top).map((p) => p.pid));
  for (let grew = true; grew;) {
    grew = false;
    for (const p of procs) if (!inTree.has(p.pid) && inTree.has(p.ppid)) { inTree.add(p.pid); grew = true; }
  }
  return procs.filter((p) => inTree.has(p.pid)).reduce((a, p) => a + p.rss, 0) / 1024;
}

const { chromium } = await import('playwright-core');
const server = await serve({ root: join(root, 'build/web') });
const mark = `--wqmesh-measure-${process.pid}`;  // an unknown switch Chromium ignores, to find its processes
const browser = await chromium.launch({ executablePath: CHROMIUM, args: [...CHROMIUM_ARGS, mark] });
try {
  if (example) {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    const base = rssMb(mark);
    await page.goto(`${server.url}?example=${encodeURIComponent(example)}${maxSize ? `&maxSize=${maxSize}` : ''}`);
    await page.waitForFunction(() => ['done', 'error'].includes(document.body.dataset.state), null, { timeout: 900_000 });
    const r = await page.evaluate(() => ({ ...window.__wqmeshPage.resultTiming, tets: window.__wqmeshPage.stats.tets,
      time: window.__wqmeshPage.stats.time_s }));
    console.log(`measure: ${example} size bound ${maxSize ?? 0}: ${r.tets} tets, run ${(r.runMs / 1000).toFixed(1)} s ` +
      `(mesher ${r.time.toFixed(1)} s), result to first picture ${r.firstPictureMs.toFixed(0)} ms (face table ${r.tableMs.toFixed(0)} ms); ` +
      `Chromium RSS ${base.toFixed(0)} MB before, ${rssMb(mark).toFixed(0)} MB after`);
    await page.close();
  }
  for (const n of sizes) {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    await page.addInitScript(() => {
      window.__longTasks = [];
      new PerformanceObserver((l) => { for (const e of l.getEntries()) window.__longTasks.push({ start: e.startTime, duration: e.duration }); })
        .observe({ type: 'longtask', buffered: true });
    });
    await page.goto(server.url);
    await page.waitForFunction(() => window.__wqmeshPage && document.querySelectorAll('#example option').length > 1);
    const base = rssMb(mark);
    // The main thread's responsiveness: the longest gap between the ticks
    // of a 5 ms interval timer while the mesh is loaded and clipped.
    const t0 = await page.evaluate(() => {
      window.__gap = 0;
      let last = performance.now();
      window.__tick = setInterval(() => { const now = performance.now(); window.__gap = Math.max(window.__gap, now - last); last = now; }, 5);
      return performance.now();
    });
    const first = await page.evaluate((k) => window.__wqmeshPage.loadSynthetic(k), n);
    const afterFirst = rssMb(mark);
    const updates = [];
    for (const cut of [0.2, 0.35, 0.5, 0.65, 0.8, 0.45, 0.55]) {
      const ms = await page.evaluate(async (c) => {
        const seq = Number(document.body.dataset.viewSeq || 0);
        const el = document.getElementById('v-cut');
        el.value = String(c);
        el.dispatchEvent(new Event('input', { bubbles: true }));
        while (Number(document.body.dataset.viewSeq) <= seq) await new Promise((r) => setTimeout(r, 5));
        return window.__wqmeshPage.lastView;
      }, cut);
      updates.push(ms);
    }
    // The page's start-up (module loading, the shader warm-up) is not counted.
    const long = await page.evaluate((t) => Math.max(0, ...window.__longTasks.filter((e) => e.start >= t).map((e) => e.duration)), t0);
    const gap = await page.evaluate(() => { clearInterval(window.__tick); return window.__gap; });
    if (process.env.WQMESH_MEASURE_DEBUG) console.log(t0, JSON.stringify(await page.evaluate(() => window.__longTasks)));
    const total = updates.map((u) => u.ms).sort((a, b) => a - b);
    const worker = updates.map((u) => u.workerMs).sort((a, b) => a - b);
    const main = updates.map((u) => u.mainMs).sort((a, b) => a - b);
    const med = (a) => a[Math.floor(a.length / 2)].toFixed(0);
    console.log(`measure: ${first.tets} tets: first picture ${first.firstPictureMs.toFixed(0)} ms ` +
      `(face table ${first.tableMs.toFixed(0)} ms); clip update median ${med(total)} ms, worst ${total.at(-1).toFixed(0)} ms ` +
      `(worker ${med(worker)} ms, main thread + frame ${med(main)} ms), ${updates[2].faces} faces / ${updates[2].drawnTets} tets drawn at the middle; ` +
      `main thread: longest timer gap ${gap.toFixed(0)} ms, longest task ${long.toFixed(0)} ms; Chromium RSS ${base.toFixed(0)} MB before, ${afterFirst.toFixed(0)} MB with the mesh`);
    await page.close();
  }
} finally {
  await browser.close();
  await server.close();
}
