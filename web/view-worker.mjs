// wqmesh page: the view worker. Holds the mesh of the last run (its arrays
// are transferred here, not copied), builds the face-to-tet table once, and
// answers the page's requests, so that no long task runs on the main thread:
//   surface  -> the input preview (triangles, input edges, the sharp edges
//               and vertices at the check report's coordinates, the
//               faces/edge/points an error message names)
//   mesh     -> table built; bounding box, histogram, worst tets
//   extract  -> the buffers of one picture (tetfaces.mjs: whole tets)
//   tet      -> the numbers of one tet
//   write    -> a file of the mesh, through the package's writers
// SPDX-License-Identifier: GPL-3.0-or-later
import { cross, dot, inputEdges, locate, readSurface, sub, triangulate } from './surface.mjs';
import { neighbours, extract, dihedralHistogram, worstTets, gridMesh, TET_FACES } from './tetfaces.mjs';

const MAX_MARKED_TRIANGLES = 200000;
let mesh = null;    // { vertices, tets, tetClass, minDihedral, radiusEdge, weights, nb, stats, ... }
let origin = [0, 0, 0];

function bbox(P) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < P.length; i += 3) {
    for (let k = 0; k < 3; ++k) {
      const x = P[i + k];
      if (x < lo[k]) lo[k] = x;
      if (x > hi[k]) hi[k] = x;
    }
  }
  if (!(lo[0] <= hi[0])) return { lo: [0, 0, 0], hi: [1, 1, 1] };
  return { lo, hi };
}

function surfaceMessage({ bytes, error, sharp }) {
  const s = readSurface(bytes);
  const { tri, triFace } = triangulate(s);
  const P = s.points;
  const box = bbox(P);
  origin = box.lo.map((x, k) => (x + box.hi[k]) / 2);
  const rel = (p, out, o) => { out[o] = p[0] - origin[0]; out[o + 1] = p[1] - origin[1]; out[o + 2] = p[2] - origin[2]; };
  const positions = new Float32Array(3 * tri.length);
  for (let i = 0; i < tri.length; ++i) rel([P[3 * tri[i]], P[3 * tri[i] + 1], P[3 * tri[i] + 2]], positions, 3 * i);
  // The input edges take time per triangle: skipped for very large
  // inputs, so that the preview (and this worker's queue) stays quick.
  let E = null;
  const marks = tri.length / 3 <= MAX_MARKED_TRIANGLES;
  if (marks) {
    try { E = inputEdges(s); } catch { E = null; }
  }
  const featureLines = new Float32Array(6 * (E ? E.edges.length : 0));
  if (E) E.edges.forEach(([a, b], i) => { rel(E.pos[a], featureLines, 6 * i); rel(E.pos[b], featureLines, 6 * i + 3); });
  // The sharp elements: the check report's coordinates (plc.sharp_edge_points,
  // plc.sharp_vertex_points), drawn over the input edges.
  const sharpEdgePoints = sharp ? sharp.edges : [];
  const sharpVertexPoints = sharp ? sharp.vertices : [];
  const sharpLines = new Float32Array(6 * sharpEdgePoints.length);
  sharpEdgePoints.forEach(([p, q], i) => { rel(p, sharpLines, 6 * i); rel(q, sharpLines, 6 * i + 3); });
  const sharpPoints = new Float32Array(3 * sharpVertexPoints.length);
  sharpVertexPoints.forEach((p, i) => rel(p, sharpPoints, 3 * i));
  // What an error message names.
  let bad = null;
  if (error) {
    const where = locate(error);
    const faces = new Set(where.faces);
    const badTris = [];
    for (let t = 0; t < triFace.length; ++t) if (faces.has(triFace[t])) badTris.push(t);
    const badPositions = new Float32Array(9 * badTris.length);
    badTris.forEach((t, i) => badPositions.set(positions.subarray(9 * t, 9 * t + 9), 9 * i));
    const badEdge = new Float32Array(where.edge ? 6 : 0);
    if (where.edge) { rel(where.edge[0], badEdge, 0); rel(where.edge[1], badEdge, 3); }
    const badPoints = new Float32Array(3 * where.points.length);
    where.points.forEach((p, i) => rel(p, badPoints, 3 * i));
    bad = { positions: badPositions, edge: badEdge, points: badPoints, faces: where.faces };
  }
  const transfer = [positions.buffer, featureLines.buffer, sharpLines.buffer, sharpPoints.buffer];
  if (bad) transfer.push(bad.positions.buffer, bad.edge.buffer, bad.points.buffer);
  return {
    value: {
      positions, featureLines, sharpLines, sharpPoints, bad, origin,
      size: Math.max(...box.hi.map((x, k) => x - box.lo[k])) || 1,
      counts: { edges: E ? E.edges.length : null, sharpEdges: sharpLines.length / 6, sharpVertices: sharpPoints.length / 3 },
      marksSkipped: !marks,
      triangles: tri.length / 3, faces: s.faces.length, points: P.length / 3,
    },
    transfer,
  };
}

