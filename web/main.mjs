// wqmesh page: the controller. Input (drop, file picker, examples), the check
// report and the preview, the parameters and their URL state, the run in the
// package's worker (progress, cancel, restart on change), the view (through
// the view worker and viewer.mjs), the numbers and the downloads.
// Test hooks (issue 12): data-action="mesh"/"cancel", body[data-state]
// (idle, running, done, error, cancelled), data-stat="KEY" on every number
// from the stats, data-error-code on the error of a rejected input.
// SPDX-License-Identifier: GPL-3.0-or-later
import { Viewer } from './viewer.mjs';
import * as engine from './engine.mjs';
import { RUN_PARAMS, VIEW_PARAMS, coerce, defaultState, meshOptions, queryFromState, stateFromQuery } from './params.mjs';
import { ERROR_WORDS } from './surface.mjs';
import { STAT_GROUPS, formatStat, statValue } from './stats.mjs';

const $ = (id) => document.getElementById(id);
const el = (tag, attrs = {}, ...children) => {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k === 'text') e.textContent = v;
    else if (k.startsWith('data-') || k === 'role' || k.startsWith('aria-') || k === 'for' || k === 'title') e.setAttribute(k, v);
    else e[k] = v;
  }
  for (const c of children) e.append(c);
  return e;
};

// ---- view worker RPC ---------------------------------------------------------------------------
const viewWorker = new Worker(new URL('./view-worker.mjs', import.meta.url), { type: 'module' });
let callSeq = 0;
const calls = new Map();
viewWorker.onmessage = (ev) => {
  const { id, value, error } = ev.data;
  const c = calls.get(id);
  calls.delete(id);
  if (!c) return;
  if (error) c.reject(Object.assign(new Error(error.message), { code: error.code }));
  else c.resolve(value);
};
viewWorker.onerror = (ev) => {
  ev.preventDefault();
  status(`The view worker failed (${ev.message || 'out of memory?'}); reload the page.`, true);
  for (const c of calls.values()) c.reject(new Error('the view worker failed'));
  calls.clear();
};
function call(type, data = {}, transfer = []) {
  return new Promise((resolve, reject) => {
    const id = ++callSeq;
    calls.set(id, { resolve, reject });
    viewWorker.postMessage({ type, id, ...data }, transfer);
  });
}

// ---- state -------------------------------------------------------------------------------------
let state = stateFromQuery(location.search);
const page = {
  input: null,        // { name, bytes, example }
  report: null,       // check report of the input
  inputSeq: 0,        // increases with every input load (stale async work is dropped)
  run: null,          // { controller, id }
  runSeq: 0,
  stats: null, prevStats: null, hist: null, prevHist: null,
  meshInfo: null,     // from the view worker: box, origin, worst, pumpedPoints
  lastView: null,     // timings of the last picture
  surface: null,
};
window.__wqmeshPage = page;  // for tests and the measurements of the README

function setState(s) {
  document.body.dataset.state = s;
  $('mesh').disabled = !(page.report && page.report.valid) || s === 'running';
  $('cancel').disabled = s !== 'running';
}

// The URL follows the state; a dragged slider writes it at most every
// 150 ms (browsers throttle, and warn about, very frequent replaceState).
let urlTimer = 0;
function writeUrl() {
  if (urlTimer) return;
  urlTimer = setTimeout(() => {
    urlTimer = 0;
    const q = queryFromState(state);
    if (q !== location.search) history.replaceState(null, '', `${location.pathname}${q}`);
  }, 150);
}

// ---- parameters --------------------------------------------------------------------------------
function buildParams() {
  const box = $('params');
  for (const p of RUN_PARAMS) {
    const id = `p-${p.key}`;
    const input = p.type === 'bool'
      ? el('input', { type: 'checkbox', id })
      : el('input', { type: 'number', id, min: p.min, max: p.max, step: p.step, inputMode: 'decimal' });
    const defText = p.type === 'bool' ? (p.def ? 'on' : 'off') : String(p.def);
    box.append(el('div', { class: 'param' },
      el('label', { for: id, text: p.label }), input,
      el('div', { class: 'help', id: `${id}-help`, text: `${p.help} Default: ${defText}.` })));
    input.setAttribute('aria-describedby', `${id}-help`);
    input.addEventListener('change', () => {
      const v = p.type === 'bool' ? input.checked : coerce(p, input.value);
      if (p.type !== 'bool' && input.value !== '' && Number(input.value) !== v) {
        status(`${p.label}: ${input.value} is out of range [${p.min}, ${p.max}]; using ${v}.`, true);
      }
      state[p.key] = v;
      showParams();
      writeUrl();
      parametersChanged();
    });
  }
}

