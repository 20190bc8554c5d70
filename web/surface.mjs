// wqmesh page: a lenient reader of OFF and STL files for the preview of the
// input surface, and its input edges (to draw them on the preview).
//
// The core's check report (the package's check()) is what decides validity,
// what the page prints as numbers, and which elements are sharp: the page
// draws the sharp edges and vertices at the report's coordinates
// (plc.sharp_vertex_points, plc.sharp_edge_points) and has no reading of
// sharpness of its own.
// Pure functions: no DOM, usable in workers and in Node.
// SPDX-License-Identifier: GPL-3.0-or-later

/** Reads OFF or STL bytes (format by content) into points and polygon faces; never throws. */
export function readSurface(bytes) {
  const u8 = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
  try {
    if (isBinaryStl(u8)) return readBinaryStl(u8);
    const text = new TextDecoder().decode(u8);
    if (/^\s*solid\b/i.test(text) && /\bfacet\b/i.test(text)) return readAsciiStl(text);
    return readOff(text);
  } catch (e) {
    return { points: new Float64Array(0), faces: [], format: '', problem: String(e.message || e) };
  }
}

function isBinaryStl(u8) {
  if (u8.length < 84) return false;
  const n = new DataView(u8.buffer, u8.byteOffset, u8.byteLength).getUint32(80, true);
  return 84 + 50 * n === u8.length;
}

function readBinaryStl(u8) {
  const dv = new DataView(u8.buffer, u8.byteOffset, u8.byteLength);
  const n = dv.getUint32(80, true);
  const points = new Float64Array(9 * n);
  const faces = new Array(n);
  for (let f = 0; f < n; ++f) {
    const o = 84 + 50 * f + 12;
    for (let k = 0; k < 9; ++k) points[9 * f + k] = dv.getFloat32(o + 4 * k, true);
    faces[f] = [3 * f, 3 * f + 1, 3 * f + 2];
  }
  return { points, faces, format: 'STL-binary' };
}

function readAsciiStl(text) {
  const re = /vertex\s+(\S+)\s+(\S+)\s+(\S+)/gi;
  const xyz = [];
  let m;
  while ((m = re.exec(text))) xyz.push(Number(m[1]), Number(m[2]), Number(m[3]));
  const n = Math.floor(xyz.length / 9);
  const faces = new Array(n);
  for (let f = 0; f < n; ++f) faces[f] = [3 * f, 3 * f + 1, 3 * f + 2];
  return { points: Float64Array.from(xyz.slice(0, 9 * n)), faces, format: 'STL-ascii' };
}

