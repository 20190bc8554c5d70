// wqmesh: examples/node/hard_inputs.mjs writes the same models for a seed, its
// smooth family (finely tessellated spheres, cylinders, tori, cut capsules)
// leaves the other families' models of a seed unchanged, and each smooth model
// is a closed, consistently and outward oriented 2-manifold of non-degenerate
// triangles (checked here from the OFF text), which `wqmesh check` accepts
// (skipped when the native build is missing).
// Run: node --test tests/node/hard_inputs.test.mjs
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { cli, root, skipCli, workDir } from './lib/setup.mjs';

const script = join(root, 'examples/node/hard_inputs.mjs');
const work = workDir('hard-inputs');
const smoothName = /^(sphere|cylinder|torus|capsule)-\d+\.off$/;

/** Runs the generator into work/NAME; the folder's OFF files by name. */
function generate(name, ...args) {
  const out = join(work, name);
  const r = spawnSync(process.execPath, [script, '--out', out, ...args], { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  const files = new Map();
  for (const f of readdirSync(out)) if (f.endsWith('.off')) files.set(f, readFileSync(join(out, f), 'utf8'));
  return files;
}

/** Points and faces of an OFF text (comments skipped). */
function parseOff(text) {
  const tok = text
    .split('\n')
    .filter((l) => !l.startsWith('#'))
    .join(' ')
    .split(/\s+/)
    .filter((s) => s.length);
  assert.equal(tok[0], 'OFF');
  const nv = Number(tok[1]);
  const nf = Number(tok[2]);
  let i = 4;
  const points = [];
  for (let k = 0; k < nv; ++k, i += 3) points.push([Number(tok[i]), Number(tok[i + 1]), Number(tok[i + 2])]);
  const faces = [];
  for (let k = 0; k < nf; ++k) {
    const n = Number(tok[i++]);
    faces.push(tok.slice(i, i + n).map(Number));
    i += n;
  }
  return { points, faces };
}

test('the smooth family leaves the other models of a seed as they were', () => {
  const without = generate('without', '--count', '12', '--seed', '15', '--smooth', '0');
  const withSmooth = generate('with', '--count', '12', '--seed', '15', '--smooth', '8');
  const again = generate('again', '--count', '12', '--seed', '15', '--smooth', '8');
  const smooth = [...withSmooth.keys()].filter((f) => smoothName.test(f));
  assert.equal(smooth.length, 8);
  assert.equal([...without.keys()].filter((f) => smoothName.test(f)).length, 0);
  for (const [f, text] of without) assert.equal(withSmooth.get(f), text, `${f} changed with --smooth 8`);
  assert.equal(withSmooth.size, without.size + 8);
  for (const [f, text] of withSmooth) assert.equal(again.get(f), text, `${f} differs between two runs`);
});

test('every smooth model is a closed, outward oriented 2-manifold of triangles', () => {
  const files = generate('manifold', '--count', '1', '--seed', '3', '--smooth', '12');
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  for (const [f, text] of files) {
    if (!smoothName.test(f)) continue;
    const { points, faces } = parseOff(text);
    const directed = new Set();
    let volume = 0;
    for (const t of faces) {
      assert.equal(t.length, 3, `${f}: a face of ${t.length} corners`);
      const n = cross(sub(points[t[1]], points[t[0]]), sub(points[t[2]], points[t[0]]));
      assert.ok(Math.hypot(...n) > 0, `${f}: a triangle of zero area`);
      // The divergence theorem about the first point (small terms for far models).
      const o = points[0];
      const [a, b, c] = t.map((v) => sub(points[v], o));
      const abc = cross(b, c);
      volume += (a[0] * abc[0] + a[1] * abc[1] + a[2] * abc[2]) / 6;
      for (let e = 0; e < 3; ++e) {
        const k = `${t[e]},${t[(e + 1) % 3]}`;
        assert.ok(!directed.has(k), `${f}: edge ${k} twice in one direction`);
        directed.add(k);
      }
    }
    for (const k of directed) {
      const [a, b] = k.split(',');
      assert.ok(directed.has(`${b},${a}`), `${f}: edge ${k} has no twin`);
    }
    assert.ok(volume > 0, `${f}: faces oriented inward (volume ${volume})`);
  }
});

test('wqmesh check accepts every smooth model', { skip: skipCli }, () => {
  const files = generate('check', '--count', '1', '--seed', '5', '--smooth', '8');
  for (const f of files.keys()) {
    if (!smoothName.test(f)) continue;
    const r = spawnSync(cli, ['check', join(work, 'check', f)], { encoding: 'utf8', maxBuffer: 1 << 28 });
    assert.equal(r.status, 0, `${f}: ${r.stderr}`);
    assert.equal(JSON.parse(r.stdout).valid, true, f);
  }
});