function showParams() {
  for (const p of RUN_PARAMS) {
    const input = $(`p-${p.key}`);
    if (p.type === 'bool') input.checked = state[p.key];
    else input.value = String(state[p.key]);
  }
  $('v-clip').checked = state.clip;
  $('v-axis').value = state.axis;
  $('v-cut').value = String(state.cut);
  $('v-flip').checked = state.flip;
  $('v-shrink').value = String(state.shrink);
  $('v-bound').value = String(state.bound);
  $('v-rest').value = state.rest;
  $('v-balls').checked = state.balls;
  $('v-pumped').checked = state.pumped;
  $('example').value = state.example;
}

let autoTimer = 0;
function parametersChanged() {
  // A change during a run cancels it first, then runs again (libfive #67).
  if (page.run) { startRun(); return; }
  if ($('auto').checked && page.report?.valid) {
    clearTimeout(autoTimer);
    autoTimer = setTimeout(startRun, 250);
  }
}

function status(text, bad = false) {
  const s = $('status');
  s.textContent = text;
  s.classList.toggle('bad', bad);
}

// ---- input -------------------------------------------------------------------------------------
async function loadExamples() {
  try {
    const list = await (await fetch('./models/index.json')).json();
    for (const name of list) $('example').append(el('option', { value: name, text: name }));
  } catch {
    status('The list of examples could not be read.', true);
  }
  $('example').value = state.example;
}

async function loadExample(name) {
  const resp = await fetch(`./models/${encodeURIComponent(name)}`);
  if (!resp.ok) { showError({ code: 'io', message: `the example ${name} is not on the server` }); return; }
  await loadInput(name, new Uint8Array(await resp.arrayBuffer()), true);
}

async function loadFile(file) {
  if (!file) return;
  if (file.size > 1 << 30) {
    await loadInput(file.name, new Uint8Array(0), false, { code: 'too_large', message: `${file.name} has ${file.size} bytes, beyond the limit of 1 GiB` });
    return;
  }
  await loadInput(file.name, new Uint8Array(await file.arrayBuffer()), false);
}

function clearResults() {
  page.meshInfo = null;
  viewer.showPlane(null);
  viewer.clear('mesh');
  viewer.clear('overlay');
  viewer.clear('marker');
  $('legend').hidden = true;
  $('pick').replaceChildren(el('p', { class: 'hint', text: 'Click a tet in the view, or one in the list of worst tets.' }));
  $('worst').replaceChildren(el('li', { class: 'hint', text: 'Mesh a model to list its tets with the smallest dihedral angles.' }));
  document.querySelectorAll('[data-download]').forEach((b) => { b.disabled = b.dataset.download !== 'png' || !page.surface; });
  $('drawn').textContent = '';
  delete document.body.dataset.drawnTets;
}