function readOff(text) {
  const tokens = [];
  for (const line of text.split('\n')) {
    const l = line.replace(/#.*/, '').trim();
    if (l) tokens.push(...l.split(/\s+/));
  }
  let i = 0;
  if (/^[CN]*OFF$/i.test(tokens[0] || '')) ++i;
  else if (/^[CN]*OFF/i.test(tokens[0] || '')) tokens[0] = tokens[0].replace(/^[CN]*OFF/i, '');
  const nv = Number(tokens[i++]), nf = Number(tokens[i++]);
  ++i;  // the edge count
  if (!Number.isInteger(nv) || !Number.isInteger(nf) || nv < 0 || nf < 0) {
    return { points: new Float64Array(0), faces: [], format: 'OFF', problem: 'no OFF header' };
  }
  const points = new Float64Array(3 * nv);
  for (let v = 0; v < 3 * nv && i < tokens.length; ++v) points[v] = Number(tokens[i++]);
  const faces = [];
  for (let f = 0; f < nf && i < tokens.length; ++f) {
    const k = Number(tokens[i++]);
    if (!Number.isInteger(k) || k < 0) break;
    const face = [];
    for (let j = 0; j < k && i < tokens.length; ++j) face.push(Number(tokens[i++]));
    faces.push(face);
    // Colours after the indices, up to the next face's count: skip what
    // cannot be an index list start (a face line has k + 1 tokens at least).
    while (i < tokens.length && f + 1 < nf && !Number.isInteger(Number(tokens[i]))) ++i;
  }
  return { points, faces, format: 'OFF' };
}

/**
 * Triangulates every polygon (ear clipping in the plane of its Newell
 * normal, so non-convex facets such as an L profile come out right) for
 * drawing. Returns `tri` (3 point indices per triangle, indices into
 * `points`, in the polygon's orientation), `triFace` (the input face of each
 * triangle) and `faceNormal` (Newell normal per face, 3 per face, not unit).
 * Faces with out-of-range indices are left out.
 */
export function triangulate(surface) {
  const P = surface.points;
  const n = P.length / 3;
  const tri = [], triFace = [];
  const faceNormal = new Float64Array(3 * surface.faces.length);
  surface.faces.forEach((face, f) => {
    if (face.length < 3 || face.some((v) => !(v >= 0 && v < n && Number.isInteger(v)))) return;
    let nx = 0, ny = 0, nz = 0;
    for (let j = 0; j < face.length; ++j) {
      const a = 3 * face[j], b = 3 * face[(j + 1) % face.length];
      nx += (P[a + 1] - P[b + 1]) * (P[a + 2] + P[b + 2]);
      ny += (P[a + 2] - P[b + 2]) * (P[a] + P[b]);
      nz += (P[a] - P[b]) * (P[a + 1] + P[b + 1]);
    }
    faceNormal.set([nx, ny, nz], 3 * f);
    if (face.length === 3) { tri.push(...face); triFace.push(f); return; }
    if (face.length > 1000) {  // ear clipping is quadratic: a fan for huge polygons (the preview only)
      for (let j = 1; j + 1 < face.length; ++j) { tri.push(face[0], face[j], face[j + 1]); triFace.push(f); }
      return;
    }
    // Project to the two axes other than the normal's largest component.
    const ax = Math.abs(nx), ay = Math.abs(ny), az = Math.abs(nz);
    const [i0, i1, s] = az >= ax && az >= ay ? [0, 1, Math.sign(nz)] : ax >= ay ? [1, 2, Math.sign(nx)] : [2, 0, Math.sign(ny)];
    const X = (v) => P[3 * v + i0], Y = (v) => P[3 * v + i1] * (s || 1);
    const area2 = (a, b, c) => (X(b) - X(a)) * (Y(c) - Y(a)) - (X(c) - X(a)) * (Y(b) - Y(a));
    const ring = face.slice();
    let guard = 0;
    while (ring.length > 3 && guard++ < 4 * face.length * face.length) {
      let cut = -1;
      for (let j = 0; j < ring.length && cut < 0; ++j) {
        const a = ring[(j + ring.length - 1) % ring.length], b = ring[j], c = ring[(j + 1) % ring.length];
        if (area2(a, b, c) <= 0) continue;  // reflex or flat corner
        let inside = false;
        for (const v of ring) {
          if (v === a || v === b || v === c) continue;
          if (area2(a, b, v) >= 0 && area2(b, c, v) >= 0 && area2(c, a, v) >= 0) { inside = true; break; }
        }
        if (!inside) cut = j;
      }
      if (cut < 0) cut = 0;  // not a simple polygon: fan what is left
      const j = cut;
      tri.push(ring[(j + ring.length - 1) % ring.length], ring[j], ring[(j + 1) % ring.length]);
      triFace.push(f);
      ring.splice(j, 1);
    }
    if (ring.length === 3) { tri.push(...ring); triFace.push(f); }
  });
  return { tri: Uint32Array.from(tri), triFace: Uint32Array.from(triFace), faceNormal };
}

/** Small vector helpers on [x, y, z] arrays (also used by the view worker). */
export const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.hypot(a[0], a[1], a[2]);
const unit = (a) => { const l = norm(a) || 1; return [a[0] / l, a[1] / l, a[2] / l]; };

/**
 * The input edges of a surface, for the wireframe of the preview: `edges`
 * (pairs of merged point indices; edges whose two faces are not coplanar, or
 * open or non-manifold edges) and `pos` (x, y, z per merged point).
 */
export function inputEdges(surface) {
  const { tri, triFace, faceNormal } = triangulate(surface);
  const P = surface.points;
  // Merge identical points, as the core does.
  const key = new Map();
  const id = new Int32Array(P.length / 3);
  const pos = [];
  for (let v = 0; v < id.length; ++v) {
    const k = `${P[3 * v] + 0},${P[3 * v + 1] + 0},${P[3 * v + 2] + 0}`;
    let m = key.get(k);
    if (m === undefined) { m = pos.length; key.set(k, m); pos.push([P[3 * v], P[3 * v + 1], P[3 * v + 2]]); }
    id[v] = m;
  }
  const nt = tri.length / 3;
  const T = new Int32Array(tri.length);
  for (let i = 0; i < tri.length; ++i) T[i] = id[tri[i]];
  const normal = [];
  for (let t = 0; t < nt; ++t) {
    const a = pos[T[3 * t]], b = pos[T[3 * t + 1]], c = pos[T[3 * t + 2]];
    const f = 3 * triFace[t];
    const nf = [faceNormal[f], faceNormal[f + 1], faceNormal[f + 2]];
    normal.push(norm(nf) > 0 ? nf : cross(sub(b, a), sub(c, a)));
  }
  // Edge -> triangles.
  const edgeTris = new Map();
  for (let t = 0; t < nt; ++t) {
    for (let j = 0; j < 3; ++j) {
      const a = T[3 * t + j], b = T[3 * t + (j + 1) % 3];
      if (a === b) continue;
      const k = a < b ? a * 4294967296 + b : b * 4294967296 + a;
      let l = edgeTris.get(k);
      if (!l) edgeTris.set(k, (l = []));
      l.push(t);
    }
  }
  // Facets: triangles joined across edges whose two triangles are coplanar.
  const parent = Int32Array.from({ length: nt }, (_, i) => i);
  const find = (x) => { while (parent[x] !== x) x = parent[x] = parent[parent[x]]; return x; };
  const coplanar = (t1, t2) => dot(unit(normal[t1]), unit(normal[t2])) > 1 - 1e-10;
  for (const l of edgeTris.values()) if (l.length === 2 && coplanar(l[0], l[1])) parent[find(l[0])] = find(l[1]);
  const edges = [];
  for (const [k, l] of edgeTris) {
    if (l.length === 2 && find(l[0]) === find(l[1])) continue;
    edges.push([Math.floor(k / 4294967296), k % 4294967296]);
  }
  return { pos, edges };
}

/**
 * Where an error message of the core locates the defect: `faces` (input
 * face indices, "face N"), `points` (every "(x, y, z)" in it) and `edge`
 * ([p, q] for "the edge from vertex i (p) to vertex j (q)" or "edge from ...").
 */
export function locate(message) {
  const faces = [...message.matchAll(/\bface (\d+)/g)].map((m) => Number(m[1]));
  const num = '(-?[\\d.]+(?:e[-+]?\\d+)?)';
  const re = new RegExp(`\\(${num}, ${num}, ${num}\\)`, 'gi');
  const points = [...message.matchAll(re)].map((m) => [Number(m[1]), Number(m[2]), Number(m[3])]);
  const edge = /\bedge from vertex/.test(message) && points.length >= 2 ? [points[0], points[1]] : null;
  return { faces: [...new Set(faces)], points, edge };
}

/** The error kinds of the core in words a person understands (the message says where). */
export const ERROR_WORDS = {
  io: 'The file could not be read.',
  empty: 'The file is empty.',
  syntax: 'The file is not valid OFF or STL.',
  truncated: 'The file ends too early: it is cut off.',
  too_large: 'The file is larger than the mesher accepts.',
  non_finite: 'A coordinate is not a finite number.',
  bad_index: 'A face refers to a point that does not exist.',
  too_few_faces: 'There are too few faces to enclose a volume.',
  degenerate_face: 'A face has zero area (its corners are repeated or on one line).',
  duplicate_face: 'Two faces have the same corners.',
  open_boundary: 'The surface has a hole: an edge belongs to only one face, so it encloses no volume.',
  non_manifold_edge: 'An edge belongs to more than two faces (the surface is not manifold).',
  non_manifold_vertex: 'Two parts of the surface touch at a single vertex (not manifold).',
  not_orientable: 'The surface cannot be oriented consistently (like a Moebius strip).',
  self_intersection: 'The surface intersects itself.',
  zero_volume: 'The surface encloses no volume.',
  out_of_range: 'The coordinates are too large or too small for double precision.',
  options: 'A parameter is out of its range.',
  limit: 'The run needs more memory than allowed.',
  internal: 'The mesher failed on an internal error (please report it).',
};
