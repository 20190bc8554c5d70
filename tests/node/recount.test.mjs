// wqmesh: the classes of a run are recountable from what it hands out
// (issue 14, item 3). (1) The JavaScript result: its tetClass, radiusEdge
// and stats equal a recount in plain JavaScript from its vertices, tets and
// protectingBalls by the definition of core/src/mesher/classify.h (R/l
// unweighted; near: circumcenter on or inside a ball (c, r), or a vertex v
// with |v - c|^2 <= (2r)^2 + L_v^2/9, L_v the shortest mesh edge at v).
// (2) `wqmesh measure MESH --stats STATS` (native) recounts the same classes
// from the written files, and tells when the statistics do not fit the mesh.
// A decision within rounding (1e-9 relative) of its threshold counts as
// ambiguous and may go either way.
// Run: node --test tests/node/recount.test.mjs
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { cli, loadModule, root, skipCli, workDir } from './lib/setup.mjs';

const wqmesh = await loadModule();
const work = workDir('recount');
const TOL = 1e-9;

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
/** -1 below, +1 above, 0 within tol. */
const side = (x, t, tol) => (Math.abs(x - t) <= tol ? 0 : x > t ? 1 : -1);

/** The classes (0 good, 1 skinny near, 2 sliver near, 3 violation; -1 ambiguous) of every tet. */
function recount(r, rho0, theta) {
  const V = r.vertices, T = r.tets, B = r.protectingBalls;
  const pt = (v) => [V[3 * v], V[3 * v + 1], V[3 * v + 2]];
  const nt = T.length / 4;
  const L2 = new Float64Array(V.length / 3).fill(Infinity);
  for (let t = 0; t < nt; ++t)
    for (let i = 0; i < 4; ++i)
      for (let j = i + 1; j < 4; ++j) {
        const a = T[4 * t + i], b = T[4 * t + j], d = sub(pt(a), pt(b)), l2 = dot(d, d);
        if (l2 < L2[a]) L2[a] = l2;
        if (l2 < L2[b]) L2[b] = l2;
      }
  const classes = new Int8Array(nt);
  const ratios = new Float64Array(nt);
  for (let t = 0; t < nt; ++t) {
    const ids = [0, 1, 2, 3].map((k) => T[4 * t + k]);
    const p = ids.map(pt);
    const u = sub(p[1], p[0]), v = sub(p[2], p[0]), w = sub(p[3], p[0]);
    const vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
    const den = 2 * dot(u, vw);
    const off = [0, 1, 2].map((k) => (dot(u, u) * vw[k] + dot(v, v) * wu[k] + dot(w, w) * uv[k]) / den);
    const z = off.map((x, k) => x + p[0][k]);
    let l = Infinity, lmax = 0;
    for (let i = 0; i < 4; ++i)
      for (let j = i + 1; j < 4; ++j) {
        const e = Math.hypot(...sub(p[i], p[j]));
        l = Math.min(l, e);
        lmax = Math.max(lmax, e);
      }
    const R = Math.hypot(...off);
    const rho = den === 0 ? Infinity : R / l;
    // The relative rounding of the circumcenter: a flat tet (four points
    // cocircular to rounding) has none defined, and its R/l is whatever
    // rounding makes it.
    const rel = Math.max(TOL, den === 0 ? Infinity : (64 * Number.EPSILON * lmax ** 3) / Math.abs(den / 2));
    ratios[t] = rho;
    let minDih = 180;
    for (let i = 0; i < 4; ++i)
      for (let j = i + 1; j < 4; ++j) {
        const [k, o] = [0, 1, 2, 3].filter((m) => m !== i && m !== j);
        const e = sub(p[j], p[i]), n1 = cross(e, sub(p[k], p[i])), n2 = cross(e, sub(p[o], p[i]));
        const a = Math.sqrt(dot(n1, n1) * dot(n2, n2));
        const c = a === 0 ? 1 : Math.max(-1, Math.min(1, dot(n1, n2) / a));
        minDih = Math.min(minDih, (Math.acos(c) * 180) / Math.PI);
      }
    const sRho = side(rho, rho0, rel * rho0), sTheta = side(minDih, theta, TOL * Math.max(1, theta));
    const skinny = sRho > 0, sliver = !skinny && sTheta < 0;
    // Bad for sure: a dihedral angle surely below theta or R/l surely above rho0.
    let unsure = !(sTheta < 0 || sRho > 0 || (sRho < 0 && sTheta > 0));
    if (!skinny && !sliver) {
      classes[t] = unsure ? -1 : 0;
      continue;
    }
    const splitUnsure = sRho === 0;
    let near = false, nearUnsure = false;
    for (let b = 0; b < B.length / 4; ++b) {
      const c = [B[4 * b], B[4 * b + 1], B[4 * b + 2]], r2 = B[4 * b + 3] ** 2;
      if (Number.isFinite(rho)) {
        const d = sub(z, c), d2 = dot(d, d);
        const s = side(d2, r2, TOL * (r2 + d2) + 4 * rel * R * (Math.sqrt(d2) + R));
        near ||= s < 0;
        nearUnsure ||= s === 0;
      }
      for (let k = 0; k < 4; ++k) {
        const d = sub(p[k], c), d2 = dot(d, d), bound = 4 * r2 + L2[ids[k]] / 9;
        const s = side(d2, bound, TOL * (bound + d2));
        near ||= s < 0;
        nearUnsure ||= s === 0;
      }
    }
    unsure ||= !near && nearUnsure;
    // -2: near or not is sure, skinny against sliver is not (1 or 2 both fit).
    classes[t] = unsure ? -1 : !near ? 3 : splitUnsure ? -2 : skinny ? 1 : 2;
  }
  return { classes, ratios };
}