async function loadInput(name, bytes, example, preError = null) {
  cancelRun(false);
  clearTimeout(autoTimer);
  const seq = ++page.inputSeq;
  state.example = example ? name : '';
  showParams();
  writeUrl();
  page.input = { name, bytes, example };
  delete document.body.dataset.input;
  page.report = null;
  page.surface = null;
  clearResults();
  hideError();
  $('empty').hidden = true;
  $('input-name').textContent = `${name} (${bytes.length} bytes)`;
  $('analysis').replaceChildren(el('li', { class: 'hint', text: 'checking…' }));
  setState('idle');
  let report;
  try {
    report = preError ? { valid: false, error: { kind: preError.code, message: preError.message } } : await engine.check(bytes);
  } catch (e) {
    report = { valid: false, error: { kind: e.code || 'internal', message: e.message } };
  }
  if (seq !== page.inputSeq) return;
  page.report = report;
  const sharp = report.valid ? { vertices: report.plc.sharp_vertex_points, edges: report.plc.sharp_edge_points } : null;
  const surface = await call('surface', { bytes: bytes.slice(), error: report.valid ? null : report.error.message, sharp });
  if (seq !== page.inputSeq) return;
  page.surface = surface;
  viewer.frame(surface.size);
  viewer.showSurface(surface);
  viewer.setSurfaceVisible(true);
  $('legend-input').hidden = false;
  $('viewnote').textContent = `input: ${surface.points} points, ${surface.faces} faces`;
  showAnalysis(report, surface);
  // The preview's first frame is drawn before a run starts, so that it is
  // not a long task of the main thread during the run.
  await viewer.nextFrame();
  if (seq !== page.inputSeq) return;
  if (!report.valid) {
    showError({ code: report.error.kind, message: report.error.message }, surface);
    setState('error');
    document.body.dataset.input = name;  // the report of this input is shown
    return;
  }
  setState('idle');
  document.body.dataset.input = name;
  status('Ready to mesh.');
  if ($('auto').checked) startRun();
}

function showAnalysis(r, surface) {
  const ul = $('analysis');
  ul.replaceChildren();
  if (!r.valid) return;
  const a = r.analysis;
  const li = (text, key, value) => {
    const l = el('li', {}, text);
    if (key) { const s = el('span', { 'data-check': key, text: String(value) }); l.append(s); }
    ul.append(l);
  };
  li(`${r.format}: `, 'facets', r.plc.facets);
  ul.lastChild.append(` facets, ${r.plc.edges} edges, ${r.plc.vertices} vertices${r.plc.holes ? `, ${r.plc.holes} holes in facets` : ''}`);
  li('smallest input angle (deg): ', 'phi_m_degrees', a.phi_m_degrees.toFixed(2));
  li('sharp edges: ', 'sharp_edges', a.counts.sharp_edges);
  ul.lastChild.append(`, sharp vertices: ${a.counts.sharp_vertices}`);
  li(`acute angles: ${a.counts.acute_edge_edge_angles} edge-edge, ${a.counts.acute_edge_facet_angles} edge-facet`);
  for (const w of r.warnings) li(`repaired: ${w}`);
  if (surface?.marksSkipped) li(`(${surface.triangles} triangles: the input edges are not drawn in the view)`);
}

function showError(err, surface) {
  const box = $('error');
  box.hidden = false;
  box.dataset.errorCode = err.code;
  const where = surface && surface.bad && (surface.bad.positions.length || surface.bad.edge.length || surface.bad.points.length)
    ? ' The place is highlighted in the view.' : '';
  box.replaceChildren(
    el('strong', { text: ERROR_WORDS[err.code] || 'The input was rejected.' }),
    el('span', { class: 'msg', text: `${err.message[0].toUpperCase()}${err.message.slice(1)}.${where}` }),
    el('div', {}, el('code', { text: err.code })));
  $('analysis').replaceChildren();
  status('Fix the file, or open another one.', true);
}
function hideError() {
  const box = $('error');
  box.hidden = true;
  delete box.dataset.errorCode;
  box.replaceChildren();
}

// ---- running -----------------------------------------------------------------------------------
function cancelRun(show = true) {
  if (!page.run) return;
  page.run.controller.abort();
  page.run = null;
  $('progress-box').hidden = true;
  if (show) {
    setState('cancelled');
    status('Cancelled. The next run starts from scratch.');
  }
}

let progressFrame = 0, progressLast = null;
function showProgress(p) {
  progressLast = p;
  if (progressFrame) return;
  progressFrame = requestAnimationFrame(() => {
    progressFrame = 0;
    const q = progressLast;
    if (!page.run || !q) return;
    $('progress').value = Math.max(0, Math.min(1, q.fraction ?? 0));
    const steps = q.steps !== undefined ? `, ${q.steps} steps` : '';
    $('progress-text').textContent = `${q.phase ?? ''}: ${q.vertices ?? 0} vertices${steps}, ${Math.round(100 * (q.fraction ?? 0))}%`;
  });
}

