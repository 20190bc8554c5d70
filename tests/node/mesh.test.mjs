// wqmesh: meshing through the wasm module (wasm/index.mjs) against the native
// command line (`wqmesh mesh`): on the example models both must conform,
// recover the input volume, agree on the counts (native and wasm may differ by
// a few tets, so vertex and tet counts within 5%), label every tet, report
// progress, and stop when cancelled. Bad input and options throw errors with a
// kind.
// Run: node --test tests/node/
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { tetVolumes } from './lib/tets.mjs';
import { cli, loadModule, root, workDir } from './lib/setup.mjs';

const wqmesh = await loadModule();
const work = workDir('node');

function nativeStats(model) {
  const stats = join(work, 'stats.json');
  const r = spawnSync(cli, ['mesh', model, '-o', join(work, 'out.mesh'), '--stats', stats, '--quiet'],
                      { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  return JSON.parse(readFileSync(stats, 'utf8'));
}

function signedVolume(v, t) {
  const { total, firstBad } = tetVolumes(v, t);
  assert.equal(firstBad, -1, `tet ${firstBad} is not positively oriented`);
  return total;
}

for (const name of ['box.off', 'thin_wedge.off', 'spike.off', 'slit.off', 'bracket.off', 'edge_facet.off']) {
  test(`wasm mesh of ${name} conforms and agrees with the native build`, () => {
    const model = join(root, 'examples/models', name);
    let calls = 0;
    const r = wqmesh.mesh(readFileSync(model), { onProgress: (phase, fraction, vertices) => {
      assert.equal(typeof phase, 'string');
      assert.ok(fraction >= 0 && fraction <= 1);
      assert.ok(vertices >= 0);
      ++calls;
      return true;
    } });
    const s = r.stats;
    assert.equal(s.conforming, true);
    assert.equal(s.stopped, '');
    assert.ok(calls >= 3, 'progress is reported at each phase');
    assert.equal(r.vertices.length, 3 * s.vertices);
    assert.equal(r.tets.length, 4 * s.tets);
    assert.equal(r.tetClass.length, s.tets);
    assert.equal(r.minDihedral.length, s.tets);
    assert.equal(r.boundary.length / 3, r.boundaryFacet.length);
    const volume = signedVolume(r.vertices, r.tets);
    assert.ok(Math.abs(volume - s.volume_input) <= 1e-9 * s.volume_input, `volume ${volume} vs ${s.volume_input}`);
    const violations = r.tetClass.filter((c) => c === 3).length;
    assert.equal(violations, s.violations);
    assert.equal(s.violation_tets.length, Math.min(s.violations, 1000));
    for (const v of s.violation_tets) assert.equal(r.tetClass[v.tet], 3, `violation_tets names tet ${v.tet}`);
    // The comparison is the point of the test: no native build is a failure.
    assert.ok(existsSync(cli), `the native command line is missing (${cli}): build it or set WQMESH_CLI`);
    const n = nativeStats(model);
    assert.ok(Math.abs(n.vertices - s.vertices) <= 0.05 * n.vertices, `vertices ${s.vertices} vs native ${n.vertices}`);
    assert.ok(Math.abs(n.tets - s.tets) <= 0.05 * n.tets, `tets ${s.tets} vs native ${n.tets}`);
    assert.equal(s.input_points, n.input_points);
    assert.equal(s.sharp_elements, n.sharp_elements);
  });
}

test('a cancelled wasm run says so', () => {
  const r = wqmesh.mesh(readFileSync(join(root, 'examples/models/thin_wedge.off')), { onProgress: () => false });
  assert.equal(r.stats.stopped, 'cancelled');
});

test('the vertex limit stops a wasm run', () => {
  const r = wqmesh.mesh(readFileSync(join(root, 'examples/models/thin_wedge.off')), { maxVertices: 60 });
  assert.equal(r.stats.stopped, 'limit');
});

test('a vertex limit below what INITIALIZE inserts is refused before meshing', () => {
  const r = wqmesh.mesh(readFileSync(join(root, 'examples/models/thin_wedge.off')), { maxVertices: 20 });
  assert.equal(r.stats.stopped, 'limit');
  assert.match(r.stats.stop_message, /INITIALIZE alone inserts \d+ vertices/);
  assert.equal(r.stats.vertices, 0);
  assert.equal(r.stats.tets, 0);
});

test('bad input and bad options throw errors with a kind', () => {
  assert.throws(() => wqmesh.mesh(new Uint8Array([1, 2, 3])), (e) => e.kind === 'truncated');
  assert.throws(() => wqmesh.mesh(new TextEncoder().encode('OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n')),
                (e) => typeof e.kind === 'string' && e.kind.length > 0);
  const box = readFileSync(join(root, 'examples/models/box.off'));
  assert.throws(() => wqmesh.mesh(box, { rho: 0.5 }), (e) => e.kind === 'options');
  assert.throws(() => wqmesh.mesh(box, { sliverAngle: 120 }), (e) => e.kind === 'options');
});