const shared = join(root, '../shared/models');
const models = ['box.off', 'thin_wedge.off', 'spike.off', 'slit.off', 'bracket.off', 'edge_facet.off']
  .map((m) => join(root, 'examples/models', m))
  .concat(['20mm-xyz-cube.stl', 'slit-1.off'].map((m) => join(shared, m)).filter((m) => existsSync(m)));

test('the JavaScript result\'s classes and counts equal a recount from its vertices, tets and balls', async () => {
  let near = 0;
  for (const model of models) {
    const r = await wqmesh.mesh(readFileSync(model));
    const s = r.stats;
    const { classes, ratios } = recount(r, s.options.rho0, s.options.theta_deg);
    let ambiguous = 0;
    const counts = [0, 0, 0, 0];
    for (let t = 0; t < classes.length; ++t) {
      if (classes[t] === -1) { ++ambiguous; continue; }
      if (classes[t] === -2) {
        ++counts[1];  // near: skinny or sliver
        assert.ok(r.tetClass[t] === 1 || r.tetClass[t] === 2, `${model}: tet ${t} is near, class ${r.tetClass[t]}`);
        continue;
      }
      ++counts[classes[t]];
      assert.equal(r.tetClass[t], classes[t], `${model}: tet ${t}`);
      if (classes[t] !== 0) assert.ok(Math.abs(r.radiusEdge[t] - ratios[t]) <= 1e-6 * ratios[t], `${model}: R/l of tet ${t}`);
    }
    const within = (a, b, what) => assert.ok(Math.abs(a - b) <= ambiguous, `${model}: ${what}: stats ${a}, recount ${b}`);
    within(s.near_small_angle, counts[1] + counts[2], 'near_small_angle');
    within(s.violations, counts[3], 'violations');
    within(s.skinny + s.slivers, counts[1] + counts[2] + counts[3], 'skinny + slivers');
    assert.equal(s.near_small_angle_share, s.tets ? s.near_small_angle / s.tets : 0);
    assert.ok(ambiguous <= 1 + classes.length / 1000, `${model}: ${ambiguous} ambiguous tets`);
    assert.equal(r.orthoradiusEdge.length, s.tets);
    const bins = s.orthoradius_edge_bins;
    assert.equal(bins['<0.6'] + bins['0.6-1.4'] + bins['1.4-2.2'] + bins['>2.2'], s.tets);
    near += counts[1] + counts[2];
  }
  assert.ok(near > 0, 'the models have tets near small angles to recount');
});

test('wqmesh measure --stats recounts the classes of the written mesh', { skip: skipCli }, () => {
  for (const model of models) {
    const mesh = join(work, 'm.mesh'), stats = join(work, 'm.json');
    const m = spawnSync(cli, ['mesh', model, '-o', mesh, '--stats', stats, '--quiet'], { encoding: 'utf8' });
    assert.equal(m.status, 0, m.stderr);
    const s = JSON.parse(readFileSync(stats, 'utf8'));
    const r = spawnSync(cli, ['measure', mesh, '--stats', stats, '--json'], { encoding: 'utf8' });
    assert.equal(r.status, 0, r.stderr);
    const out = JSON.parse(r.stdout);
    for (const k of ['skinny', 'slivers', 'near_small_angle', 'violations']) assert.equal(out.classes[k], s[k], `${model}: ${k}`);
    assert.equal(out.classes_match_stats, true);
  }
  // Statistics that do not fit the mesh: without the balls nothing is near.
  const mesh = join(work, 'w.mesh'), stats = join(work, 'w.json');
  assert.equal(spawnSync(cli, ['mesh', join(root, 'examples/models/thin_wedge.off'), '-o', mesh, '--stats', stats, '--quiet']).status, 0);
  const s = JSON.parse(readFileSync(stats, 'utf8'));
  assert.ok(s.near_small_angle > 0);
  writeFileSync(join(work, 'noballs.json'), JSON.stringify({ ...s, protecting_balls: [] }));
  const r = spawnSync(cli, ['measure', mesh, '--stats', join(work, 'noballs.json'), '--json'], { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  const out = JSON.parse(r.stdout);
  assert.equal(out.classes.near_small_angle, 0);
  assert.equal(out.classes.violations, s.skinny + s.slivers);
  assert.equal(out.classes_match_stats, false);
  // Unreadable statistics exit 2, naming the file and the defect.
  writeFileSync(join(work, 'bad.json'), '{"options": {"rho0": 2.2}');
  const bad = spawnSync(cli, ['measure', mesh, '--stats', join(work, 'bad.json')], { encoding: 'utf8' });
  assert.equal(bad.status, 2);
  assert.match(bad.stderr, /syntax: .*bad\.json: JSON: at byte \d+/);
  writeFileSync(join(work, 'keys.json'), '{"options": {"rho0": 2.2, "theta_deg": 3}}');
  const keys = spawnSync(cli, ['measure', mesh, '--stats', join(work, 'keys.json')], { encoding: 'utf8' });
  assert.equal(keys.status, 2);
  assert.match(keys.stderr, /keys\.json: not the statistics of `wqmesh mesh`: no valid "skinny"/);
  assert.equal(spawnSync(cli, ['measure', mesh, '--stats']).status, 1);
});
