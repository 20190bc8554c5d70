// wqmesh: the command line (glibc's libm) and the wasm module (the wasm libc's)
// give the same mesh bit for bit, vertices and tets, on models with shield
// arcs where they once differed: thin_wedge.off, wedge.off and part.off (the
// SOS points were placed with std::cos and std::sin and their arcs chosen by
// std::atan2, which round differently in the two libraries; now with +, -,
// *, / and sqrt only: Sector in core/src/mesher/domain.cpp). The models of
// ../shared/models are skipped when it is absent. WQMESH_CLI and
// WQMESH_MODULE (the path of wqmesh.mjs) choose other builds than
// build/native and build/wasm (as in scale.test.mjs).
// Run: node --test tests/node/identity.test.mjs
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { cli, loadModule, root, skipCli, workDir } from './lib/setup.mjs';

const wqmesh = await loadModule({ build: true });
const work = workDir('identity');

/** The vertices (x, y, z each) and 0-based tets of a Medit file the command line wrote. */
function medit(path) {
  const t = readFileSync(path, 'utf8').split(/\s+/).filter((x) => x.length > 0);
  let i = t.indexOf('Vertices');
  const vertices = [];
  for (let k = 0, n = Number(t[i + 1]); k < n; ++k) for (let c = 0; c < 3; ++c) vertices.push(Number(t[i + 2 + 4 * k + c]));
  i = t.indexOf('Tetrahedra');
  const tets = [];
  for (let k = 0, n = Number(t[i + 1]); k < n; ++k) for (let c = 0; c < 4; ++c) tets.push(Number(t[i + 2 + 5 * k + c]) - 1);
  return { vertices, tets };
}

const models = [
  join(root, 'examples/models/thin_wedge.off'),
  join(root, '../shared/models/wedge.off'),
  join(root, '../shared/models/part.off'),
];

for (const file of models) {
  const name = file.slice(file.lastIndexOf('/') + 1);
  test(`${name}: the same vertices bit for bit and the same tets, native and wasm`,
       { skip: skipCli || (!existsSync(file) && `${file} is absent`) }, () => {
    const out = join(work, `${name}.mesh`);
    const c = spawnSync(cli, ['mesh', file, '-o', out, '--quiet'], { encoding: 'utf8', timeout: 300_000 });
    assert.equal(c.status, 0, c.stderr);
    const n = medit(out);
    const w = wqmesh.mesh(readFileSync(file));
    assert.ok(w.stats.conforming, `${name}: the wasm mesh conforms`);
    const v = Array.from(w.vertices);
    assert.equal(v.length, n.vertices.length, `${name}: vertex count, native vs wasm`);
    const first = v.findIndex((x, k) => !Object.is(x, n.vertices[k]));
    assert.equal(first, -1, `${name}: vertex ${Math.floor(first / 3)} differs, native ${n.vertices.slice(first - first % 3, first - first % 3 + 3)} vs wasm ${v.slice(first - first % 3, first - first % 3 + 3)}`);
    assert.deepEqual(Array.from(w.tets), n.tets, `${name}: tets, native vs wasm`);
  });
}