async function startRun() {
  clearTimeout(autoTimer);
  if (!page.input || !page.report?.valid) return;
  cancelRun(false);
  const controller = new AbortController();
  const id = ++page.runSeq;
  page.run = { controller, id, options: meshOptions(state), startedAt: performance.now() };
  const options = meshOptions(state);
  setState('running');
  $('progress-box').hidden = false;
  $('progress').value = 0;
  $('progress-text').textContent = 'starting…';
  status(`Meshing ${page.input.name}…`);
  const t0 = performance.now();
  let result;
  try {
    result = await engine.mesh(page.input.bytes, options, { signal: controller.signal, onProgress: showProgress });
  } catch (e) {
    if (page.run?.id !== id) return;  // cancelled or replaced
    page.run = null;
    $('progress-box').hidden = true;
    if (e.name === 'AbortError') { setState('cancelled'); return; }
    const box = $('error');
    box.hidden = false;
    box.dataset.errorCode = e.code || 'internal';
    box.replaceChildren(el('strong', { text: ERROR_WORDS[e.code] || 'The run failed.' }), el('span', { text: e.message }),
                        el('div', {}, el('code', { text: e.code || 'internal' })));
    status('The run failed; change the parameters or the input and mesh again.', true);
    setState('error');
    return;
  }
  if (page.run?.id !== id) return;
  page.run = null;
  $('progress-box').hidden = true;
  await showResult(result, performance.now() - t0, id);
}

async function showResult(result, ms, id) {
  const shown = performance.now();
  page.prevStats = page.stats;
  page.prevHist = page.hist;
  page.stats = result.stats;
  const arrays = {};
  const transfer = [];
  for (const [k, v] of Object.entries(result)) {
    if (ArrayBuffer.isView(v)) { arrays[k] = v; transfer.push(v.buffer); }
  }
  const info = await call('mesh', { result: arrays }, transfer);
  if (id !== page.runSeq) return;
  page.meshInfo = info;
  page.hist = info.histogram;
  showNumbers();
  showHistogram();
  showWorst(info.worst);
  document.querySelectorAll('[data-download]').forEach((b) => { b.disabled = false; });
  const s = result.stats;
  const stop = s.stopped ? ` Stopped (${s.stopped}): ${s.stop_message || ''}` : '';
  status(`Meshed ${page.input.name} (${(ms / 1000).toFixed(1)} s with the transfers).${stop}`, Boolean(s.stopped));
  $('legend-input').hidden = true;
  $('legend').hidden = false;
  viewer.setSurfaceVisible($('v-surface').checked);
  $('viewnote').replaceChildren('mesh: ', el('span', { 'data-stat': 'tets', text: formatStat('tets', s.tets) }), ' tets, ',
    el('span', { 'data-stat': 'vertices', text: formatStat('vertices', s.vertices) }), ' vertices');
  showOverlays();
  await refreshView();
  if (id !== page.runSeq) return;
  page.resultTiming = { runMs: ms, firstPictureMs: performance.now() - shown, tableMs: info.tableMs };
  setState('done');
}

// ---- numbers -----------------------------------------------------------------------------------
function showNumbers() {
  const body = $('numbers').tBodies[0];
  body.replaceChildren();
  for (const [title, rows] of STAT_GROUPS) {
    body.append(el('tr', { class: 'group' }, el('td', { colSpan: 3, text: title })));
    for (const [key, label] of rows) {
      const now = statValue(page.stats, key), prev = statValue(page.prevStats, key);
      body.append(el('tr', {},
        el('td', { text: label }),
        el('td', { 'data-stat': key, text: formatStat(key, now) }),
        el('td', { 'data-prev-stat': key, text: page.prevStats ? formatStat(key, prev) : '–' })));
    }
  }
}

