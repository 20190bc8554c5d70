// wqmesh: the command line's contract (`wqmesh check` and `wqmesh mesh`): exit
// codes, output files in every format, and the keys of the statistics.
// Skipped when the native build is missing.
// Run: node --test tests/node/
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { cli, root, skipCli, workDir } from './lib/setup.mjs';

const skip = skipCli;
const work = workDir('cli');
const spike = join(root, 'examples/models/spike.off');
const run = (...args) => spawnSync(cli, args, { encoding: 'utf8' });

const KEYS = ['input_points', 'sharp_elements', 'points_inserted', 'vertices', 'tets', 'min_dihedral_deg',
  'radius_edge_bins', 'dihedral_bins', 'slivers', 'skinny', 'near_small_angle', 'violations', 'volume_input',
  'volume_mesh', 'protecting_balls', 'stopped', 'time_s', 'phases'];

test('mesh writes .mesh, .vtu and TetGen files and complete statistics', { skip }, () => {
  for (const ext of ['mesh', 'vtu', 'ele']) {
    const out = join(work, `spike.${ext}`);
    const stats = join(work, `spike.${ext}.json`);
    const r = run('mesh', spike, '-o', out, '--stats', stats, '--quiet');
    assert.equal(r.status, 0, r.stderr);
    const s = JSON.parse(readFileSync(stats, 'utf8'));
    for (const k of KEYS) assert.ok(k in s, `stats key ${k}`);
    assert.deepEqual(Object.keys(s.radius_edge_bins), ['0.6-1.4', '1.4-2.2', '>2.2']);
    assert.deepEqual(Object.keys(s.dihedral_bins), ['0-3', '3-5', '5-10']);
    assert.equal(s.stopped, '');
    assert.ok(Math.abs(s.volume_mesh - s.volume_input) <= 1e-9 * s.volume_input);
    if (ext === 'ele') {
      for (const e of ['node', 'ele', 'face']) assert.ok(existsSync(join(work, `spike.${e}`)), `spike.${e}`);
      const header = readFileSync(join(work, 'spike.ele'), 'utf8').trim().split('\n')[0].trim().split(/\s+/);
      assert.equal(Number(header[0]), s.tets);
    } else if (ext === 'mesh') {
      const text = readFileSync(out, 'utf8');
      assert.match(text, /MeshVersionFormatted/);
      assert.match(text, new RegExp(`Tetrahedra\\s+${s.tets}\\s`));
    } else {
      const text = readFileSync(out, 'utf8');
      assert.match(text, new RegExp(`NumberOfCells="${s.tets}"`));
      assert.match(text, /Name="class"/);
    }
  }
});

test('invalid input exits 2 with the defect on stderr', { skip }, () => {
  const open = join(work, 'open.off');
  writeFileSync(open, 'OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n');
  for (const cmd of ['check', 'mesh']) {
    const r = cmd === 'check' ? run('check', open) : run('mesh', open, '-o', join(work, 'x.mesh'));
    assert.equal(r.status, 2, `${cmd}: ${r.stderr}`);
    assert.match(r.stderr, /open_boundary/);
  }
});

test('the vertex limit exits 3 and says so in the statistics', { skip }, () => {
  const stats = join(work, 'limit.json');
  const r = run('mesh', join(root, 'examples/models/thin_wedge.off'), '-o', join(work, 'limit.mesh'),
                '--stats', stats, '--max-vertices', '40', '--quiet');
  assert.equal(r.status, 3, r.stderr);
  assert.equal(JSON.parse(readFileSync(stats, 'utf8')).stopped, 'limit');
});

test('a vertex limit below what INITIALIZE inserts exits 3 before meshing', { skip }, () => {
  const r = run('mesh', join(root, 'examples/models/thin_wedge.off'), '-o', join(work, 'refused.mesh'),
                '--max-vertices', '20');
  assert.equal(r.status, 3, r.stderr);
  assert.match(r.stderr, /INITIALIZE alone inserts \d+ vertices/);
});

test('usage errors exit 1', { skip }, () => {
  assert.equal(run().status, 1);
  assert.equal(run('frobnicate').status, 1);
  assert.equal(run('mesh', spike, '-o', join(work, 'x.obj')).status, 1);
  assert.equal(run('mesh', spike).status, 1);
  assert.equal(run('mesh', spike, '-o', join(work, 'x.mesh'), '--rho', 'abc').status, 1);
  assert.equal(run('check').status, 1);
  assert.equal(run('--help').status, 0);
});
