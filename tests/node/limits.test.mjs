// wqmesh: the limits, through the command line and the wasm module, each
// ending in a clean error rather than a crash or an endless run:
// - input size: more bytes than InputLimits.max_bytes (1 GiB; a sparse file
//   for the command line, which refuses it by its size without reading it; a
//   Uint8Array for the module, refused before it is copied into wasm memory),
//   and OFF or STL headers announcing more points or faces than the limits
//   (too_large, exit code 2);
// - vertex count: out-of-range limits are usage or options errors;
// - wasm memory: a run that needs more than options.maxMemoryBytes stops with
//   a "limit" error wherever the allocation that crosses the cap happens (the
//   caps swept below fail in the reader, the mesher and the output), and the
//   module stays usable for the next call. Beyond the cap, the same path
//   serves a real shortage (4 GB, -sABORTING_MALLOC=0): std::bad_alloc.
//   The 4 GB path is tested on wqmesh-mem32.mjs, the same module linked with a
//   32 MB ceiling (skipped when not built).
// WQMESH_CLI and WQMESH_MODULE (the path of wqmesh.mjs; wqmesh-mem32.mjs is
// looked for beside it) choose other builds than build/native and build/wasm.
// Run: node --test tests/node/
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { closeSync, existsSync, ftruncateSync, openSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { after, test } from 'node:test';
import { pathToFileURL } from 'node:url';

import { loadWqmesh } from '../../wasm/index.mjs';
import { cli, loadModule, modulePath, root, skipCli, workDir } from './lib/setup.mjs';

const mem32Path = join(dirname(modulePath({ build: true })), 'wqmesh-mem32.mjs');
const wqmesh = await loadModule({ build: true });
const work = workDir('limits');
const run = (...args) => spawnSync(cli, args, { encoding: 'utf8', timeout: 60_000 });
const model = (name) => readFileSync(join(root, 'examples/models', name));

const MAX_BYTES = 2 ** 30;  // InputLimits.max_bytes

// Inputs whose header announces more than the limits (5e6 points, 1e7 faces).
const announced = {
  'points.off': 'OFF\n6000000 4 0\n0 0 0\n',
  'faces.off': 'OFF\n4 20000000 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n',
  'polygon.off': 'OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n200000 0 1 2\n',
};
// (A binary STL is one only at exactly 84 + 50 n bytes, so a short file
// announcing 2e7 triangles is "not an OFF or STL file": readers.test.mjs.)

test('the command line refuses an input larger than 1 GiB without reading it', { skip: skipCli }, () => {
  const big = join(work, 'big.off');
  const fd = openSync(big, 'w');
  ftruncateSync(fd, MAX_BYTES + 1);  // sparse: no disk used
  closeSync(fd);
  const start = Date.now();
  const check = run('check', big, '--compact');
  assert.equal(check.status, 2, check.stderr);
  const report = JSON.parse(check.stdout);
  assert.equal(report.valid, false);
  assert.equal(report.error.kind, 'too_large');
  assert.match(report.error.message, /1073741825 bytes, beyond the limit of 1073741824/);
  const mesh = run('mesh', big, '-o', join(work, 'big.mesh'));
  assert.equal(mesh.status, 2, mesh.stderr);
  assert.match(mesh.stderr, /too_large/);
  assert.ok(Date.now() - start < 10_000, 'refused by its size, not read');
});

test('the command line refuses a folder or a missing file as input', { skip: skipCli }, () => {
  for (const path of [work, join(work, 'missing.off')]) {
    const check = run('check', path);
    assert.equal(check.status, 2);
    assert.equal(JSON.parse(check.stdout).error.kind, 'io');
    assert.match(check.stderr, path === work ? /folder/ : /cannot open/);
    assert.equal(run('mesh', path, '-o', join(work, 'x.mesh')).status, 2);
  }
});

test('headers announcing too many points, faces or polygon corners are too_large (command line)',
     { skip: skipCli }, () => {
  const files = { ...announced };
  for (const [name, content] of Object.entries(files)) {
    const path = join(work, name);
    writeFileSync(path, content);
    const check = run('check', path, '--compact');
    assert.equal(check.status, 2, `${name}: ${check.stderr}`);
    assert.equal(JSON.parse(check.stdout).error.kind, 'too_large', name);
    const mesh = run('mesh', path, '-o', join(work, 'x.mesh'), '--quiet');
    assert.equal(mesh.status, 2, `${name}: ${mesh.stderr}`);
    assert.match(mesh.stderr, /too_large/, name);
  }
});

test('the wasm module refuses an input larger than 1 GiB before copying it', () => {
  const big = new Uint8Array(MAX_BYTES + 1);  // zero pages, never touched
  const report = wqmesh.check(big);
  assert.equal(report.valid, false);
  assert.equal(report.error.kind, 'too_large');
  assert.match(report.error.message, /1073741825 bytes, beyond the limit of 1073741824/);
  assert.throws(() => wqmesh.mesh(big), (e) => e.kind === 'too_large');
});

test('headers announcing too many points, faces or polygon corners are too_large (wasm)', () => {
  const inputs = { ...announced };
  for (const [name, content] of Object.entries(inputs)) {
    const report = wqmesh.check(content);
    assert.equal(report.valid, false, name);
    assert.equal(report.error.kind, 'too_large', `${name}: ${report.error.message}`);
    assert.throws(() => wqmesh.mesh(content), (e) => e.kind === 'too_large', name);
  }
});

test('vertex limits out of range are refused', () => {
  const box = model('box.off');
  for (const maxVertices of [7, 1e10, Infinity, NaN]) {
    assert.throws(() => wqmesh.mesh(box, { maxVertices }), (e) => e.kind === 'options', String(maxVertices));
  }
  for (const boxMargin of [0, 1e-4, 1e4, Infinity]) {
    assert.throws(() => wqmesh.mesh(box, { boxMargin }), (e) => e.kind === 'options', String(boxMargin));
  }
  assert.throws(() => wqmesh.mesh(box, { maxSize: Infinity }), (e) => e.kind === 'options');
  if (!skipCli) {
    for (const n of ['7', '1e10', '12.5']) {
      assert.equal(run('mesh', join(root, 'examples/models/box.off'), '-o', join(work, 'x.mesh'),
                       '--max-vertices', n).status, 1, n);
    }
  }
});

test('maxMemoryBytes out of range is refused', () => {
  const box = model('box.off');
  for (const maxMemoryBytes of [0, 1024, 2 ** 16 - 1, 2 ** 32 + 1, Infinity, NaN]) {
    assert.throws(() => wqmesh.mesh(box, { maxMemoryBytes }), (e) => e.kind === 'options', String(maxMemoryBytes));
  }
  assert.equal(wqmesh.mesh(box, { maxMemoryBytes: 2 ** 32 }).stats.stopped, '');
});

test('a run beyond maxMemoryBytes stops with a limit error and the module stays usable', () => {
  const spike = model('spike.off');
  const box = model('box.off');
  const full = wqmesh.mesh(spike);
  const peak = full.stats.peak_memory_mb * 2 ** 20;
  assert.ok(peak > 2 ** 17 && peak < 2 ** 30, `peak memory ${full.stats.peak_memory_mb} MB`);
  // Caps from 64 KiB up to twice the peak: below the peak the run must stop
  // with "limit" (in every phase of the mesher, wherever the cap is crossed),
  // above it the run must give the same mesh as without.
  let limited = 0;
  for (let cap = 2 ** 16; cap < 2 * peak; cap = Math.ceil(cap * 1.25)) {
    let r;
    try {
      r = wqmesh.mesh(spike, { maxMemoryBytes: cap });
    } catch (e) {
      assert.equal(e.kind, 'limit', `cap ${cap}: ${e.message}`);
      assert.match(e.message, new RegExp(`maxMemoryBytes = ${cap} bytes`));
      assert.ok(cap < 1.05 * peak, `cap ${cap} above the peak ${peak} failed: ${e.message}`);
      ++limited;
    }
    if (r) {
      assert.ok(cap > 0.95 * peak, `cap ${cap} below the peak ${peak} succeeded`);
      assert.equal(r.stats.tets, full.stats.tets);
      assert.equal(r.stats.stopped, '');
    }
    // The module still works, for meshing and checking.
    const after = wqmesh.mesh(box);
    assert.equal(after.stats.conforming, true);
    assert.equal(wqmesh.check(box).valid, true);
  }
  assert.ok(limited >= 5, `${limited} capped runs`);
  // Crossing the cap while reading: 300000 unused points (7 MB once read).
  const points = '0 0 0\n'.repeat(300000);
  const crowded = new TextEncoder().encode(
    'OFF\n300008 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n' + points +
    '4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n');
  assert.throws(() => wqmesh.mesh(crowded, { maxMemoryBytes: 4 * 2 ** 20 }), (e) => {
    assert.equal(e.kind, 'limit', e.message);
    assert.match(e.message, /\(in read, at 0 vertices\)/);
    return true;
  });
  assert.equal(wqmesh.mesh(crowded).stats.conforming, true);
  // Memory is given back: the same run again gives the same peak.
  const again = wqmesh.mesh(spike);
  assert.equal(again.stats.tets, full.stats.tets);
  assert.ok(Math.abs(again.stats.peak_memory_mb - full.stats.peak_memory_mb) < 1,
            `${again.stats.peak_memory_mb} vs ${full.stats.peak_memory_mb} MB`);
});

test('a run beyond the wasm memory ceiling stops with a limit error and the module stays usable',
     { skip: !existsSync(mem32Path) && 'wqmesh-mem32.mjs is not built' }, async () => {
  // The module linked with -sMAXIMUM_MEMORY=32MB: malloc returns null when the
  // memory cannot grow, operator new throws std::bad_alloc, the run unwinds.
  const small = await loadWqmesh({ moduleUrl: pathToFileURL(mem32Path) });
  const box = model('box.off');
  const spike = model('spike.off');
  for (const maxSize of [0.03, 0.02]) {
    // No maxMemoryBytes cap (4 GiB): only the ceiling stops the run.
    assert.throws(() => small.mesh(box, { maxSize, maxMemoryBytes: 2 ** 32 }), (e) => {
      assert.equal(e.kind, 'limit', e.message);
      assert.match(e.message, /does not fit in the wasm memory .*\(in (refine|pump|extract|output), at \d+ vertices\)/);
      return true;
    });
    const after = small.mesh(spike);
    assert.equal(after.stats.stopped, '');
    assert.equal(after.stats.conforming, true);
    assert.equal(small.check(box).valid, true);
  }
});
