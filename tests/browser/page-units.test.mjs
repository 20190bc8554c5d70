// wqmesh: Node tests of the page's pure modules (web/params.mjs,
// web/surface.mjs, web/tetfaces.mjs): the URL state round trip and its
// validation, the page's own reading of sharp elements against the core's
// check report (examples/models, where both must agree), the face-to-tet
// table and the whole-tet extraction on a structured grid and on a real
// mesh of the package. No browser needed.
// Run: node --test tests/browser/
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';

import { RUN_PARAMS, defaultState, queryFromState, stateFromQuery } from '../../web/params.mjs';
import { inputEdges, locate, readSurface } from '../../web/surface.mjs';
import { extract, gridMesh, neighbours, TET_FACES, worstTets, dihedralHistogram } from '../../web/tetfaces.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const examples = join(root, 'examples/models');

test('URL state: round trip, defaults left out, bad values fall back to the default', () => {
  const s = { ...defaultState(), example: 'spike.off', rho: 3, pump: false, maxSize: 0.25, cut: 0.3, rest: 'fade' };
  const q = queryFromState(s);
  assert.deepEqual(stateFromQuery(q), s);
  assert.equal(queryFromState(defaultState()), '');
  const bad = stateFromQuery('?rho=0.5&sliverAngle=abc&maxVertices=1e12&rest=purple&example=../x.off&pump=maybe');
  for (const p of RUN_PARAMS) assert.equal(bad[p.key], p.def, p.key);
  assert.equal(bad.rest, 'show');
  assert.equal(bad.example, '');
});

test('the input edges the page draws are the core\'s PLC edges, and the report carries the sharp elements\' coordinates (examples/models)', async () => {
  const pkg = await import('../../wasm/index.mjs');
  await pkg.ready();
  for (const name of readdirSync(examples).filter((f) => f.endsWith('.off'))) {
    const bytes = readFileSync(join(examples, name));
    const r = pkg.checkSync(bytes);
    const f = inputEdges(readSurface(bytes));
    assert.equal(f.edges.length, r.plc.edges, `${name}: input edges`);
    // What the page draws for the sharp elements (web/view-worker.mjs).
    assert.equal(r.plc.sharp_vertex_points.length, r.analysis.counts.sharp_vertices, `${name}: sharp vertex points`);
    assert.equal(r.plc.sharp_edge_points.length, r.analysis.counts.sharp_edges, `${name}: sharp edge points`);
    // Every sharp point is an input point of the file.
    const P = readSurface(bytes).points;
    const isInput = (p) => { for (let i = 0; i < P.length; i += 3) if (P[i] === p[0] && P[i + 1] === p[1] && P[i + 2] === p[2]) return true; return false; };
    for (const p of [...r.plc.sharp_vertex_points, ...r.plc.sharp_edge_points.flat()]) assert.ok(isInput(p), `${name}: ${p} is not an input point`);
  }
});

test('locate() finds the faces, the edge and the points an error message names', () => {
  const w = locate('non-manifold edge from vertex 6 (1, 1, 1) to vertex 7 (1, 1, 0): it is in 4 faces: face 6 (line 24), face 8 (line 26)');
  assert.deepEqual(w.faces, [6, 8]);
  assert.deepEqual(w.edge, [[1, 1, 1], [1, 1, 0]]);
  assert.deepEqual(locate('face 192 (line 1346) and face 53 (line 373) meet away from their common vertex (6.24057, -1.568279, 6.4e-3)').points,
                   [[6.24057, -1.568279, 0.0064]]);
});

/** Signed volume x 6 of tet t. */
function vol6(V, T, t) {
  const p = [0, 1, 2, 3].map((k) => [0, 1, 2].map((c) => V[3 * T[4 * t + k] + c]));
  const a = p[1].map((x, c) => x - p[0][c]), b = p[2].map((x, c) => x - p[0][c]), d = p[3].map((x, c) => x - p[0][c]);
  return a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) + a[2] * (b[0] * d[1] - b[1] * d[0]);
}