function showHistogram() {
  const box = $('histogram');
  const h = page.hist, p = page.prevHist;
  if (!h.counts.some((c) => c > 0)) {
    box.replaceChildren(el('p', { class: 'hint', text: 'This run made no tets.' }));
    return;
  }
  const n = h.counts.length, W = 360, H = 120, pad = 18, bw = (W - 2) / n;
  const total = (c) => c.reduce((a, b) => a + b, 0) || 1;
  const tn = total(h.counts), tp = p ? total(p.counts) : 1;  // (total() is at least 1: no division by 0)
  let max = 0;
  h.counts.forEach((c) => { max = Math.max(max, c / tn); });
  if (p) p.counts.forEach((c) => { max = Math.max(max, c / tp); });
  max = max || 1;
  const ns = 'http://www.w3.org/2000/svg';
  const svg = document.createElementNS(ns, 'svg');
  svg.setAttribute('viewBox', `0 0 ${W} ${H + pad}`);
  svg.setAttribute('role', 'img');
  svg.setAttribute('aria-label', 'Histogram of the smallest dihedral angle per tet, this run (blue) and the previous (grey), as a share of the tets');
  const rect = (x, y, w, hh, cls, title) => {
    const r = document.createElementNS(ns, 'rect');
    Object.entries({ x, y, width: w, height: hh, class: cls }).forEach(([k, v]) => r.setAttribute(k, v));
    const t = document.createElementNS(ns, 'title');
    t.textContent = title;
    r.append(t);
    svg.append(r);
  };
  for (let i = 0; i < n; ++i) {
    const lab = i === n - 1 ? `${i * h.width}+` : `${i * h.width}-${(i + 1) * h.width}`;
    const fn = h.counts[i] / tn, hn = max ? (fn * H) : 0;
    if (p) {
      const fp = p.counts[i] / tp, hp = max ? (fp * H) : 0;
      rect(1 + i * bw, H - hp / max, bw / 2 - 1, hp / max, 'prev', `previous run, ${lab} deg: ${p.counts[i]} tets`);
    }
    rect(1 + i * bw + (p ? bw / 2 : 0), H - hn / max, (p ? bw / 2 : bw) - 1, hn / max, 'now', `this run, ${lab} deg: ${h.counts[i]} tets`);
    if (i % 2 === 0) {
      const t = document.createElementNS(ns, 'text');
      t.setAttribute('x', 1 + i * bw);
      t.setAttribute('y', H + 12);
      t.textContent = String(i * h.width);
      svg.append(t);
    }
  }
  box.replaceChildren(svg, el('p', { class: 'hint',
    text: `degrees; bars are shares of the tets${p ? ', blue: this run, grey: the previous run' : ''}.` }));
}

function showWorst(list) {
  const ol = $('worst');
  ol.replaceChildren();
  const names = ['good', 'skinny', 'sliver', 'violation'];
  for (const w of list) {
    const deg = w.minDihedral < 1 ? w.minDihedral.toPrecision(2) : w.minDihedral.toFixed(2);
    const b = el('button', { type: 'button', text: `tet ${w.tet}: ${deg} deg, ${names[w.cls] || w.cls}` });
    b.addEventListener('click', () => pickTet(w.tet, true));
    ol.append(el('li', {}, b));
  }
}

async function pickTet(tet, move) {
  if (tet < 0) return;
  const info = await call('tet', { tet, stats: page.stats });
  if (!info) return;
  viewer.mark(info);
  if (move) viewer.lookAt(info.centroid, info.size);
  const dl = el('dl');
  const row = (k, v) => dl.append(el('dt', { text: k }), el('dd', { text: v }));
  row('tet', String(info.tet));
  row('vertices', info.vertices.join(', '));
  info.points.forEach((p, i) => row(`v${i}`, p.map((x) => x.toPrecision(6)).join(', ')));
  row('smallest dihedral', `${info.minDihedral < 1 ? info.minDihedral.toPrecision(3) : info.minDihedral.toFixed(3)} deg`);
  row('R/l', info.radiusEdge.toFixed(3));
  if (info.orthoradiusEdge !== undefined) row('orthoradius / l (weighted)', info.orthoradiusEdge.toFixed(3));
  row('class', info.className);
  if (info.near) row('why near', info.near);
  $('pick').replaceChildren(dl);
}

