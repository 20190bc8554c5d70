// wqmesh: the package's async API (wasm/index.mjs: check, mesh and the writers
// in a worker_threads worker) and its Node command line (wasm/cli.mjs):
// - the option table: the exported table is the module's; the native command
//   line and the module accept and refuse the same values (min, max, beyond);
// - the mesher's invariants through the package on several models
//   (conforming, positively oriented, the input volume), and the same counts
//   as the native build within 5% (the tolerance of mesh.test.mjs);
// - every broken model of ../shared/models rejected with the native kind as
//   its `code`; empty, garbage, a 0-byte file, a path string, null, a
//   misspelt option: each a clear error;
// - a caller run as `node --input-type=module -e ...` (flags a worker
//   refuses) gets the same valid mesh as this process;
// - wqmesh.mjs holds no copy of its binary (the package ships wqmesh.wasm
//   once); instances on one compiled module give the same mesh; a missing,
//   corrupt or foreign .wasm beside a module is a WqmeshError `internal`
//   naming it (loadWqmesh, and mesh() through a worker), never a crash at
//   import, and a load after the file is back succeeds;
// - abort in the middle of a run, in each phase (PUMP included): an AbortError within
//   100 ms of the abort, and the next call succeeds; progress never goes
//   down and the phases come in order;
// - 100 calls in a row in one process: the module's live C++ bytes and its
//   heap do not grow after the first call (the process RSS is reported);
// - the writers: the same VTU arrays on every run, TetGen files with .edge
//   that TetGen itself reads without a missing connection (when installed);
// - the Node command line: the native exit codes and stats keys, Ctrl-C.
// ../shared/models is optional (its tests skip), except under CI.
// Run: node --test tests/node/package-api.test.mjs
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { readFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { after, test } from 'node:test';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { WqmeshError, check, defaultOptions, loadWqmesh, mesh, meshSync, options, ready, writeMedit, writeTetgen,
         writeVtu } from '../../wasm/index.mjs';
import { compileWasm, instantiateModule } from '../../wasm/core.mjs';
import { tetVolumes } from './lib/tets.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const cli = join(root, 'build/native/bin/wqmesh');
const nodeCli = join(root, 'wasm/cli.mjs');
const shared = join(root, '../shared/models');
if (!existsSync(shared) && process.env.CI) throw new Error(`${shared} is missing (CI is set)`);
const skipShared = !existsSync(shared) && '../shared/models is absent';
const skipNative = !existsSync(cli) && 'the native build is missing';
const work = mkdtempSync(join(tmpdir(), 'wqmesh-package-api-'));
after(() => rmSync(work, { recursive: true, force: true }));

const example = (name) => readFileSync(join(root, 'examples/models', name));
const PHASES = ['initialize', 'conform', 'refine', 'pump', 'extract', 'improve'];

function signedVolume(v, t, name) {
  const { total, firstBad } = tetVolumes(v, t);
  assert.equal(firstBad, -1, `${name}: tet ${firstBad} is not positively oriented`);
  return total;
}

function native(args) {
  return spawnSync(cli, args, { encoding: 'utf8' });
}

// ---- The option table --------------------------------------------------------

test('the exported option table is the module\'s and gives the defaults', async () => {
  const w = await loadWqmesh();
  assert.ok(options.length >= 7);
  for (const o of options) {
    assert.equal(typeof o.doc, 'string');
    assert.equal(defaultOptions[o.name], o.default);
    if (o.type !== 'boolean') assert.ok(o.min <= o.default && o.default <= o.max, `${o.name}: default in range`);
  }
  // The stats echo the options the core ran with: the table's defaults are the core's.
  const s = w.mesh(example('box.off')).stats;
  assert.equal(s.options.rho0, defaultOptions.rho);
  assert.equal(s.options.theta_deg, defaultOptions.sliverAngle);
  assert.equal(s.options.pump, defaultOptions.pump);
  assert.equal(s.options.max_vertices, defaultOptions.maxVertices);
  assert.equal(s.options.max_size, defaultOptions.maxSize);
  assert.equal(s.options.box_margin, defaultOptions.boxMargin);
});

test('polish: true runs the polish (beyond the paper) and keeps the mesh valid; a non-boolean is refused', async () => {
  const slit = example('slit.off');
  const plain = await mesh(slit);
  const polished = await mesh(slit, { polish: true });
  assert.equal(defaultOptions.polish, false);
  assert.equal(plain.stats.options.polish, false);
  assert.equal(plain.stats.improve.polished, 0);
  assert.equal(polished.stats.options.polish, true);
  assert.ok(polished.stats.improve.polished > 0, 'the polish changed something on slit.off');
  // The polish only accepts changes whose new tets beat its floor, and never adds tets.
  assert.ok(polished.stats.min_dihedral_deg >= plain.stats.min_dihedral_deg,
            `${polished.stats.min_dihedral_deg} >= ${plain.stats.min_dihedral_deg}`);
  assert.ok(polished.stats.tets <= plain.stats.tets);
  assert.equal(polished.stats.violations, plain.stats.violations);
  const a = signedVolume(plain.vertices, plain.tets, 'slit');
  const b = signedVolume(polished.vertices, polished.tets, 'slit, polished');
  assert.ok(Math.abs(a - b) <= 1e-9 * Math.abs(a), `the same volume: ${a} ${b}`);
  for (const bad of [1, 'yes'])
    await assert.rejects(mesh(slit, { polish: bad }),
                         (e) => e.code === 'options' && /polish must be true or false/.test(e.message), String(bad));
});

test('the native command line and the module accept and refuse the same option values', { skip: skipNative }, async () => {
  const box = join(root, 'examples/models/box.off');
  const bytes = example('box.off');
  const out = join(work, 'range.mesh');
  for (const o of options.filter((x) => x.flag && x.type !== 'boolean')) {
    const step = o.type === 'integer' ? 1 : Math.max(Math.abs(o.min), 1) * 1e-3;
    const cases = [[o.min, true], [o.max, true], [o.min - step, false], [o.max * 2 + 1, false]];
    if (o.type === 'integer') cases.push([o.min + 0.5, false]);
    for (const [value, ok] of cases) {
      // A vertex limit of 8 stops every run before meshing (exit code 3, a
      // resolved result): what is tested is only whether the value is taken.
      const limit = o.name === 'maxVertices' ? {} : { maxVertices: 8 };
      const args = ['mesh', box, '-o', out, '--quiet', ...(o.name === 'maxVertices' ? [] : ['--max-vertices', '8']),
                    o.flag, String(value)];
      if (o.name === 'maxVertices' && value === o.max) continue;  // would mesh the box fully: covered elsewhere
      const n = native(args);
      let wasm;
      try {
        await mesh(bytes, { ...limit, [o.name]: value });
        wasm = true;
      } catch (e) {
        assert.ok(e instanceof WqmeshError, `${o.name} = ${value}: ${e}`);
        assert.equal(e.code, 'options');
        assert.match(e.message, new RegExp(o.name));
        wasm = false;
      }
      assert.equal(n.status !== 1, ok, `native ${o.flag} ${value}: exit ${n.status} ${n.stderr.split('\n')[0]}`);
      assert.equal(wasm, ok, `wasm ${o.name} = ${value}`);
    }
  }
  // maxSize 0 (no bound) is taken by both (it was refused by the command line).
  assert.equal(native(['mesh', box, '-o', out, '--quiet', '--max-size', '0']).status, 0);
  assert.equal((await mesh(bytes, { maxSize: 0 })).stats.conforming, true);
});

// ---- Invariants through the package vs native --------------------------------

const invariantModels = [
  ...['box.off', 'spike.off', 'thin_wedge.off', 'bracket.off'].map((n) => join(root, 'examples/models', n)),
  ...(skipShared ? [] : ['wedge.off', 'schonhardt.off', 'extrusion.off', 'example012.stl'].map((n) => join(shared, n))),
];
for (const model of invariantModels) {
  const name = model.split('/').pop();
  test(`mesh() through the package: ${name} conforms, keeps its volume and agrees with native`, async () => {
    const fractions = [];
    const phases = [];
    const r = await mesh(await readFile(model), {}, { onProgress: (p) => { fractions.push(p.fraction); phases.push(p.phase); } });
    const s = r.stats;
    assert.equal(s.conforming, true);
    assert.equal(s.stopped, '');
    assert.equal(r.vertices.length, 3 * s.vertices);
    assert.equal(r.weights.length, s.vertices);
    assert.equal(r.tets.length, 4 * s.tets);
    for (const k of ['tetClass', 'minDihedral', 'radiusEdge']) assert.equal(r[k].length, s.tets, k);
    assert.equal(r.boundary.length / 3, r.boundaryFacet.length);
    assert.equal(r.protectingBalls.length, 4 * s.protecting_balls.length);
    assert.equal(r.protectingBallIsVertex.length, s.protecting_balls.length);
    const volume = signedVolume(r.vertices, r.tets, name);
    assert.ok(Math.abs(volume - s.volume_input) <= 1e-9 * s.volume_input, `volume ${volume} vs ${s.volume_input}`);
    assert.equal(Array.from(r.tetClass).filter((c) => c === 3).length, s.violations);
    for (let i = 1; i < fractions.length; ++i) {
      assert.ok(fractions[i] >= fractions[i - 1], `fraction went down: ${fractions[i - 1]} -> ${fractions[i]}`);
      assert.ok(PHASES.indexOf(phases[i]) >= PHASES.indexOf(phases[i - 1]), `phase ${phases[i - 1]} -> ${phases[i]}`);
    }
    assert.ok(fractions.length >= 1 && fractions.every((f) => f >= 0 && f <= 1));
    if (!skipNative) {
      const stats = join(work, `${name}.json`);
      const n = native(['mesh', model, '-o', join(work, `${name}.mesh`), '--stats', stats, '--quiet']);
      assert.equal(n.status, 0, n.stderr);
      const ns = JSON.parse(readFileSync(stats, 'utf8'));
      for (const k of Object.keys(ns)) assert.ok(k in s, `native stats key ${k} in the package's stats`);
      assert.ok(Math.abs(ns.vertices - s.vertices) <= 0.05 * ns.vertices, `vertices ${s.vertices} vs native ${ns.vertices}`);
      assert.ok(Math.abs(ns.tets - s.tets) <= 0.05 * ns.tets, `tets ${s.tets} vs native ${ns.tets}`);
      assert.equal(s.input_points, ns.input_points);
      assert.equal(s.sharp_elements, ns.sharp_elements);
    }
  });
}

// ---- Bad input ----------------------------------------------------------------

const BROKEN = ['cubes.off', 'cube-ouvert.off', 'self_intersecting.off', 'issue1580-zero-area-triangle.stl',
                'bad-stl-pcbvicebar.stl'];
test('every broken shared model is rejected with the native error kind as its code', { skip: skipShared || skipNative }, async () => {
  for (const name of BROKEN) {
    const path = join(shared, name);
    const n = native(['check', path, '--compact']);
    assert.equal(n.status, 2, `${name}: native exit code`);
    const kind = JSON.parse(n.stdout).error.kind;
    await assert.rejects(mesh(await readFile(path)), (e) => {
      assert.ok(e instanceof WqmeshError, `${name}: ${e}`);
      assert.equal(e.code, kind, name);
      assert.ok(e.message.length > kind.length + 20, `${name}: a message naming where: ${e.message}`);
      return true;
    });
    const report = await check(await readFile(path));
    assert.equal(report.valid, false);
    assert.equal(report.error.kind, kind);
  }
});

test('empty, garbage, 0-byte file, path, null and misspelt option: clear errors', async () => {
  await assert.rejects(mesh(new Uint8Array(0)), (e) => e instanceof WqmeshError && e.code === 'empty');
  const garbage = new Uint8Array(300).map((_, i) => (i * 131 + 7) % 256);
  await assert.rejects(mesh(garbage), (e) => e instanceof WqmeshError && !['internal', 'options'].includes(e.code) &&
                                           /wqmesh: \w+: .{10,}/.test(e.message));
  const zero = join(work, 'zero.off');
  writeFileSync(zero, '');
  await assert.rejects(mesh(await readFile(zero)), (e) => e.code === 'empty');
  for (const path of ['model.off', '/tmp/x.stl', 'C:\\models\\part.off', './a']) {
    await assert.rejects(mesh(path), (e) => e instanceof TypeError && /looks like a file name/.test(e.message), path);
    await assert.rejects(check(path), TypeError);
  }
  for (const bad of [null, undefined, 42, {}, [1, 2, 3], true]) {
    await assert.rejects(mesh(bad), (e) => e instanceof TypeError && /expected the file's bytes/.test(e.message), String(bad));
  }
  const box = example('box.off');
  await assert.rejects(mesh(box, { rhoo: 5 }), (e) => e instanceof WqmeshError && e.code === 'options' &&
                                                      /'rhoo'/.test(e.message) && /rho, sliverAngle/.test(e.message));
  await assert.rejects(mesh(box, { rho: '3' }), (e) => e.code === 'options' && /rho must be a number/.test(e.message));
  await assert.rejects(mesh(box, { pump: 1 }), (e) => e.code === 'options' && /pump must be true or false/.test(e.message));
  await assert.rejects(mesh(box, { signal: new AbortController().signal }), (e) => e.code === 'options' && /third argument/.test(e.message));
  await assert.rejects(check(box, { rho: 3 }), (e) => e.code === 'options' && /boxMargin/.test(e.message));
  await assert.rejects(mesh(box, 5), TypeError);
  await assert.rejects(mesh(box, {}, { signal: 5 }), TypeError);
  // Text input is read by content.
  assert.equal((await check(box.toString('utf8'))).valid, true);
  // The sync forms need the module in this thread first.
  await ready();
  assert.throws(() => meshSync('a/b.off'), TypeError);
  assert.throws(() => meshSync(box, { rhoo: 1 }), (e) => e.code === 'options');
});

// ---- Abort and progress --------------------------------------------------------

// A run of seconds: the box with a small size bound.
const LONG = { maxSize: 0.02, maxVertices: 2000000 };

// PUMP comes after REFINE: a shorter run (2 s) reaches it.
for (const [phase, runOptions] of [['initialize', LONG], ['conform', LONG], ['refine', LONG], ['pump', { maxSize: 0.1 }]]) {
  test(`an abort during ${phase} rejects within 100 ms and the next call succeeds`, async () => {
    const controller = new AbortController();
    let abortedAt = 0;
    let seen = '';
    const box = example('box.off');
    await assert.rejects(mesh(box, runOptions, {
      signal: controller.signal,
      onProgress: (p) => {
        if (!abortedAt && p.phase === phase && (phase !== 'refine' || p.vertices > 3000)) {
          seen = p.phase;
          abortedAt = performance.now();
          controller.abort();
        }
      },
    }), (e) => {
      const ms = performance.now() - abortedAt;
      assert.equal(e.name, 'AbortError');
      assert.ok(e instanceof DOMException);
      assert.ok(ms < 100, `rejected ${ms} ms after the abort`);
      return true;
    });
    assert.equal(seen, phase);
    const r = await mesh(box);
    assert.equal(r.stats.conforming, true);
  });
}

test('an already aborted signal rejects at once; abort also stops check and the writers', async () => {
  const signal = AbortSignal.abort();
  await assert.rejects(mesh(example('box.off'), {}, { signal }), { name: 'AbortError' });
  await assert.rejects(check(example('box.off'), {}, { signal }), { name: 'AbortError' });
  const r = await mesh(example('box.off'));
  await assert.rejects(writeVtu(r, { signal }), { name: 'AbortError' });
});

test('100 calls in a row: no growth of the module\'s memory', async () => {
  const box = example('box.off');
  const live = [];
  const heap = [];
  const rss = [];
  for (let i = 0; i < 100; ++i) {
    const r = await mesh(box);
    assert.equal(r.stats.conforming, true);
    live.push(r.memory.liveBytes);
    heap.push(r.memory.heapBytes);
    rss.push(process.memoryUsage().rss);
  }
  // The same worker runs them all (it is reused); after the first call the
  // C++ allocations held between calls and the wasm memory stay put.
  assert.ok(live[99] <= live[1], `live C++ bytes ${live[1]} -> ${live[99]}`);
  assert.equal(heap[99], heap[1], `wasm heap ${heap[1]} -> ${heap[99]}`);
  const mb = (x) => (x / 2 ** 20).toFixed(1);
  test.diagnostic?.(`100 calls: live C++ bytes ${live[0]} / ${live[1]} / ${live[99]}, wasm heap ${mb(heap[1])} MB / ` +
                    `${mb(heap[99])} MB, process RSS ${mb(rss[1])} MB -> ${mb(rss[99])} MB`);
  console.log(`# memory over 100 calls: live C++ bytes after call 1, 2, 100: ${live[0]}, ${live[1]}, ${live[99]}; ` +
              `wasm heap ${mb(heap[1])} -> ${mb(heap[99])} MB; process RSS ${mb(rss[1])} -> ${mb(rss[99])} MB`);
});

// ---- Writers ------------------------------------------------------------------

function vtuArrays(text) {
  return [...text.matchAll(/<DataArray[^>]*Name="([^"]+)"/g)].map((m) => m[1]);
}

test('the VTU has the same arrays on every run, and TetGen gets .edge', async () => {
  const spike = example('spike.off');
  const pumped = await mesh(spike);
  const plain = await mesh(spike, { pump: false });
  const a = vtuArrays(await writeVtu(pumped));
  const b = vtuArrays(await writeVtu(plain));
  assert.deepEqual(a, b);
  for (const name of ['weight', 'min_dihedral', 'radius_edge', 'radius_ratio_R_over_r', 'volume', 'class'])
    assert.ok(a.includes(name), `array ${name}`);
  assert.ok(!a.includes('aspect_ratio'), 'no array named like VTK\'s normalised measure');
  const medit = await writeMedit(pumped);
  assert.match(medit, new RegExp(`\\nTetrahedra\\n${pumped.stats.tets}\\n`));
  const bytes = await writeMedit(pumped, { bytes: true });
  assert.ok(bytes instanceof Uint8Array);
  assert.equal(new TextDecoder().decode(bytes), medit);
  const t = await writeTetgen(pumped);
  const count = (s) => Number(s.split(/\s+/)[0]);
  assert.equal(count(t.node), pumped.stats.vertices);
  assert.equal(count(t.ele), pumped.stats.tets);
  assert.equal(count(t.face), pumped.boundary.length / 3);
  assert.ok(count(t.edge) >= 15, 'spike has at least its 15 input edges');
  // Chains are oriented: at a vertex on exactly two subsegments (inside an
  // input edge), one ends and the other begins (TetGen's -r wants this).
  const rows = t.edge.trim().split('\n').slice(1).map((l) => l.trim().split(/\s+/).map(Number));
  assert.equal(rows.length, count(t.edge));
  const starts = new Map();
  const ends = new Map();
  for (const [, a, b, marker] of rows) {
    assert.equal(marker, 1);
    starts.set(a, (starts.get(a) ?? 0) + 1);
    ends.set(b, (ends.get(b) ?? 0) + 1);
  }
  let inside = 0;
  for (const v of new Set([...starts.keys(), ...ends.keys()])) {
    if ((starts.get(v) ?? 0) + (ends.get(v) ?? 0) !== 2) continue;
    ++inside;
    assert.equal(starts.get(v), 1, `vertex ${v}: one subsegment begins there`);
    assert.equal(ends.get(v), 1, `vertex ${v}: one subsegment ends there`);
  }
  assert.ok(inside > 0, 'spike has input edges split into several subsegments');
  await assert.rejects(writeVtu({ ...pumped, tets: new Uint32Array([0, 1, 2, 999999]), tetClass: new Uint8Array(1) }),
                       (e) => e instanceof TypeError && /not a vertex index/.test(e.message));
  await assert.rejects(writeVtu(null), TypeError);
  const tetgen = spawnSync('tetgen', ['-h'], { encoding: 'utf8' });
  if (tetgen.error) return;  // TetGen is optional (apt-get install tetgen)
  const base = join(work, 'spike_tg');
  for (const ext of ['node', 'ele', 'face', 'edge']) writeFileSync(`${base}.${ext}`, t[ext]);
  const r = spawnSync('tetgen', ['-rNEFC', `${base}.ele`], { encoding: 'utf8' });
  assert.doesNotMatch(r.stdout + r.stderr, /missing connection|Wrong seg/i, 'tetgen -rNEFC reads the files cleanly');
});

// ---- The Node command line -----------------------------------------------------

function nodeCliRun(args) {
  return spawnSync(process.execPath, [nodeCli, ...args], { encoding: 'utf8' });
}

test('the Node command line has the native exit codes and stats keys', { skip: skipNative }, () => {
  const box = join(root, 'examples/models/box.off');
  const stats = join(work, 'cli.json');
  const r = nodeCliRun(['mesh', box, '-o', join(work, 'cli.ele'), '--stats', stats]);
  assert.equal(r.status, 0, r.stderr);
  for (const ext of ['node', 'ele', 'face', 'edge']) assert.ok(existsSync(join(work, `cli.${ext}`)), ext);
  const n = native(['mesh', box, '-o', join(work, 'native.ele'), '--stats', join(work, 'native.json'), '--quiet']);
  assert.equal(n.status, 0);
  const ws = JSON.parse(readFileSync(stats, 'utf8'));
  for (const k of Object.keys(JSON.parse(readFileSync(join(work, 'native.json'), 'utf8')))) assert.ok(k in ws, k);
  const wasmCheck = nodeCliRun(['check', box]);
  const nativeCheck = native(['check', box]);
  assert.equal(wasmCheck.status, 0);
  assert.equal(wasmCheck.stdout, nativeCheck.stdout, 'the same check JSON, byte for byte');
  const broken = join(work, 'open.off');
  writeFileSync(broken, 'OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n');
  for (const args of [['check', broken], ['mesh', broken, '-o', join(work, 'x.vtu')]]) {
    const w = nodeCliRun(args);
    const nn = native(args);
    assert.equal(w.status, 2, w.stderr);
    assert.equal(w.status, nn.status);
  }
  assert.equal(nodeCliRun(['mesh', box, '-o', join(work, 'x.vtu'), '--max-vertices', '8']).status, 3);
  assert.equal(nodeCliRun(['mesh', box, '-o', join(work, 'x.vtu'), '--rho', '0.5']).status, 1);
  assert.equal(nodeCliRun(['mesh', box, '-o', join(work, 'x.vtu'), '--rhoo', '3']).status, 1);
  assert.equal(nodeCliRun(['mesh', box, '-o', join(work, 'x.txt')]).status, 1);
  assert.equal(nodeCliRun(['check', join(work, 'missing.off')]).status, 2);
  const lines = nodeCliRun(['mesh', box, '-o', join(work, 'x.vtu')]).stderr;
  assert.match(lines, /^wqmesh: initialize: \d+ vertices$/m, 'plain progress lines when stderr is not a terminal');
});

test('Ctrl-C stops a Node command-line run at once and writes nothing', async () => {
  const out = join(work, 'interrupted.vtu');
  const child = spawn(process.execPath, [nodeCli, 'mesh', join(root, 'examples/models/box.off'), '-o', out,
                                         '--max-size', '0.02', '--max-vertices', '2000000']);
  let stderr = '';
  let sentAt = 0;
  child.stderr.on('data', (d) => {
    stderr += d;
    if (!sentAt && /refine: /.test(stderr)) {
      sentAt = performance.now();
      child.kill('SIGINT');
    }
  });
  const code = await new Promise((ok) => child.on('exit', (c) => ok(c)));
  assert.ok(sentAt > 0, `the run reached refine: ${stderr}`);
  assert.equal(code, 130, stderr);
  assert.match(stderr, /interrupted/);
  assert.ok(!existsSync(out));
  console.log(`# Ctrl-C to exit: ${(performance.now() - sentAt).toFixed(0)} ms`);
});

test('on a terminal the Node command line draws a progress bar', { skip: !existsSync('/usr/bin/script') && 'no script(1)' }, () => {
  // script(1) gives the command a pseudo-terminal.
  const out = join(work, 'tty.vtu');
  const r = spawnSync('script', ['-qec', `${process.execPath} ${nodeCli} mesh ${join(root, 'examples/models/spike.off')} -o ${out}`,
                                 '/dev/null'], { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stdout);
  assert.match(r.stdout, /\rwqmesh: \[[#.]{30}\] +\d+% (initialize|conform|refine|pump|extract) \d+ vertices/);
  assert.ok(existsSync(out));
});

test('calls at the same time run in workers of their own and all succeed', async () => {
  const models = ['box.off', 'spike.off', 'thin_wedge.off'];
  const results = await Promise.all(models.map((m) => mesh(example(m))));
  for (const [k, r] of results.entries()) {
    assert.equal(r.stats.conforming, true, models[k]);
    signedVolume(r.vertices, r.tets, models[k]);
  }
});

test('a caller run as node --input-type=module -e gets a valid mesh from the worker', async () => {
  // The worker must not inherit flags such as --input-type, which Node refuses
  // in a worker script (wasm/index.mjs starts it with execArgv: []).
  const entry = new URL('../../wasm/index.mjs', import.meta.url).href;
  const model = join(root, 'examples/models/spike.off');
  const script = `import { mesh } from ${JSON.stringify(entry)};
import { readFileSync } from 'node:fs';
const r = await mesh(readFileSync(${JSON.stringify(model)}));
process.stdout.write(JSON.stringify({ conforming: r.stats.conforming, vertices: [...r.vertices], tets: [...r.tets] }));`;
  const child = spawnSync(process.execPath, ['--input-type=module', '-e', script], { encoding: 'utf8', maxBuffer: 1 << 26 });
  assert.equal(child.status, 0, `node --input-type=module -e: exit ${child.status}: ${child.stderr}`);
  const got = JSON.parse(child.stdout);
  assert.equal(got.conforming, true);
  const volume = signedVolume(got.vertices, got.tets, 'spike.off through node -e');
  const here = await mesh(example('spike.off'));
  assert.equal(got.tets.length, here.tets.length, 'the same mesh as in this process');
  assert.ok(Math.abs(volume - signedVolume(here.vertices, here.tets, 'spike.off')) <= 1e-9 * Math.abs(volume));
});

test('wqmesh.mjs holds no copy of its binary; instances on one compiled module mesh alike', async () => {
  const glue = join(root, 'wasm/wqmesh.mjs');
  const text = readFileSync(glue, 'utf8');
  const binary = readFileSync(join(root, 'wasm/wqmesh.wasm'));
  assert.ok(binary.subarray(0, 4).equals(Buffer.from([0, 97, 115, 109])), 'wasm/wqmesh.wasm is a wasm binary');
  // "\0asm" in base64 is "AGFzbQ": a SINGLE_FILE glue carries it in a data URI.
  assert.ok(!/base64,AGFzbQ/.test(text), 'wqmesh.mjs inlines no binary');
  assert.ok(text.length < binary.length / 4, `the glue (${text.length} bytes) is small beside the binary (${binary.length})`);
  const factory = (await import(pathToFileURL(glue).href)).default;
  const compiled = await compileWasm(pathToFileURL(join(root, 'wasm/wqmesh.wasm')));
  assert.ok(compiled instanceof WebAssembly.Module);
  const bytes = example('spike.off');
  const results = [];
  for (let k = 0; k < 2; ++k) {
    const module = await instantiateModule(factory, compiled);
    const r = module.mesh(bytes, {}, undefined);
    assert.equal(r.error, undefined);
    results.push(r);
  }
  assert.deepEqual(results[1].vertices, results[0].vertices);
  assert.deepEqual(results[1].tets, results[0].tets);
  signedVolume(results[0].vertices, results[0].tets, 'spike.off');
  await assert.rejects(instantiateModule(factory, null), (e) => e instanceof WqmeshError && e.code === 'internal');
});

test('a missing, corrupt or foreign .wasm beside a module: a WqmeshError naming it; a retry once it is there loads',
     { timeout: 60000 }, async () => {
  const cases = { missing: null, corrupt: Buffer.from('not wasm at all'), foreign: Buffer.from([0, 97, 115, 109, 1, 0, 0, 0]) };
  for (const [name, binary] of Object.entries(cases)) {
    const dir = join(work, `beside-${name}`);
    mkdirSync(dir);
    copyFileSync(join(root, 'wasm/wqmesh.mjs'), join(dir, 'wqmesh.mjs'));
    if (binary) writeFileSync(join(dir, 'wqmesh.wasm'), binary);
    const moduleUrl = pathToFileURL(join(dir, 'wqmesh.mjs'));
    await assert.rejects(loadWqmesh({ moduleUrl }), (e) => {
      assert.ok(e instanceof WqmeshError, `${name}: ${e}`);
      assert.equal(e.code, 'internal');
      assert.match(e.message, name === 'foreign' ? /not the one of this module's glue/ : /wqmesh\.wasm/, name);
      return true;
    });
  }
  // The missing file put back: the failed load is not remembered.
  const dir = join(work, 'beside-missing');
  copyFileSync(join(root, 'wasm/wqmesh.wasm'), join(dir, 'wqmesh.wasm'));
  const wq = await loadWqmesh({ moduleUrl: pathToFileURL(join(dir, 'wqmesh.mjs')) });
  const r = wq.mesh(example('box.off'));
  assert.equal(r.stats.conforming, true);
  signedVolume(r.vertices, r.tets, 'box.off once wqmesh.wasm is back');
});

test('a package without wqmesh.wasm: import works, mesh() and ready() reject with a WqmeshError naming it', { timeout: 60000 }, () => {
  const dir = join(work, 'package-without-wasm');
  mkdirSync(dir);
  for (const f of ['index.mjs', 'core.mjs', 'worker.mjs', 'options.mjs', 'wqmesh.mjs']) copyFileSync(join(root, 'wasm', f), join(dir, f));
  const script = `import { mesh, ready, version } from ${JSON.stringify(pathToFileURL(join(dir, 'index.mjs')).href)};
const out = { version };
for (const [name, call] of [['mesh', () => mesh('OFF 4 4 0 0 0 0 1 0 0 0 1 0 0 0 1 3 0 2 1 3 0 1 3 3 0 3 2 3 1 2 3')], ['ready', () => ready()]]) {
  try { await call(); out[name] = 'resolved'; } catch (e) { out[name] = { name: e.name, code: e.code, message: e.message }; }
}
process.stdout.write(JSON.stringify(out));`;
  const child = spawnSync(process.execPath, ['--input-type=module', '-e', script], { encoding: 'utf8', timeout: 50000 });
  assert.equal(child.status, 0, `exit ${child.status}: ${child.stderr}`);
  const out = JSON.parse(child.stdout);
  assert.equal(typeof out.version, 'string');
  for (const name of ['mesh', 'ready']) {
    assert.equal(out[name].name, 'WqmeshError', `${name}: ${JSON.stringify(out[name])}`);
    assert.equal(out[name].code, 'internal');
    assert.match(out[name].message, /wqmesh\.wasm/);
  }
});
