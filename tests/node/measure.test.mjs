// wqmesh: the contract of `wqmesh measure` (the benchmark's common measure):
// usage errors exit 1, unreadable meshes and invalid inputs exit 2 with the
// reason on stderr, and meshes written by `wqmesh mesh` in Medit and TetGen
// form measure the same, with the volume of the input.
// Skipped when the native build is missing.
// Run: node --test tests/node/
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { cli, root, skipCli, workDir } from './lib/setup.mjs';

const skip = skipCli;
const work = workDir('measure');
const spike = join(root, 'examples/models/spike.off');
const run = (...args) => spawnSync(cli, args, { encoding: 'utf8' });

const KEYS = ['mesh', 'format', 'vertices', 'file_vertices', 'tets', 'orientation_flipped', 'inverted',
  'min_dihedral_deg', 'max_dihedral_deg', 'dihedral_below_3', 'dihedral_below_5', 'dihedral_below_10',
  'radius_edge_above_2_2', 'max_radius_edge', 'slivers', 'volume_mesh', 'volume_input', 'relative_volume_error'];

test('measure usage errors exit 1 with the usage', { skip }, () => {
  for (const args of [
    ['measure'],                                    // no mesh
    ['measure', 'a.mesh', 'b.mesh'],                // two meshes
    ['measure', 'a.mesh', '--frob'],                // unknown option
    ['measure', 'a.mesh', '--input'],               // --input without its file
    ['measure', 'a.mesh', '--input', '--json'],     // --input followed by an option
  ]) {
    const r = run(...args);
    assert.equal(r.status, 1, `${args.join(' ')}: ${r.stderr}`);
    assert.match(r.stderr, /usage: wqmesh/);
    assert.match(r.stderr, /measure MESH/);
  }
});

test('unreadable meshes and invalid inputs exit 2 with the reason', { skip }, () => {
  const missing = run('measure', join(work, 'missing.mesh'));
  assert.equal(missing.status, 2);
  assert.match(missing.stderr, /io: .*missing\.mesh/);

  const unknown = join(work, 'mesh.vtu');
  writeFileSync(unknown, '<VTKFile/>');
  assert.match(run('measure', unknown).stderr, /unknown mesh format/);

  const garbled = join(work, 'garbled.mesh');
  writeFileSync(garbled, 'MeshVersionFormatted 2\nDimension 3\nVertices 1\n0 0 zero 0\n');
  const g = run('measure', garbled);
  assert.equal(g.status, 2);
  assert.match(g.stderr, /syntax: .*garbled\.mesh: line 4/);

  const badIndex = join(work, 'bad.mesh');
  writeFileSync(badIndex, 'Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra 1\n1 2 3 9 1\nEnd\n');
  const b = run('measure', badIndex);
  assert.equal(b.status, 2);
  assert.match(b.stderr, /bad_index: .*line 7/);

  const open = join(work, 'open.off');
  writeFileSync(open, 'OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n');
  const tet = join(work, 'tet.mesh');
  writeFileSync(tet, 'Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra 1\n1 2 3 4 1\nEnd\n');
  const o = run('measure', tet, '--input', open);
  assert.equal(o.status, 2);
  assert.match(o.stderr, /open_boundary/);
});

test('Medit and TetGen files of one mesh measure the same', { skip }, () => {
  const stats = join(work, 'spike.json');
  assert.equal(run('mesh', spike, '-o', join(work, 'spike.mesh'), '--stats', stats, '--quiet').status, 0);
  assert.equal(run('mesh', spike, '-o', join(work, 'spike.ele'), '--quiet').status, 0);
  const s = JSON.parse(readFileSync(stats, 'utf8'));
  const measured = [join(work, 'spike.mesh'), join(work, 'spike.ele'), join(work, 'spike.node')].map((m) => {
    const r = run('measure', m, '--input', spike, '--json');
    assert.equal(r.status, 0, r.stderr);
    return JSON.parse(r.stdout);
  });
  for (const m of measured) {
    for (const k of KEYS) assert.ok(k in m, `key ${k}`);
    assert.equal(m.tets, s.tets);
    assert.equal(m.vertices, s.vertices);
    assert.equal(m.orientation_flipped, false);
    assert.equal(m.inverted, 0);
    assert.ok(m.dihedral_below_3 <= m.dihedral_below_5 && m.dihedral_below_5 <= m.dihedral_below_10);
    assert.ok(m.relative_volume_error < 1e-9, String(m.relative_volume_error));
    assert.equal(m.volume_input, s.volume_input);
  }
  assert.equal(measured[0].format, 'medit');
  assert.equal(measured[1].format, 'tetgen');
  const { mesh: _a, format: _b, ...medit } = measured[0];
  const { mesh: _c, format: _d, ...tetgen } = measured[1];
  assert.deepEqual(medit, tetgen);

  // Without --input: no volume error; the text form names the same counts.
  const plain = run('measure', join(work, 'spike.mesh'));
  assert.equal(plain.status, 0, plain.stderr);
  assert.match(plain.stdout, new RegExp(`tets\\s+${s.tets}\\b`));
  assert.doesNotMatch(plain.stdout, /relative volume error/);
  const noInput = JSON.parse(run('measure', join(work, 'spike.mesh'), '--json').stdout);
  assert.equal(noInput.relative_volume_error, null);
});

test('tets in the other orientation are flipped by majority', { skip }, () => {
  const neg = join(work, 'neg.mesh');
  writeFileSync(neg, 'Vertices 5\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n1 1 1 0\n' +
    'Tetrahedra 2\n1 3 2 4 1\n2 3 4 5 1\nEnd\n');
  const m = JSON.parse(run('measure', neg, '--json').stdout);
  assert.equal(m.tets, 2);
  // 1 3 2 4 is negative, 2 3 4 5 positive: a tie keeps the file's order.
  assert.equal(m.orientation_flipped, false);
  assert.equal(m.inverted, 1);
  const neg2 = join(work, 'neg2.mesh');
  writeFileSync(neg2, 'Vertices 4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra 1\n1 3 2 4 1\nEnd\n');
  const m2 = JSON.parse(run('measure', neg2, '--json').stdout);
  assert.equal(m2.orientation_flipped, true);
  assert.equal(m2.inverted, 0);
  assert.ok(Math.abs(m2.volume_mesh - 1 / 6) < 1e-15);
});