// ---- view --------------------------------------------------------------------------------------
function viewParams() {
  const info = page.meshInfo;
  const k = { x: 0, y: 1, z: 2 }[state.axis];
  const lo = info.box.lo[k], hi = info.box.hi[k];
  const at = lo + state.cut * (hi - lo);
  const normal = [0, 0, 0];
  normal[k] = state.flip ? -1 : 1;
  return {
    clip: state.clip, normal, offset: state.flip ? -at : at, bound: state.bound, rest: state.rest,
    shrunk: state.shrink < 1, selected: -1, edges: true,
  };
}

let viewBusy = false, viewAgain = false;
async function refreshView() {
  if (!page.meshInfo) return;
  if (viewBusy) { viewAgain = true; return; }
  viewBusy = true;
  try {
    do {
      viewAgain = false;
      const t0 = performance.now();
      const x = await call('extract', { view: viewParams() });
      if (!x || !page.meshInfo) break;
      const t1 = performance.now();
      viewer.showTets(x);
      showPlane();
      viewer.setShrink(state.shrink);
      await viewer.nextFrame();
      const t2 = performance.now();
      page.lastView = { ms: t2 - t0, workerMs: x.ms, mainMs: t2 - t1, drawnTets: x.drawnTets, keptTets: x.keptTets,
                        faces: x.index.length / 3 };
      document.body.dataset.drawnTets = String(x.drawnTets);
      document.body.dataset.keptTets = String(x.keptTets);
      document.body.dataset.viewSeq = String(Number(document.body.dataset.viewSeq || 0) + 1);
      $('drawn').textContent = `${x.keptTets} tets kept, ${x.drawnTets} drawn (${x.index.length / 3} faces); ` +
                               `picture in ${page.lastView.ms.toFixed(0)} ms`;
    } while (viewAgain);
  } finally {
    viewBusy = false;
  }
}

function showPlane() {
  const info = page.meshInfo;
  if (!info || !state.clip) { viewer.showPlane(null); return; }
  const k = { x: 0, y: 1, z: 2 }[state.axis];
  const lo = info.box.lo.map((x, i) => x - info.origin[i]), hi = info.box.hi.map((x, i) => x - info.origin[i]);
  viewer.showPlane({ axis: k, at: lo[k] + state.cut * (hi[k] - lo[k]), lo, hi });
}

function showOverlays() {
  viewer.showOverlays({
    balls: state.balls && page.stats ? page.stats.protecting_balls : null,
    pumped: state.pumped && page.meshInfo ? page.meshInfo.pumpedPoints : null,
  }, page.meshInfo ? page.meshInfo.origin : [0, 0, 0]);
}

function bindView() {
  const onView = (key, read, rebuild = true) => (ev) => {
    state[key] = coerce(VIEW_PARAMS.find((p) => p.key === key), read(ev.target));
    writeUrl();
    if (rebuild) refreshView();
  };
  $('v-clip').addEventListener('change', onView('clip', (t) => t.checked));
  $('v-axis').addEventListener('change', onView('axis', (t) => t.value));
  $('v-cut').addEventListener('input', onView('cut', (t) => t.value));
  $('v-flip').addEventListener('change', onView('flip', (t) => t.checked));
  $('v-shrink').addEventListener('input', (ev) => {
    const was = state.shrink < 1;
    onView('shrink', (t) => t.value, false)(ev);
    viewer.setShrink(state.shrink);
    if (was !== state.shrink < 1) refreshView();
  });
  $('v-bound').addEventListener('change', onView('bound', (t) => t.value));
  $('v-rest').addEventListener('change', onView('rest', (t) => t.value));
  $('v-balls').addEventListener('change', (ev) => { onView('balls', (t) => t.checked, false)(ev); showOverlays(); });
  $('v-pumped').addEventListener('change', (ev) => { onView('pumped', (t) => t.checked, false)(ev); showOverlays(); });
  $('v-reset').addEventListener('click', () => {
    const b = page.meshInfo?.box;
    viewer.frame(b ? Math.max(...b.hi.map((x, k) => x - b.lo[k])) : page.surface?.size);
  });
  $('v-surface').addEventListener('change', (ev) => {
    viewer.setSurfaceVisible(ev.target.checked || !page.meshInfo);
    viewer.groups.mesh.visible = !ev.target.checked;
    viewer.render();
  });
  // A click (not a drag) picks a tet.
  let down = null;
  viewer.canvas.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
  viewer.canvas.addEventListener('pointerup', (e) => {
    if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4) return;
    const t = viewer.pick(e.clientX, e.clientY);
    if (t >= 0) pickTet(t, false);
  });
}

