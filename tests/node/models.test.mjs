// wqmesh: every model of ../shared/models, broken ones included, through the
// command line (`wqmesh check`, `wqmesh mesh --max-vertices 10000`) and the
// wasm module (check, mesh with maxVertices 10000): no crash, no hang, no
// uncaught exception. Expected: exit code 0 (valid / meshed), 2 (invalid
// input: an error kind and a message) or 3 (stopped at the vertex limit:
// `stopped: "limit"` and a stop message); statistics well formed; the command
// line and the module agree on whether the input is valid and on the error
// kind. A meshed model conforms and keeps the input volume. The limit keeps
// the whole file near a minute (models that need more vertices stop at it).
// Skipped when ../shared/models is absent. WQMESH_CLI and WQMESH_MODULE choose
// other builds than build/native and build/wasm.
// Run: node --test tests/node/
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, readdirSync, readFileSync } from 'node:fs';
import { basename, join } from 'node:path';
import { test } from 'node:test';

import { errorKinds } from './lib/names.mjs';
import { cli, loadModule, root, skipCli, workDir } from './lib/setup.mjs';

const shared = join(root, '../shared/models');
const MAX_VERTICES = 10000;
const DEADLINE_MS = 120_000;  // per run: beyond it, a hang
const MAX_BUFFER = 256 * 2 ** 20;  // the check report of a big model is megabytes long

const KINDS = errorKinds();  // the one list: error.h
const STATS_KEYS = ['input_points', 'sharp_elements', 'points_inserted', 'vertices', 'tets', 'min_dihedral_deg',
  'radius_edge_bins', 'dihedral_bins', 'slivers', 'skinny', 'near_small_angle', 'violations', 'volume_input',
  'volume_mesh', 'conforming', 'protecting_balls', 'stopped', 'time_s', 'phases'];

const models = existsSync(shared)
  ? readdirSync(shared).filter((n) => /\.(off|stl)$/i.test(n)).sort().map((n) => join(shared, n))
  : [];
const skip = models.length === 0 && '../shared/models is absent';
const skipBoth = skip || skipCli;
const work = workDir('models');

const wqmesh = skip ? null : await loadModule();

/** What the command line said about each model: { valid, kind, meshed, stopped }. */
const native = new Map();

function checkStats(name, s, stopped) {
  for (const k of STATS_KEYS) assert.ok(k in s, `${name}: stats key ${k}`);
  assert.ok(Number.isInteger(s.vertices) && s.vertices >= 0, `${name}: vertices`);
  assert.ok(Number.isInteger(s.tets) && s.tets >= 0, `${name}: tets`);
  // No bound on the count of a stopped run: INITIALIZE inserts every input
  // vertex and protecting-ball point before the limit is looked at (fandisk:
  // 29223 vertices with a limit of 10000).
  if (stopped === '') assert.ok(s.vertices <= MAX_VERTICES, `${name}: ${s.vertices} vertices beyond the limit`);
  assert.equal(s.stopped, stopped, `${name}: stopped`);
  if (stopped === 'limit') {
    assert.equal(typeof s.stop_message, 'string', `${name}: stop_message`);
    assert.ok(s.stop_message.length > 0, `${name}: stop_message`);
  } else {
    assert.equal(s.conforming, true, `${name}: a finished mesh conforms`);
    assert.ok(s.tets > 0, `${name}: tets`);
    assert.ok(Math.abs(s.volume_mesh - s.volume_input) <= 1e-9 * Math.abs(s.volume_input),
              `${name}: volume ${s.volume_mesh} vs ${s.volume_input}`);
  }
}

for (const path of models) {
  const name = basename(path);

  test(`command line: ${name}`, { skip: skipBoth }, () => {
    const t0 = Date.now();
    const check = spawnSync(cli, ['check', path, '--compact'],
                            { encoding: 'utf8', timeout: DEADLINE_MS, maxBuffer: MAX_BUFFER });
    assert.equal(check.error, undefined, `check: ${check.error}`);
    assert.equal(check.signal, null, `check killed by ${check.signal}`);
    assert.ok(check.status === 0 || check.status === 2, `check exit ${check.status}: ${check.stderr}`);
    const report = JSON.parse(check.stdout);
    assert.equal(report.valid, check.status === 0);
    if (!report.valid) {
      assert.ok(KINDS.includes(report.error.kind), `kind ${report.error.kind}`);
      assert.ok(report.error.message.length > 10, 'a message naming the defect');
      assert.match(check.stderr, new RegExp(`${report.error.kind}: `));
    }

    const stats = join(work, `${name}.json`);
    const mesh = spawnSync(cli, ['mesh', path, '-o', join(work, `${name}.mesh`), '--stats', stats, '--quiet',
                                 '--max-vertices', String(MAX_VERTICES)],
                           { encoding: 'utf8', timeout: DEADLINE_MS, maxBuffer: MAX_BUFFER });
    assert.equal(mesh.error, undefined, `mesh: ${mesh.error}`);
    assert.equal(mesh.signal, null, `mesh killed by ${mesh.signal}`);
    assert.doesNotMatch(mesh.stderr, /internal error|out of memory/);
    if (!report.valid) {
      assert.equal(mesh.status, 2, mesh.stderr);
      assert.match(mesh.stderr, new RegExp(`${report.error.kind}: `));
    } else {
      assert.ok(mesh.status === 0 || mesh.status === 3, `mesh exit ${mesh.status}: ${mesh.stderr}`);
      checkStats(name, JSON.parse(readFileSync(stats, 'utf8')), mesh.status === 3 ? 'limit' : '');
    }
    native.set(name, { valid: report.valid, kind: report.error?.kind, status: mesh.status });
    console.log(`${name}: check ${check.status}, mesh ${mesh.status}, ${(Date.now() - t0) / 1000} s (native)`);
  });

  test(`wasm: ${name}`, { skip }, () => {
    const t0 = Date.now();
    const bytes = readFileSync(path);
    const report = wqmesh.check(bytes);
    if (!report.valid) {
      assert.ok(KINDS.includes(report.error.kind), `kind ${report.error.kind}`);
      assert.ok(report.error.message.length > 10, 'a message naming the defect');
    }
    let result;
    try {
      result = wqmesh.mesh(bytes, { maxVertices: MAX_VERTICES, onProgress: () => Date.now() - t0 < DEADLINE_MS });
    } catch (e) {
      assert.equal(report.valid, false, `mesh threw on a valid input: ${e.message}`);
      assert.equal(e.kind, report.error.kind, e.message);
    }
    if (result) {
      assert.equal(report.valid, true, 'mesh accepted an invalid input');
      assert.notEqual(result.stats.stopped, 'cancelled', `no result within ${DEADLINE_MS / 1000} s`);
      assert.ok(['', 'limit'].includes(result.stats.stopped), `stopped: ${result.stats.stopped}`);
      checkStats(name, result.stats, result.stats.stopped);
      assert.equal(result.tets.length, 4 * result.stats.tets);
      assert.equal(result.vertices.length, 3 * result.stats.vertices);
    }
    const n = native.get(name);
    if (n) {
      assert.equal(report.valid, n.valid, 'native and wasm agree on validity');
      assert.equal(report.error?.kind, n.kind, 'native and wasm agree on the error kind');
    }
    console.log(`${name}: ${report.valid ? `mesh ${result.stats.stopped || 'done'}` : report.error.kind}, ` +
                `${(Date.now() - t0) / 1000} s (wasm)`);
  });
}
