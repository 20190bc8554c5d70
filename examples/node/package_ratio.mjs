// wqmesh: the wasm/native time ratio per closed model, through the npm package
// as users run it: mesh() in a worker_threads worker in Node, and mesh() in a
// module worker of Chromium (a page served by scripts/serve.mjs, through
// playwright-core), each over the native command line's time. Runs are
// paired (native, Node, browser, native, ...), so that a machine whose speed
// drifts moves both sides; the ratio printed is the median of the pairs'
// ratios. The times are the runs' own `stats.time_s` (the mesher, without
// process start-up or module instantiation). A measurement, not a test.
// Usage: node examples/node/package_ratio.mjs [--runs N] [--no-browser] [--all] [MODEL ...]
//   default models: the closed models of ../shared/models that take seconds,
//   not minutes (--all adds anchor, fandisk and part), and examples/models.
// SPDX-License-Identifier: GPL-3.0-or-later
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

import { mesh } from '../../wasm/index.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const cli = join(root, 'build/native/bin/wqmesh');
const shared = join(root, '../shared/models');
const BROKEN = new Set(['cubes.off', 'cube-ouvert.off', 'self_intersecting.off', 'issue1580-zero-area-triangle.stl',
                        'bad-stl-pcbvicebar.stl']);
// mpi.off takes minutes and step.off is refused before meshing; these three take tens of seconds natively.
const SLOW = new Set(['anchor.off', 'fandisk.off', 'part.off']);
const SKIP = new Set(['mpi.off', 'step.off']);

const args = process.argv.slice(2);
let runs = 3;
let browser = true;
let all = false;
const named = [];
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--runs') runs = Number(args[++i]);
  else if (args[i] === '--no-browser') browser = false;
  else if (args[i] === '--all') all = true;
  else named.push(resolve(args[i]));
}
if (!existsSync(cli)) {
  console.error(`package_ratio: ${cli} is missing: run bash scripts/build.sh native`);
  process.exit(1);
}
const list = (dir) => existsSync(dir) ? readdirSync(dir).filter((f) => /\.(off|stl)$/i.test(f)).sort().map((f) => join(dir, f)) : [];
const models = named.length ? named : [
  ...list(shared).filter((p) => !BROKEN.has(basename(p)) && !SKIP.has(basename(p)) && (all || !SLOW.has(basename(p)))),
  ...list(join(root, 'examples/models')),
];

const work = mkdtempSync(join(tmpdir(), 'wqmesh-ratio-'));
function nativeTime(model) {
  const stats = join(work, 'stats.json');
  const r = spawnSync(cli, ['mesh', model, '-o', join(work, 'out.mesh'), '--stats', stats, '--quiet'], { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`native ${model}: exit ${r.status}: ${r.stderr}`);
  return JSON.parse(readFileSync(stats, 'utf8'));
}

let page = null;
let closeBrowser = async () => {};
if (browser) {
  const { browserSkipReason, launchBrowser } = await import('../../tests/browser/lib/browser.mjs');
  const reason = browserSkipReason();
  if (reason) {
    console.error(`package_ratio: no browser column: ${reason}`);
    browser = false;
  } else {
    const { serve } = await import('../../scripts/serve.mjs');
    const server = await serve({ root });
    const b = await launchBrowser({ timeout: 600000 });
    page = b.page;
    await page.route(`${server.url}__ratio/**`, (route) => route.fulfill({
      status: 200, contentType: route.request().url().endsWith('.html') ? 'text/html' : 'text/javascript',
      body: route.request().url().endsWith('.html') ? '<!doctype html><script type="module" src="/__ratio/r.mjs"></script>'
        : "import * as w from '/wasm/index.mjs'; window.wqmesh = w;",
    }));
    await page.goto(`${server.url}__ratio/index.html`);
    await page.waitForFunction(() => window.wqmesh !== undefined);
    closeBrowser = async () => { await b.close(); await server.close(); };
  }
}

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
console.log(`runs ${runs}, paired; time_s of the runs; ratio = median of the pairs' wasm/native`);
console.log(`${'model'.padEnd(22)} ${'tets'.padStart(7)} ${'native s'.padStart(9)} ${'node s'.padStart(8)} ${'node/nat'.padStart(8)}` +
            (browser ? ` ${'browser s'.padStart(9)} ${'brow/nat'.padStart(8)}` : ''));
for (const model of models) {
  const n = [];
  const w = [];
  const c = [];
  let tets = 0;
  for (let k = 0; k < runs; ++k) {
    const ns = nativeTime(model);
    n.push(ns.time_s);
    tets = ns.tets;
    const bytes = readFileSync(model);
    w.push((await mesh(bytes)).stats.time_s);
    if (browser) c.push(await page.evaluate(async (b64) => {
      const bin = Uint8Array.from(atob(b64), (ch) => ch.charCodeAt(0));
      return (await window.wqmesh.mesh(bin)).stats.time_s;
    }, bytes.toString('base64')));
  }
  const ratio = (xs) => median(xs.map((x, k) => x / n[k]));
  console.log(`${basename(model).padEnd(22)} ${String(tets).padStart(7)} ${median(n).toFixed(3).padStart(9)} ` +
              `${median(w).toFixed(3).padStart(8)} ${ratio(w).toFixed(2).padStart(8)}` +
              (browser ? ` ${median(c).toFixed(3).padStart(9)} ${ratio(c).toFixed(2).padStart(8)}` : ''));
}
await closeBrowser();
rmSync(work, { recursive: true, force: true });