function meshMessage({ result, synthetic }) {
  const r = synthetic ? gridMesh(synthetic) : result;
  const t0 = performance.now();
  mesh = { ...r, nb: neighbours(r.tets) };
  const tableMs = performance.now() - t0;
  const box = bbox(mesh.vertices);
  if (synthetic) origin = box.lo.map((x, k) => (x + box.hi[k]) / 2);
  const pumped = [];
  const W = mesh.weights || [];
  for (let v = 0; v < W.length; ++v) if (W[v] > 0) pumped.push(v);
  const pumpedPoints = new Float32Array(3 * pumped.length);
  pumped.forEach((v, i) => {
    for (let k = 0; k < 3; ++k) pumpedPoints[3 * i + k] = mesh.vertices[3 * v + k] - origin[k];
  });
  return {
    value: {
      tets: mesh.tets.length / 4, vertices: mesh.vertices.length / 3, box, origin, tableMs,
      histogram: dihedralHistogram(mesh.minDihedral),
      worst: worstTets(mesh.minDihedral, 12).map((w) => ({ ...w, cls: mesh.tetClass[w.tet] })),
      pumpedPoints,
      synthetic: Boolean(synthetic),
    },
    transfer: [pumpedPoints.buffer],
  };
}

function extractMessage({ view }) {
  if (!mesh) return { value: null, transfer: [] };
  const t0 = performance.now();
  const g = extract(mesh, { ...view, origin });
  const ms = performance.now() - t0;
  return {
    value: { ...g, ms },
    transfer: [g.positions.buffer, g.centroids.buffer, g.colours.buffer, g.index.buffer, g.faceTet.buffer, g.edges.buffer],
  };
}

/** Circumcenter and R/l (circumradius over shortest edge, unweighted) of four points. */
function circum(p) {
  const [a, b, c, d] = p;
  const ba = sub(b, a), ca = sub(c, a), da = sub(d, a);
  const den = 2 * dot(ba, cross(ca, da));
  const n = cross(ca, da).map((x) => x * dot(ba, ba));
  const m = cross(da, ba).map((x) => x * dot(ca, ca));
  const o = cross(ba, ca).map((x) => x * dot(da, da));
  const off = [0, 1, 2].map((k) => (n[k] + m[k] + o[k]) / den);
  const R = Math.hypot(...off);
  let l = Infinity;
  for (let i = 0; i < 4; ++i) for (let j = i + 1; j < 4; ++j) l = Math.min(l, Math.hypot(...sub(p[i], p[j])));
  return { center: [a[0] + off[0], a[1] + off[1], a[2] + off[2]], ratio: R / l };
}

/** L_v for each of the given vertices: the shortest mesh edge at v (one pass over the tets). */
function nearestOver(ids) {
  const T = mesh.tets, V = mesh.vertices;
  const best = ids.map(() => Infinity);
  for (let t = 0; t < T.length; t += 4) {
    for (let a = 0; a < 4; ++a) {
      const k = ids.indexOf(T[t + a]);
      if (k < 0) continue;
      for (let b = 0; b < 4; ++b) {
        if (b === a) continue;
        const u = 3 * T[t + a], w = 3 * T[t + b];
        const d = Math.hypot(V[u] - V[w], V[u + 1] - V[w + 1], V[u + 2] - V[w + 2]);
        if (d < best[k]) best[k] = d;
      }
    }
  }
  return best;
}

