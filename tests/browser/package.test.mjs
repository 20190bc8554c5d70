// wqmesh: the package in a browser (Debian's Chromium through playwright-core,
// tests/browser/lib/browser.mjs), served by scripts/serve.mjs with the strict
// policy `Content-Security-Policy: script-src 'self' 'wasm-unsafe-eval'` on
// every answer (no 'unsafe-eval', no inline script). The server's folder
// holds the packed tarball (`npm pack --ignore-scripts`: the files already
// built beside wasm/index.mjs), unpacked into node_modules/wqmesh/ of a
// temporary folder: its wasm/wqmesh.wasm is the one binary (the glue
// wqmesh.mjs inlines none), and a page imports
// /node_modules/wqmesh/wasm/index.mjs with no bundler, meshes a model in a module worker (the
// mesh must conform, be positively oriented and keep the input volume),
// aborts a second, long run (AbortError, within 100 ms of the abort) and
// meshes again; wqmesh.wasm is fetched once for all of it (one compiled
// module). No CSP violation, no page error, no failed request. Then the
// page loaded again with wqmesh.wasm answered 404: mesh() rejects with a
// WqmeshError `internal` naming the file (no hang).
// Skipped when Chromium or playwright-core is missing (an error under CI).
// Run: node --test tests/browser/
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';

import { serve } from '../../scripts/serve.mjs';
import { tetVolumes } from '../node/lib/tets.mjs';
import { browserSkipReason, launchBrowser } from './lib/browser.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const CSP = "script-src 'self' 'wasm-unsafe-eval'";
const skip = browserSkipReason() || false;

// The page and its module script exist only for this test (routed, never on
// disk); the package files come from the server.
const PAGE = '<!doctype html><meta charset="utf-8"><title>wqmesh smoke</title>' +
             '<script type="module" src="/__smoke/smoke.mjs"></script>';
const SCRIPT = `
import * as wqmesh from '/node_modules/wqmesh/wasm/index.mjs';
window.violations = [];
document.addEventListener('securitypolicyviolation', (e) => window.violations.push(e.violatedDirective + ' ' + e.blockedURI));
window.wqmesh = wqmesh;
window.smokeReady = true;
`;