// ---- downloads ---------------------------------------------------------------------------------
function save(blob, name) {
  const a = el('a', { href: URL.createObjectURL(blob), download: name });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}

async function download(kind) {
  const base = (page.input?.name || 'mesh').replace(/\.(off|stl)$/i, '');
  try {
    if (kind === 'png') { save(await viewer.screenshot(), `${base}.png`); return; }
    if (kind === 'stats') { save(new Blob([JSON.stringify(page.stats, null, 2)], { type: 'application/json' }), `${base}.stats.json`); return; }
    const text = await call('write', { format: kind, stats: page.stats });
    if (kind === 'medit') save(new Blob([text], { type: 'text/plain' }), `${base}.mesh`);
    else if (kind === 'vtu') save(new Blob([text], { type: 'application/xml' }), `${base}.vtu`);
    else for (const [ext, t] of Object.entries(text)) save(new Blob([t], { type: 'text/plain' }), `${base}.${ext}`);
  } catch (e) {
    status(`Download failed: ${e.message}`, true);
  }
}

// ---- wiring ------------------------------------------------------------------------------------
const viewer = new Viewer($('view'));
page.viewer = viewer;
buildParams();
showParams();
bindView();
$('mesh').addEventListener('click', () => startRun());
$('cancel').addEventListener('click', () => cancelRun(true));
$('reset').addEventListener('click', () => {
  const ex = state.example;
  state = { ...defaultState(), example: ex };
  showParams();
  writeUrl();
  parametersChanged();
  refreshView();
});
$('file').addEventListener('change', (ev) => {
  loadFile(ev.target.files[0]);
  ev.target.value = '';  // the same file again is a change too
});
$('example').addEventListener('change', (ev) => { if (ev.target.value) loadExample(ev.target.value); });
document.querySelectorAll('[data-download]').forEach((b) => b.addEventListener('click', () => download(b.dataset.download)));
let dragDepth = 0;
window.addEventListener('dragenter', (e) => { e.preventDefault(); ++dragDepth; $('dropveil').hidden = false; });
window.addEventListener('dragleave', () => { if (--dragDepth <= 0) { dragDepth = 0; $('dropveil').hidden = true; } });
window.addEventListener('dragover', (e) => e.preventDefault());
window.addEventListener('drop', (e) => {
  e.preventDefault();
  dragDepth = 0;
  $('dropveil').hidden = true;
  const f = e.dataTransfer?.files?.[0];
  if (f) loadFile(f);
});
window.addEventListener('keydown', (e) => {
  if (e.key === 'Escape' && page.run) cancelRun(true);
});

/** Measurement hook (README "Web page"): views a structured test mesh of 6 n^3 tets. */
page.loadSynthetic = async (n) => {
  cancelRun(false);
  ++page.inputSeq;
  const id = ++page.runSeq;
  clearResults();
  $('empty').hidden = true;
  viewer.setSurfaceVisible(false);
  const t0 = performance.now();
  const info = await call('mesh', { synthetic: n });
  if (id !== page.runSeq) return null;
  page.meshInfo = info;
  page.stats = null;
  viewer.frame(Math.max(...info.box.hi.map((x, k) => x - info.box.lo[k])));
  $('legend').hidden = false;
  await refreshView();
  return { firstPictureMs: performance.now() - t0, tableMs: info.tableMs, tets: info.tets };
};

engine.version().then((v) => { $('version').textContent = v ? `wqmesh ${v}` : ''; });
await loadExamples();
setState('idle');
if (state.example) loadExample(state.example);