/** Checks extract() against a direct count: drawn faces = faces of kept tets whose neighbour is not kept. */
function checkExtract(mesh, view) {
  const x = extract(mesh, view);
  const { vertices: V, tets: T, nb } = mesh;
  const nt = T.length / 4;
  const kept = (t) => {
    if (view.rest === 'hide' && !(mesh.tetClass[t] !== 0 || mesh.minDihedral[t] < view.bound)) return false;
    let s = 0;
    for (let k = 0; k < 4; ++k) for (let c = 0; c < 3; ++c) s += V[3 * T[4 * t + k] + c] * view.normal[c];
    return !view.clip || s / 4 <= view.offset;
  };
  const hi = (t) => mesh.tetClass[t] !== 0 || mesh.minDihedral[t] < view.bound;
  let keptCount = 0, faces = 0;
  for (let t = 0; t < nt; ++t) {
    if (!kept(t)) continue;
    ++keptCount;
    for (let i = 0; i < 4; ++i) {
      const u = nb[4 * t + i];
      if (u < 0 || !kept(u)) ++faces;
      // Faded: the highlighted tets inside show through the plain ones.
      else if (view.rest === 'fade' && hi(t) && !hi(u)) ++faces;
    }
  }
  assert.equal(x.keptTets, keptCount);
  assert.equal(x.index.length / 3, faces);
  assert.equal(x.positions.length, 12 * x.drawnTets);
  // Every drawn face is oriented out of its tet: its normal points away from the tet's fourth corner.
  for (let f = 0; f < Math.min(faces, 2000); ++f) {
    const [a, b, c] = [0, 1, 2].map((j) => x.index[3 * f + j]);
    const base = a - (a % 4);
    const d = [0, 1, 2, 3].map((k) => base + k).find((v) => v !== a && v !== b && v !== c);
    const P = (v) => [0, 1, 2].map((k) => x.positions[3 * v + k]);
    const u = P(b).map((y, k) => y - P(a)[k]), w = P(c).map((y, k) => y - P(a)[k]), e = P(d).map((y, k) => y - P(a)[k]);
    const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
    // (Slivers are flat to float precision: their sign is noise.)
    const dot = n[0] * e[0] + n[1] * e[1] + n[2] * e[2];
    if (Math.abs(dot) > 1e-4 * Math.hypot(...n) * Math.hypot(...e)) {
      assert.ok(dot < 0, `face ${f} points into its tet (${JSON.stringify(view)})`);
    }
  }
  return x;
}

test('grid mesh: positive tets, the face table pairs every inner face, whole-tet clipping', () => {
  const n = 6;
  const m = gridMesh(n);
  const nt = m.tets.length / 4;
  assert.equal(nt, 6 * n ** 3);
  for (let t = 0; t < nt; ++t) assert.ok(vol6(m.vertices, m.tets, t) > 0, `tet ${t} positive`);
  const nb = neighbours(m.tets);
  let boundary = 0;
  for (let t = 0; t < nt; ++t) {
    for (let i = 0; i < 4; ++i) {
      const u = nb[4 * t + i];
      if (u < 0) { ++boundary; continue; }
      assert.ok([0, 1, 2, 3].some((j) => nb[4 * u + j] === t), 'neighbours are mutual');
    }
  }
  assert.equal(boundary, 12 * n * n, 'two triangles per boundary square');
  const mesh = { ...m, nb };
  const all = checkExtract(mesh, { clip: false, normal: [1, 0, 0], offset: 0, bound: 0, rest: 'show', shrunk: false });
  assert.equal(all.index.length / 3, 12 * n * n);
  for (const cut of [0.5, 2.5, 5.9]) checkExtract(mesh, { clip: true, normal: [1, 0, 0], offset: cut, bound: 0, rest: 'show' });
  checkExtract(mesh, { clip: true, normal: [0, 0, -1], offset: -2, bound: 30, rest: 'hide' });
  const s = extract(mesh, { clip: true, normal: [0, 1, 0], offset: 3, bound: 0, rest: 'show', shrunk: true });
  assert.equal(s.index.length / 3, 4 * s.drawnTets, 'shrunk: every face of every drawn tet');
});

test('a real mesh of the package: extraction, worst tets, histogram', async () => {
  const pkg = await import('../../wasm/index.mjs');
  await pkg.ready();
  const r = pkg.meshSync(readFileSync(join(examples, 'spike.off')), { maxSize: 0.4 });
  const mesh = { ...r, nb: neighbours(r.tets) };
  let boundary = 0;
  for (const x of mesh.nb) if (x < 0) ++boundary;
  assert.equal(boundary, r.boundary.length / 3, `the unpaired faces are the boundary triangles (${r.tets.length / 4} tets)`);
  for (const cut of [0.2, 0.5, 0.8]) checkExtract(mesh, { clip: true, normal: [0, 0, 1], offset: cut, bound: 20, rest: 'show' });
  checkExtract(mesh, { clip: false, normal: [1, 0, 0], offset: 0, bound: 20, rest: 'fade' });
  const worst = worstTets(r.minDihedral, 5);
  assert.equal(worst[0].minDihedral, Math.min(...r.minDihedral));
  for (let i = 1; i < worst.length; ++i) assert.ok(worst[i - 1].minDihedral <= worst[i].minDihedral);
  const h = dihedralHistogram(r.minDihedral);
  assert.equal(h.counts.reduce((a, b) => a + b, 0), r.tets.length / 4);
  assert.equal(TET_FACES.length, 4);
});