test('the package meshes in a module worker and aborts under a strict CSP', { skip, timeout: 240000 }, async () => {
  const site = mkdtempSync(join(tmpdir(), 'wqmesh-site-'));
  const pkg = join(site, 'node_modules/wqmesh');
  mkdirSync(pkg, { recursive: true });
  const pack = spawnSync('npm', ['pack', '--json', '--ignore-scripts', '--pack-destination', site], { cwd: root, encoding: 'utf8' });
  assert.equal(pack.status, 0, pack.stderr);
  const packed = JSON.parse(pack.stdout.slice(pack.stdout.search(/^\[$/m)))[0];
  const untar = spawnSync('tar', ['-xzf', join(site, packed.filename), '-C', pkg, '--strip-components=1'], { encoding: 'utf8' });
  assert.equal(untar.status, 0, untar.stderr);
  const size = (f) => packed.files.find((e) => e.path === f)?.size ?? 0;
  assert.ok(size('wasm/wqmesh.wasm') > 500000, 'the tarball holds wasm/wqmesh.wasm');
  assert.equal(statSync(join(pkg, 'wasm/wqmesh.wasm')).size, size('wasm/wqmesh.wasm'));
  assert.ok(size('wasm/wqmesh.mjs') > 0 && size('wasm/wqmesh.mjs') < size('wasm/wqmesh.wasm') / 4,
            `the glue (${size('wasm/wqmesh.mjs')} bytes) holds no copy of the binary`);
  const server = await serve({ root: site, csp: CSP });
  const browser = await launchBrowser();
  try {
    const { page } = browser;
    await page.route(`${server.url}__smoke/**`, (route) => {
      const url = route.request().url();
      const html = url.endsWith('.html');
      route.fulfill({ status: 200, body: html ? PAGE : SCRIPT,
                      headers: { 'Content-Type': html ? 'text/html' : 'text/javascript', 'Content-Security-Policy': CSP } });
    });
    await page.goto(`${server.url}__smoke/index.html`);
    await page.waitForFunction(() => window.smokeReady === true);

    const spike = readFileSync(join(root, 'examples/models/spike.off'), 'utf8');
    const first = await page.evaluate(async (text) => {
      const fractions = [];
      const r = await window.wqmesh.mesh(text, { rho: 2.2 }, { onProgress: (p) => fractions.push(p.fraction) });
      const typed = ['vertices', 'tets', 'weights', 'tetClass', 'minDihedral'].every((k) => ArrayBuffer.isView(r[k]));
      return { stats: r.stats, vertices: Array.from(r.vertices), tets: Array.from(r.tets), fractions, typed,
               mainThreadHasModule: typeof window.createWqmeshModule !== 'undefined' };
    }, spike);
    assert.ok(first.typed, 'result arrays are typed arrays');
    assert.equal(first.stats.conforming, true);
    assert.equal(first.stats.stopped, '');
    assert.equal(first.tets.length, 4 * first.stats.tets);
    const v = tetVolumes(first.vertices, first.tets);
    assert.ok(v.smallest > 0, 'every tet is positively oriented');
    assert.ok(Math.abs(v.total - first.stats.volume_input) <= 1e-9 * first.stats.volume_input,
              `volume ${v.total} vs ${first.stats.volume_input}`);
    assert.ok(first.fractions.length > 0, 'progress reported');
    for (let i = 1; i < first.fractions.length; ++i) assert.ok(first.fractions[i] >= first.fractions[i - 1], 'progress never goes down');

    // A long run (a box refined to a small size bound), aborted once it refines.
    const box = readFileSync(join(root, 'examples/models/box.off'), 'utf8');
    const aborted = await page.evaluate(async (text) => {
      const controller = new AbortController();
      let abortedAt = 0;
      let phase = '';
      try {
        await window.wqmesh.mesh(text, { maxSize: 0.02, maxVertices: 2000000 }, {
          signal: controller.signal,
          onProgress: (p) => {
            if (!abortedAt && p.phase === 'refine' && p.vertices > 2000) {
              phase = p.phase;
              abortedAt = performance.now();
              controller.abort();
            }
          },
        });
        return { name: 'resolved' };
      } catch (e) {
        return { name: e.name, isDomException: e instanceof DOMException, ms: performance.now() - abortedAt, phase };
      }
    }, box);
    assert.equal(aborted.name, 'AbortError', JSON.stringify(aborted));
    assert.ok(aborted.isDomException);
    assert.equal(aborted.phase, 'refine');
    assert.ok(aborted.ms < 100, `rejected ${aborted.ms} ms after the abort`);

    const again = await page.evaluate(async (text) => (await window.wqmesh.mesh(text)).stats, box);
    assert.equal(again.conforming, true, 'a run after an abort succeeds');

    const violations = await page.evaluate(() => window.violations);
    assert.deepEqual(violations, [], 'no Content-Security-Policy violation');
    assert.deepEqual(browser.pageErrors, []);
    assert.deepEqual(browser.failedRequests, []);
    const csp = browser.consoleMessages.filter((m) => /Content Security Policy|unsafe-eval/i.test(m.text));
    assert.deepEqual(csp, [], 'no CSP message on the console');
    const urls = browser.requests.map((r) => new URL(r.url).pathname);
    assert.ok(urls.includes('/node_modules/wqmesh/wasm/worker.mjs'), `the worker was loaded: ${urls.join(' ')}`);
    assert.ok(urls.includes('/node_modules/wqmesh/wasm/wqmesh.mjs'), 'the module was loaded');
    // index.mjs compiles the binary once, from wqmesh.wasm (compileStreaming),
    // for the page and every worker: fetched once, though three runs in two
    // workers (the abort terminates the first).
    assert.equal(urls.filter((u) => u === '/node_modules/wqmesh/wasm/wqmesh.wasm').length, 1, 'wqmesh.wasm fetched once');
    assert.ok(!first.mainThreadHasModule);

    // The same page without its binary (404): a clear error, not a hang.
    await page.route(`${server.url}node_modules/wqmesh/wasm/wqmesh.wasm`, (route) => route.fulfill({ status: 404, body: '' }));
    await page.goto(`${server.url}__smoke/index.html`);
    await page.waitForFunction(() => window.smokeReady === true);
    const missing = await page.evaluate(async (text) => {
      try {
        await window.wqmesh.mesh(text);
        return { name: 'resolved' };
      } catch (e) {
        return { name: e.name, code: e.code, message: e.message };
      }
    }, spike);
    assert.equal(missing.name, 'WqmeshError', JSON.stringify(missing));
    assert.equal(missing.code, 'internal');
    assert.match(missing.message, /wqmesh\.wasm .*HTTP 404/);
  } finally {
    await browser.close();
    await server.close();
    rmSync(site, { recursive: true, force: true });
  }
});
