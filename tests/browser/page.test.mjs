// wqmesh: browser tests of the web page (issue 12), with playwright-core
// driving Debian's headless Chromium against the built page (build/web, made
// by `node web/build.mjs`) served by scripts/serve.mjs on 127.0.0.1. Covers:
// file input, a dropped file and the example picker (numbers equal the
// package's result for the same model and options), the overlays (one
// sphere per protecting ball), every broken model of ../shared/models (its error
// code and message, then a good model meshes), Cancel (cancelled within a
// second, the next run succeeds), a rho0 change during a run restarts it,
// the URL state round trip, the clipping plane (whole tets: the drawn faces
// are exactly the faces of kept tets whose neighbour is not kept, computed
// here from the package's mesh; the user's bound colours exactly the tets
// below it; hidden rest keeps only highlighted tets; shrink draws whole
// tets), picking by click and from the worst-tets list (the camera moves),
// keyboard use (Tab, arrows, Enter; visible focus), downloads, no long task on the main thread
// during a run, no console error or warning, no request off 127.0.0.1, no
// horizontal overflow at phone width, a strict CSP header; saves screenshots under
// build/screenshots/. Skips when Chromium or the built page is missing
// (unless CI is set); the broken-model test skips without ../shared/models
// (unless CI is set).
// Run: node web/build.mjs && node --test tests/browser/
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { existsSync, mkdirSync, readFileSync, readdirSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { after, before, test } from 'node:test';
import { fileURLToPath } from 'node:url';

import { serve } from '../../scripts/serve.mjs';
import { browserSkipReason, CHROMIUM, CHROMIUM_ARGS } from './lib/browser.mjs';
import { formatStat, statValue, STAT_GROUPS } from '../../web/stats.mjs';
import { CLASS_COLOURS, linearBytes, neighbours, TET_FACES } from '../../web/tetfaces.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const webRoot = join(root, 'build/web');
const shared = join(root, '../shared/models');
const shots = join(root, 'build/screenshots');
const BROKEN = ['cubes.off', 'cube-ouvert.off', 'self_intersecting.off', 'issue1580-zero-area-triangle.stl',
  'bad-stl-pcbvicebar.stl'];

const missing = browserSkipReason() ||
  (!existsSync(join(webRoot, 'index.html')) ? 'build/web is missing (node web/build.mjs)' : '');
if (missing && process.env.CI) throw new Error(`browser tests: ${missing}`);
const skip = missing || false;

// Numbers that depend on the machine, not on the mesh.
const TIMING = new Set(['time_s', 'tets_per_second', 'peak_memory_mb']);
const STAT_KEYS = STAT_GROUPS.flatMap(([, rows]) => rows.map(([k]) => k)).filter((k) => !TIMING.has(k));

// Chromium without a GPU composites a WebGL canvas by reading it back and
// says so on the console for every page with WebGL, the page's own or an
// empty one (checked with a page that only clears a canvas): that one line
// is the browser's, not the page's, and is the only message let through.
// The longest main-thread task allowed while the mesher runs in its worker (see the cancel test).
const LONG_TASK_MS = 250;
const BROWSER_NOISE = /GL Driver Message \(OpenGL, Performance, GL_CLOSE_PATH_NV, High\): GPU stall due to ReadPixels/;

let browser, server, pkg;
const consoleProblems = [];
const offHostRequests = [];

async function launch() {
  const { chromium } = await import('playwright-core');
  return chromium.launch({ executablePath: CHROMIUM, args: CHROMIUM_ARGS });
}

before(async () => {
  if (skip) return;
  browser = await launch();
  server = await serve({ root: webRoot });
  pkg = await import('../../wasm/index.mjs');
  await pkg.ready();
  mkdirSync(shots, { recursive: true });
});
after(async () => {
  await browser?.close();
  await server?.close();
});

/** A new page at `width` x `height` that records console problems and requests. */
async function open(query = '', { width = 1280, height = 800, longTasks = false } = {}, base = server.url) {
  const context = await browser.newContext({ viewport: { width, height }, acceptDownloads: true });
  if (longTasks) {
    // Every task over 50 ms on the main thread, from the first script on, and every wasm instance made on the
    // main thread (the mesher runs in the package's worker: the page itself instantiates none).
    await context.addInitScript(() => {
      window.__longTasks = [];
      new PerformanceObserver((l) => {
        for (const e of l.getEntries()) window.__longTasks.push({ start: e.startTime, duration: e.duration });
      }).observe({ type: 'longtask', buffered: true });
      window.__mainThreadInstances = 0;
      for (const name of ['instantiate', 'instantiateStreaming']) {
        const original = WebAssembly[name];
        WebAssembly[name] = function (...args) {
          ++window.__mainThreadInstances;
          return original.apply(this, args);
        };
      }
      WebAssembly.Instance = new Proxy(WebAssembly.Instance, {
        construct(target, args) {
          ++window.__mainThreadInstances;
          return Reflect.construct(target, args);
        },
      });
    });
  }
  const page = await context.newPage();
  page.on('console', (m) => {
    if ((m.type() === 'error' || m.type() === 'warning') && !BROWSER_NOISE.test(m.text())) {
      consoleProblems.push(`${m.type()}: ${m.text()}`);
    }
  });
  page.on('pageerror', (e) => consoleProblems.push(`pageerror: ${e.message}`));
  page.on('worker', (w) => w.on('console', (m) => {
    if ((m.type() === 'error' || m.type() === 'warning') && !BROWSER_NOISE.test(m.text())) {
      consoleProblems.push(`worker ${w.url()}: ${m.type()}: ${m.text()}`);
    }
  }));
  page.on('request', (r) => {
    const u = r.url();
    if (!u.startsWith('http://127.0.0.1:') && !u.startsWith('blob:http://127.0.0.1:') && !u.startsWith('data:')) {
      offHostRequests.push(u);
    }
  });
  await page.goto(`${base}${query}`);
  return page;
}

const state = (page) => page.evaluate(() => document.body.dataset.state);
async function waitState(page, wanted, timeout = 90_000) {
  await page.waitForFunction((w) => w.includes(document.body.dataset.state), [].concat(wanted), { timeout });
  return state(page);
}

/** The page's shown numbers, by data-stat key. */
const shownStats = (page) => page.evaluate(() =>
  Object.fromEntries([...document.querySelectorAll('[data-stat]')].map((e) => [e.dataset.stat, e.textContent])));

/** The package's result for a model and the page's run options. */
function packageResult(bytes, options) {
  return pkg.meshSync(bytes, options);
}

function assertSameNumbers(shown, stats, what) {
  for (const k of STAT_KEYS) {
    assert.equal(shown[k], formatStat(k, statValue(stats, k)), `${what}: data-stat ${k}`);
  }
}

const DEFAULTS = { rho: 2.2, sliverAngle: 3, pump: true, improve: true, maxSize: 0, maxVertices: 1000000 };
const model = (name) => readFileSync(join(root, 'examples/models', name));

test('file input: spike.off meshes and shows the package\'s numbers', { skip }, async () => {
  const page = await open();
  assert.equal(await state(page), 'idle');
  assert.match(await page.textContent('#empty'), /drop a polyhedron here/i);
  await page.setInputFiles('input[type=file]', join(root, 'examples/models/spike.off'));
  assert.equal(await waitState(page, ['done', 'error']), 'done');
  const shown = await shownStats(page);
  const spike = packageResult(model('spike.off'), DEFAULTS);
  assertSameNumbers(shown, spike.stats, 'spike.off');
  // Overlays: one sphere per protecting ball, one point per pumped vertex.
  await page.check('#v-balls');
  await page.check('#v-pumped');
  const overlay = await page.evaluate(() => window.__wqmeshPage.viewer.groups.overlay.children.map((o) =>
    (o.isInstancedMesh ? `balls ${o.count}` : `points ${o.geometry.getAttribute('position').count}`)));
  const pumped = spike.weights.filter((w) => w > 0).length;
  assert.ok(spike.stats.protecting_balls.length > 0, 'spike.off has protecting balls');
  assert.deepEqual(overlay, [`balls ${spike.stats.protecting_balls.length}`, ...(pumped ? [`points ${pumped}`] : [])]);
  // The analysis before meshing: the report's numbers, and the marks drawn
  // are exactly the report's sharp elements, at its coordinates.
  const report = pkg.checkSync(model('spike.off'));
  assert.equal(await page.textContent('[data-check=sharp_edges]'), String(report.analysis.counts.sharp_edges));
  const drawn = await page.evaluate(() => {
    const s = window.__wqmeshPage.surface;
    return { counts: s.counts, origin: s.origin, lines: Array.from(s.sharpLines), points: Array.from(s.sharpPoints) };
  });
  assert.ok(report.analysis.counts.sharp_vertices > 0, 'spike.off has sharp vertices');
  assert.equal(drawn.counts.sharpVertices, report.analysis.counts.sharp_vertices);
  assert.equal(drawn.counts.sharpEdges, report.analysis.counts.sharp_edges);
  assert.equal(drawn.counts.edges, report.plc.edges);
  const near = (a, b, what) => assert.ok(Math.abs(a - b) <= 1e-5 * (1 + Math.abs(b)), `${what}: ${a} vs ${b}`);
  report.plc.sharp_vertex_points.forEach((p, i) => p.forEach((x, k) => near(drawn.points[3 * i + k] + drawn.origin[k], x, `sharp vertex ${i}`)));
  report.plc.sharp_edge_points.forEach((e, i) => e.flat().forEach((x, k) => near(drawn.lines[6 * i + k] + drawn.origin[k % 3], x, `sharp edge ${i}`)));
  // A file dropped anywhere on the page loads too.
  await page.evaluate((text) => {
    const dt = new DataTransfer();
    dt.items.add(new File([text], 'dropped_box.off'));
    document.querySelector('h1').dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, readFileSync(join(root, 'examples/models/box.off'), 'utf8'));
  await page.waitForFunction(() => document.body.dataset.input === 'dropped_box.off');
  assert.equal(await waitState(page, ['done', 'error']), 'done');
  assert.equal(await page.textContent('[data-stat=tets]'), String(packageResult(model('box.off'), DEFAULTS).stats.tets));
  await page.context().close();
});

test('example picker, URL round trip, previous run side by side', { skip }, async () => {
  const page = await open();
  await page.waitForFunction(() => document.querySelectorAll('#example option').length > 1);
  const names = await page.$$eval('#example option', (o) => o.map((x) => x.value).filter(Boolean));
  const files = readdirSync(join(root, 'examples/models')).filter((f) => /\.(off|stl)$/i.test(f)).sort();
  assert.deepEqual(names, files);
  await page.selectOption('#example', 'thin_wedge.off');
  assert.equal(await waitState(page, ['done', 'error']), 'done');
  // A parameter change runs again (automatic runs are on by default); the
  // previous run stays beside it.
  const seq = await page.evaluate(() => window.__wqmeshPage.runSeq);
  await page.fill('#p-sliverAngle', '5');
  await page.dispatchEvent('#p-sliverAngle', 'change');
  await page.waitForFunction((s) => window.__wqmeshPage.runSeq > s && document.body.dataset.state !== 'running', seq,
                             { timeout: 90_000 });
  assert.equal(await state(page), 'done');
  const options = { ...DEFAULTS, sliverAngle: 5 };
  const stats = packageResult(model('thin_wedge.off'), options).stats;
  const shown = await shownStats(page);
  assertSameNumbers(shown, stats, 'thin_wedge.off theta 5');
  const prevTets = await page.textContent('[data-prev-stat=tets]');
  assert.equal(prevTets, String(packageResult(model('thin_wedge.off'), DEFAULTS).stats.tets));
  const url = page.url();
  assert.match(url, /example=thin_wedge\.off/);
  assert.match(url, /sliverAngle=5/);
  // The URL in a new page: same parameters, same numbers.
  const again = await open(url.slice(server.url.length));
  assert.equal(await waitState(again, ['done', 'error']), 'done');
  assert.equal(await again.inputValue('#p-sliverAngle'), '5');
  assert.equal(await again.inputValue('#example'), 'thin_wedge.off');
  const shown2 = await shownStats(again);
  for (const k of STAT_KEYS) assert.equal(shown2[k], shown[k], `round trip: ${k}`);
  await again.context().close();
  await page.context().close();
});

test('keyboard: pick an example and mesh without the mouse; focus is visible', { skip }, async () => {
  const page = await open();
  await page.waitForFunction(() => document.querySelectorAll('#example option').length > 1);
  await page.uncheck('#auto');
  // Tab until the example picker has the focus, then choose with the arrows.
  let steps = 0;
  while (await page.evaluate(() => document.activeElement.id) !== 'example' && steps++ < 20) await page.keyboard.press('Tab');
  assert.equal(await page.evaluate(() => document.activeElement.id), 'example');
  const outline = await page.evaluate(() => getComputedStyle(document.activeElement).outlineStyle);
  assert.notEqual(outline, 'none', 'the focused control shows an outline');
  const names = await page.$$eval('#example option', (o) => o.map((x) => x.value));
  await page.keyboard.press('ArrowDown');
  await page.waitForFunction((n) => document.body.dataset.input === n, names[1]);
  assert.equal(await state(page), 'idle', 'automatic runs are off');
  // Tab to the Mesh button and press Enter.
  steps = 0;
  while (await page.evaluate(() => document.activeElement.dataset.action) !== 'mesh' && steps++ < 30) await page.keyboard.press('Tab');
  assert.equal(await page.evaluate(() => document.activeElement.dataset.action), 'mesh');
  await page.keyboard.press('Enter');
  assert.equal(await waitState(page, ['done', 'error']), 'done');
  assert.equal(await page.textContent('[data-stat=tets]'), String(packageResult(model(names[1]), DEFAULTS).stats.tets));
  await page.context().close();
});

test('a run stopped by the vertex limit before meshing: done, stopped "limit", its message, no tets drawn', { skip }, async () => {
  const page = await open('?example=spike.off&maxVertices=10');
  assert.equal(await waitState(page, ['done', 'error']), 'done');
  const stats = packageResult(model('spike.off'), { ...DEFAULTS, maxVertices: 10 }).stats;
  assert.equal(stats.stopped, 'limit');
  assertSameNumbers(await shownStats(page), stats, 'spike.off maxVertices 10');
  assert.ok((await page.textContent('#status')).includes(stats.stop_message), 'the stop message is shown');
  assert.match(await page.textContent('#histogram'), /no tets/);
  await page.context().close();
});

// Without ../shared/models the test skips, except under CI, where it fails.
const noShared = !existsSync(shared) && !process.env.CI && '../shared/models is absent';
test('broken models: error code and message, highlight, then a good model meshes', { skip: skip || noShared }, async () => {
  assert.ok(existsSync(shared), `${shared} is missing (under CI the shared models must be there)`);
  const page = await open();
  for (const name of BROKEN) {
    const bytes = readFileSync(join(shared, name));
    const report = pkg.checkSync(bytes);
    assert.equal(report.valid, false, `${name} is broken`);
    await page.setInputFiles('input[type=file]', join(shared, name));
    await page.waitForFunction((n) => document.body.dataset.input === n, name);
    assert.equal(await state(page), 'error', name);
    const code = await page.getAttribute('[data-error-code]', 'data-error-code');
    assert.equal(code, report.error.kind, `${name}: data-error-code`);
    const text = await page.textContent('[data-error-code]');
    assert.ok(text.toLowerCase().includes(report.error.message.toLowerCase().slice(1, 40)),
              `${name}: the message "${report.error.message}" is shown (got "${text}")`);
    // Where the message names a face, an edge or a point, the view highlights it.
    const bad = await page.evaluate(() => {
      const b = window.__wqmeshPage.surface.bad;
      return { faces: b.positions.length / 9, edge: b.edge.length / 6, points: b.points.length / 3 };
    });
    if (/\bface \d+/.test(report.error.message)) assert.ok(bad.faces > 0, `${name}: face highlighted`);
    if (/edge from vertex/.test(report.error.message)) assert.equal(bad.edge, 1, `${name}: edge highlighted`);
    assert.equal(await page.isDisabled('[data-action=mesh]'), true, `${name}: nothing to mesh`);
  }
  await page.selectOption('#example', 'box.off');
  await page.waitForFunction(() => document.body.dataset.input === 'box.off');
  assert.equal(await waitState(page, ['done', 'error']), 'done');
  assert.equal(await page.locator('[data-error-code]').count(), 0);
  assert.equal(await page.textContent('[data-stat=tets]'), String(packageResult(model('box.off'), DEFAULTS).stats.tets));
  await page.context().close();
});

test('cancel within a second, a second run succeeds; a rho0 change during a run restarts it; no long task', { skip }, async () => {
  // box.off with a size bound of 0.02: about a million tets, far longer than the test waits.
  const page = await open('?example=box.off&maxSize=0.02', { longTasks: true });
  await waitState(page, 'running');
  const runStart = await page.evaluate(() => window.__wqmeshPage.run.startedAt);
  await page.waitForFunction(() => /vertices/.test(document.getElementById('progress-text').textContent));
  await page.waitForTimeout(1500);
  const progress = await page.textContent('#progress-text');
  assert.match(progress, /^(initialize|conform|refine|pump|extract): \d+ vertices/, progress);
  // rho0 changes during the run: the run in progress is cancelled and a new one starts with rho0 = 3.
  const before = await page.evaluate(() => window.__wqmeshPage.runSeq);
  await page.fill('#p-rho', '3');
  await page.dispatchEvent('#p-rho', 'change');
  assert.equal(await state(page), 'running');
  const after = await page.evaluate(() => ({ seq: window.__wqmeshPage.runSeq, running: Boolean(window.__wqmeshPage.run) }));
  assert.equal(after.seq, before + 1, 'a new run started');
  assert.ok(after.running);
  await page.waitForURL(/rho=3/);
  await page.waitForTimeout(1000);
  assert.equal(await state(page), 'running');
  const t0 = Date.now();
  await page.click('[data-action=cancel]');
  await waitState(page, 'cancelled', 1000);
  assert.ok(Date.now() - t0 < 1000, `cancelled after ${Date.now() - t0} ms`);
  // The mesher never ran on the main thread (a main-thread meshSync of box.off before the worker's run fails
  // here), and the main thread stayed responsive during the runs. A main-thread mesh of this run would be one
  // task of at least the 2,500 ms waited above (meshSync cannot yield and the run has no end before the cancel);
  // LONG_TASK_MS leaves room for a loaded machine (a 138 ms task once at a load of 13-15).
  assert.equal(await page.evaluate(() => window.__mainThreadInstances), 0, 'a wasm instance on the main thread');
  const long = await page.evaluate((t) => window.__longTasks.filter((e) => e.start >= t).map((e) => e.duration), runStart);
  assert.ok(long.every((d) => d <= LONG_TASK_MS), `long tasks on the main thread during the run: ${long.join(', ')} ms`);
  // The next run works: a small model after the cancelled one.
  await page.fill('#p-maxSize', '0');
  await page.dispatchEvent('#p-maxSize', 'change');
  await page.fill('#p-rho', '2.2');
  await page.dispatchEvent('#p-rho', 'change');
  await page.click('[data-action=mesh]');
  assert.equal(await waitState(page, ['done', 'error']), 'done');
  assert.equal(await page.textContent('[data-stat=tets]'), String(packageResult(model('box.off'), DEFAULTS).stats.tets));
  await page.context().close();
});

/** The faces a whole-tet clip must draw, computed here from the mesh: { kept, faces: Set('t,i') }. */
function expectedCut(result, normal, offset) {
  const { vertices: V, tets: T } = result;
  const nt = T.length / 4;
  const kept = new Uint8Array(nt);
  let keptCount = 0;
  for (let t = 0; t < nt; ++t) {
    let s = 0;
    for (let k = 0; k < 4; ++k) for (let c = 0; c < 3; ++c) s += V[3 * T[4 * t + k] + c] * normal[c];
    if (s / 4 <= offset) { kept[t] = 1; ++keptCount; }
  }
  const nb = neighbours(T);
  const faces = new Set();
  for (let t = 0; t < nt; ++t) {
    if (!kept[t]) continue;
    for (let i = 0; i < 4; ++i) if (nb[4 * t + i] < 0 || !kept[nb[4 * t + i]]) faces.add(`${t},${i}`);
  }
  return { keptCount, faces };
}

/** What the page draws: per drawn face, its tet and its three corners (model coordinates). */
const drawnFaces = (page) => page.evaluate(() => {
  const p = window.__wqmeshPage;
  const g = p.viewer.meshObject.geometry;
  const pos = g.getAttribute('position').array, idx = g.index.array;
  const o = p.meshInfo.origin;
  const out = [];
  for (let f = 0; f < idx.length / 3; ++f) {
    out.push({ tet: p.viewer.faceTet[f],
      corners: [0, 1, 2].map((j) => [0, 1, 2].map((k) => pos[3 * idx[3 * f + j] + k] + o[k])) });
  }
  return { faces: out, vertexCount: pos.length / 3, drawn: p.lastView.drawnTets, kept: p.lastView.keptTets };
});

function checkWholeTets(view, result, expected, what) {
  const { vertices: V, tets: T } = result;
  assert.equal(view.kept, expected.keptCount, `${what}: kept tets`);
  assert.equal(view.faces.length, expected.faces.size, `${what}: drawn faces`);
  const tetsDrawn = new Set();
  for (const f of view.faces) {
    tetsDrawn.add(f.tet);
    // The face is a whole face of its tet (no fragment): find which one.
    const i = TET_FACES.findIndex((F) => F.every((c, j) => {
      const v = T[4 * f.tet + c];
      return [0, 1, 2].every((k) => Math.abs(V[3 * v + k] - f.corners[j][k]) <= 1e-5 * (1 + Math.abs(V[3 * v + k])));
    }));
    assert.ok(i >= 0, `${what}: face of tet ${f.tet} is one of its faces`);
    assert.ok(expected.faces.has(`${f.tet},${i}`), `${what}: face ${i} of tet ${f.tet} should not be drawn`);
  }
  assert.equal(view.drawn, tetsDrawn.size, `${what}: drawn tets`);
  assert.equal(view.vertexCount, 4 * tetsDrawn.size, `${what}: four corners per drawn tet`);
}

test('clipping plane keeps whole tets; downloads; screenshots at both widths', { skip }, async () => {
  const query = '?example=bracket.off&maxSize=0.3&cut=0.6&bound=25';  // plane x = 3.6, through the hole
  const page = await open(query);
  assert.equal(await waitState(page, ['done', 'error']), 'done');
  const options = { ...DEFAULTS, maxSize: 0.3 };
  const result = packageResult(model('bracket.off'), options);
  assertSameNumbers(await shownStats(page), result.stats, 'bracket.off');
  const box = await page.evaluate(() => window.__wqmeshPage.meshInfo.box);
  const at = (cut) => box.lo[0] + cut * (box.hi[0] - box.lo[0]);
  const first = await drawnFaces(page);
  checkWholeTets(first, result, expectedCut(result, [1, 0, 0], at(0.6)), 'cut 0.6');
  // Move the plane: a new picture, different tets, still whole ones.
  const seq = await page.evaluate(() => Number(document.body.dataset.viewSeq));
  await page.$eval('#v-cut', (e) => { e.value = '0.3'; e.dispatchEvent(new Event('input', { bubbles: true })); });
  await page.waitForFunction((s) => Number(document.body.dataset.viewSeq) > s && window.__wqmeshPage.lastView, seq);
  await page.waitForFunction(() => !document.querySelector('#drawn').textContent.includes('…'));
  await page.waitForTimeout(200);
  const second = await drawnFaces(page);
  assert.ok(second.kept < first.kept, 'fewer tets kept with the plane moved towards lo');
  checkWholeTets(second, result, expectedCut(result, [1, 0, 0], at(0.3)), 'cut 0.3');
  await page.waitForURL(/cut=0\.3/);
  // The user's bound: every drawn tet below it (and good otherwise) has the
  // "below" colour, and no other; hidden rest: only highlighted tets are kept.
  const colours = await page.evaluate(() => {
    const p = window.__wqmeshPage, g = p.viewer.meshObject.geometry;
    const col = g.getAttribute('color').array, idx = g.index.array;
    const out = {};
    for (let f = 0; f < idx.length / 3; ++f) out[p.viewer.faceTet[f]] = Array.from(col.slice(3 * idx[3 * f], 3 * idx[3 * f] + 3)).join(',');
    return out;
  });
  const below = linearBytes(CLASS_COLOURS.below).join(',');
  for (const [t, c] of Object.entries(colours)) {
    const isBelow = result.tetClass[t] === 0 && result.minDihedral[t] < 25;
    assert.equal(c === below, isBelow, `tet ${t} (${result.minDihedral[t].toFixed(2)} deg, class ${result.tetClass[t]}): colour ${c}`);
  }
  const seqHide = await page.evaluate(() => Number(document.body.dataset.viewSeq));
  await page.selectOption('#v-rest', 'hide');
  await page.waitForFunction((s) => Number(document.body.dataset.viewSeq) > s, seqHide);
  let highlighted = 0;
  for (let t = 0; t < result.tets.length / 4; ++t) {
    let x = 0;
    for (let k = 0; k < 4; ++k) x += result.vertices[3 * result.tets[4 * t + k]] / 4;
    if (x <= at(0.3) && (result.tetClass[t] !== 0 || result.minDihedral[t] < 25)) ++highlighted;
  }
  assert.equal(await page.evaluate(() => window.__wqmeshPage.lastView.keptTets), highlighted, 'hidden rest: kept = highlighted');
  await page.selectOption('#v-rest', 'show');
  // Shrink below 1: all four faces of every drawn tet.
  const seqShrink = await page.evaluate(() => Number(document.body.dataset.viewSeq));
  await page.$eval('#v-shrink', (e) => { e.value = '0.7'; e.dispatchEvent(new Event('input', { bubbles: true })); });
  await page.waitForFunction((s) => Number(document.body.dataset.viewSeq) > s + 0 &&
    window.__wqmeshPage.lastView.faces === 4 * window.__wqmeshPage.lastView.drawnTets, seqShrink);
  await page.$eval('#v-shrink', (e) => { e.value = '1'; e.dispatchEvent(new Event('input', { bubbles: true })); });
  // Picking: a click on the part shows a tet's numbers; the worst tet from
  // the list moves the camera to it.
  const box2 = await page.locator('#view canvas').boundingBox();
  await page.mouse.click(box2.x + box2.width * 0.35, box2.y + box2.height * 0.5);
  await page.waitForSelector('#pick dl');
  const picked = Number((await page.textContent('#pick dd')).trim());
  assert.ok(Number.isInteger(picked) && picked >= 0 && picked < result.tets.length / 4, `picked tet ${picked}`);
  const target0 = await page.evaluate(() => window.__wqmeshPage.viewer.controls.target.toArray());
  await page.click('#worst button');
  await page.waitForFunction((t) => window.__wqmeshPage.viewer.controls.target.toArray().join() !== t.join(), target0);
  const worstTet = Number((await page.textContent('#worst button')).match(/tet (\d+)/)[1]);
  await page.waitForFunction((t) => document.querySelector('#pick dd')?.textContent === String(t), worstTet);
  assert.match(await page.textContent('#pick'), /smallest dihedral/);
  let minD = Infinity;
  for (const d of result.minDihedral) minD = Math.min(minD, d);
  assert.equal(result.minDihedral[worstTet], minD, 'the first of the worst tets is the worst');
  // Downloads.
  for (const [kind, pattern] of [['medit', /^MeshVersionFormatted/], ['vtu', /<VTKFile/], ['stats', /"tets"/]]) {
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click(`[data-download=${kind}]`)]);
    const text = readFileSync(await dl.path(), 'utf8');
    assert.match(text, pattern, kind);
  }
  // TetGen: four files, .node with the mesh's vertex count, .ele with its tet count.
  const tetgen = [];
  page.on('download', (d) => tetgen.push(d));
  await page.click('[data-download=tetgen]');
  for (let i = 0; i < 50 && tetgen.length < 4; ++i) await page.waitForTimeout(100);
  const files = Object.fromEntries(await Promise.all(tetgen.map(async (d) => [d.suggestedFilename().split('.').pop(), readFileSync(await d.path(), 'utf8')])));
  assert.deepEqual(Object.keys(files).sort(), ['edge', 'ele', 'face', 'node']);
  assert.equal(Number(files.node.trim().split(/\s+/)[0]), result.vertices.length / 3);
  assert.equal(Number(files.ele.trim().split(/\s+/)[0]), result.tets.length / 4);
  page.removeAllListeners('download');  // (the listener above only)
  const [png] = await Promise.all([page.waitForEvent('download'), page.click('[data-download=png]')]);
  assert.equal(readFileSync(await png.path()).subarray(1, 4).toString(), 'PNG');
  // Screenshots: clip on, tets below 20 degrees highlighted, both widths.
  await page.$eval('#v-cut', (e) => { e.value = '0.6'; e.dispatchEvent(new Event('input', { bubbles: true })); });
  await page.click('#v-reset');
  await page.$eval('#controls', (e) => { e.scrollTop = 0; });
  await page.waitForTimeout(500);
  await page.screenshot({ path: join(shots, 'bracket-1280x800.png') });
  await page.context().close();
  const phone = await open(query, { width: 390, height: 844 });
  assert.equal(await waitState(phone, ['done', 'error']), 'done');
  await phone.waitForTimeout(300);
  const overflow = await phone.evaluate(() => ({ scroll: document.documentElement.scrollWidth, client: document.documentElement.clientWidth }));
  assert.ok(overflow.scroll <= overflow.client, `phone width: ${overflow.scroll} > ${overflow.client}`);
  await phone.screenshot({ path: join(shots, 'bracket-390x844.png') });
  await phone.screenshot({ path: join(shots, 'bracket-390x844-full.png'), fullPage: true });
  await phone.context().close();
  // The tets near small angles of thin_wedge.off (skinny and slivers near its
  // 10-degree edges), every other tet hidden.
  const wedge = await open('?example=thin_wedge.off&clip=0&rest=hide');
  assert.equal(await waitState(wedge, ['done', 'error']), 'done');
  await wedge.waitForTimeout(300);
  await wedge.screenshot({ path: join(shots, 'thin_wedge-near-1280x800.png') });
  await wedge.context().close();
});

test('under a strict Content-Security-Policy header (script-src \'self\' \'wasm-unsafe-eval\') the page meshes', { skip }, async () => {
  const strict = await serve({ root: webRoot, csp: "script-src 'self' 'wasm-unsafe-eval'" });
  try {
    const page = await open('', {}, strict.url);
    await page.selectOption('#example', 'spike.off');
    assert.equal(await waitState(page, ['done', 'error']), 'done');
    assert.equal(await page.textContent('[data-stat=tets]'), String(packageResult(model('spike.off'), DEFAULTS).stats.tets));
    await page.context().close();
  } finally {
    await strict.close();
  }
});

test('console free of errors and warnings; no request off 127.0.0.1', { skip }, () => {
  assert.deepEqual(consoleProblems, []);
  assert.deepEqual(offHostRequests, []);
});