const CLASS_NAMES = ['good', 'skinny, near a small input angle', 'sliver, near a small input angle', 'violation'];

function tetMessage({ tet, stats }) {
  if (!mesh || !(tet >= 0 && tet < mesh.tets.length / 4)) return { value: null, transfer: [] };
  const ids = Array.from(mesh.tets.subarray(4 * tet, 4 * tet + 4));
  const pts = ids.map((v) => Array.from(mesh.vertices.subarray(3 * v, 3 * v + 3)));
  const c = circum(pts);
  const cls = mesh.tetClass[tet];
  const ratio = mesh.radiusEdge ? mesh.radiusEdge[tet] : c.ratio;
  const orthoratio = mesh.orthoradiusEdge ? mesh.orthoradiusEdge[tet] : undefined;
  // Why near, by the core's rule (README, "Every output tet has a class";
  // core/src/mesher/classify.h): its circumcenter on or inside a protecting
  // ball (c, r), or a vertex v with |v - c|^2 <= (2r)^2 + L_v^2/9, L_v the
  // shortest mesh edge at v, both on the unweighted mesh, as here.
  let near = '';
  const balls = (stats && stats.protecting_balls) || [];
  if (cls === 1 || cls === 2) {
    const name = (i) => `protecting ball ${i} (${balls[i].vertex_ball ? 'vertex ball of a sharp vertex' : 'ball of a sharp edge'}, ` +
                        `radius ${balls[i].radius.toPrecision(3)})`;
    const inside = balls.findIndex((b) => Math.hypot(...sub(c.center, b.center)) <= b.radius);
    if (inside >= 0) near = `circumcenter inside ${name(inside)}`;
    else {
      const nn = nearestOver(ids);
      for (let k = 0; k < 4 && !near; ++k) {
        const j = balls.findIndex((b) => dot(sub(pts[k], b.center), sub(pts[k], b.center)) <= 4 * b.radius ** 2 + nn[k] ** 2 / 9);
        if (j >= 0) near = `vertex ${ids[k]} within (2r)^2 + L_v^2/9 of ${name(j)}`;
      }
      if (!near) near = 'near by the core (a test within rounding of a ball\'s boundary here)';
    }
  }
  const g = pts.reduce((s, p) => s.map((x, k) => x + p[k] / 4), [0, 0, 0]);
  let size = 0;
  for (const p of pts) size = Math.max(size, Math.hypot(...sub(p, g)));
  return {
    value: {
      tet, vertices: ids, points: pts, minDihedral: mesh.minDihedral[tet], radiusEdge: ratio,
      orthoradiusEdge: orthoratio, cls, className: CLASS_NAMES[cls] || String(cls), near,
      centroid: g.map((x, k) => x - origin[k]), size,
      corners: new Float32Array(pts.flatMap((p) => p.map((x, k) => x - origin[k]))),
      faces: TET_FACES,
    },
    transfer: [],
  };
}

async function writeMessage({ format, stats }) {
  if (!mesh) throw new Error('no mesh');
  const pkg = await import('./pkg/wasm/index.mjs');
  const result = { ...mesh, stats };
  const need = { medit: 'writeMedit', vtu: 'writeVtu', tetgen: 'writeTetgen' }[format];
  // This worker is off the main thread already: the synchronous writers
  // need no worker of their own.
  if (typeof pkg.ready === 'function' && typeof pkg[`${need}Sync`] === 'function') {
    await pkg.ready();
    return { value: pkg[`${need}Sync`](result), transfer: [] };
  }
  if (typeof pkg[need] !== 'function') throw new Error(`this build of the package has no ${need}()`);
  return { value: await pkg[need](result), transfer: [] };
}

const handlers = { surface: surfaceMessage, mesh: meshMessage, extract: extractMessage, tet: tetMessage, write: writeMessage };

self.onmessage = async (ev) => {
  const { id, type } = ev.data;
  try {
    const { value, transfer } = await handlers[type](ev.data);
    self.postMessage({ id, value }, transfer);
  } catch (e) {
    self.postMessage({ id, error: { message: String(e.message || e), code: e.code || 'internal' } });
  }
};
