// wqmesh page: what the viewer draws of a tetrahedral mesh. The clipping
// plane keeps WHOLE tets (a tet is kept when its centroid is on the kept
// side), and only the faces of kept tets whose neighbour across the face is
// removed or absent are drawn, so the cost of a picture grows with the
// surface and the cut, not with the tet count. The face-to-tet table
// (`neighbours`) is built once per mesh by hashing sorted vertex triples.
// Beyond the paper: this is viewing only; the paper's classes come from the
// core (tetClass), this file only chooses colours and faces.
// Pure functions on typed arrays: no DOM, used by the view worker and by Node tests.
// SPDX-License-Identifier: GPL-3.0-or-later

/**
 * The faces of a positively oriented tet (v0, v1, v2, v3), face i opposite
 * corner i, each listed so that its normal points out of the tet.
 */
export const TET_FACES = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/** The six edges of a tet as corner pairs, and the edges (bit masks) of each face. */
const EDGE_CORNERS = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];
const FACE_EDGES = TET_FACES.map((F) => {
  let m = 0;
  EDGE_CORNERS.forEach(([a, b], e) => { if (F.includes(a) && F.includes(b)) m |= 1 << e; });
  return m;
});

/**
 * The neighbour of every tet across each face: Int32Array(4 * tetCount),
 * entry 4 t + i is the tet across face i of tet t, or -1 on the boundary.
 * Open addressing on a hash of the sorted vertex triple; O(tets).
 */
export function neighbours(tets) {
  const nt = tets.length / 4;
  const nb = new Int32Array(4 * nt).fill(-1);
  let size = 1;
  while (size < 8 * nt) size *= 2;  // load factor at most 1/4 for the 2 nt distinct faces
  const table = new Int32Array(size).fill(-1);  // face id 4 t + i
  const mask = size - 1;
  const key = new Uint32Array(3);
  const sorted = (f, out) => {
    const t = f >> 2, i = f & 3, o = 4 * t;
    const F = TET_FACES[i];
    let a = tets[o + F[0]], b = tets[o + F[1]], c = tets[o + F[2]], x;
    if (a > b) { x = a; a = b; b = x; }
    if (b > c) { x = b; b = c; c = x; }
    if (a > b) { x = a; a = b; b = x; }
    out[0] = a; out[1] = b; out[2] = c;
  };
  const other = new Uint32Array(3);
  for (let f = 0; f < 4 * nt; ++f) {
    sorted(f, key);
    let h = (Math.imul(key[0], 0x9e3779b1) ^ Math.imul(key[1], 0x85ebca77) ^ Math.imul(key[2], 0xc2b2ae3d)) >>> 0;
    h = (h ^ (h >>> 15)) & mask;
    for (;;) {
      const g = table[h];
      if (g === -1) { table[h] = f; break; }
      if (g < -1) { h = (h + 1) & mask; continue; }  // a paired face: matches nothing more
      sorted(g, other);
      if (other[0] === key[0] && other[1] === key[1] && other[2] === key[2] && nb[g] < 0) {
        nb[g] = f >> 2;
        nb[f] = g >> 2;
        table[h] = -2 - g;  // paired: keep the probe chain, free for nothing else
        break;
      }
      h = (h + 1) & mask;
    }
  }
  return nb;
}

/** Colours of the classes and of the user bound (sRGB bytes); the legend shows the same. */
export const CLASS_COLOURS = {
  good: [176, 190, 206],         // 0: good
  skinny: [235, 140, 30],        // 1: skinny near a small input angle
  sliver: [150, 70, 200],        // 2: sliver near a small input angle
  violation: [215, 25, 28],      // 3: skinny or sliver, not near (a violation of the guarantee)
  below: [245, 210, 0],          // below the user's dihedral bound (and good otherwise)
  selected: [0, 170, 120],       // the picked tet
};
/**
 * A colour as the vertex-colour bytes that show it: three.js takes vertex
 * colours as linear and writes sRGB, so the sRGB bytes are linearised first.
 */
export function linearBytes(rgb) {
  return rgb.map((c) => {
    const x = c / 255;
    return Math.round(255 * (x <= 0.04045 ? x / 12.92 : ((x + 0.055) / 1.055) ** 2.4));
  });
}
const LINEAR = Object.fromEntries(Object.entries(CLASS_COLOURS).map(([k, v]) => [k, linearBytes(v)]));
const BY_CLASS = [LINEAR.good, LINEAR.skinny, LINEAR.sliver, LINEAR.violation];

/**
 * What to draw. `mesh`: { vertices (Float64Array), tets, tetClass, minDihedral,
 * nb (from neighbours) }. `view`: { clip (bool), normal [x, y, z], offset (the
 * kept side is centroid . normal <= offset), bound (degrees), rest ('show',
 * 'fade', 'hide'), shrunk (bool: draw all four faces of every drawn tet, so
 * that a shrink factor below 1 shows single tets), origin [x, y, z]
 * (subtracted from positions, for float precision), selected (tet or -1) }.
 *
 * A tet is *highlighted* when its class is not good or its smallest dihedral
 * angle is below `bound`. Kept: on the kept side (when clip), and highlighted
 * when rest = 'hide'. Drawn faces: faces of kept tets whose neighbour is
 * absent or not kept; with rest = 'fade' also the faces between a highlighted
 * and a plain kept tet (from the highlighted side), and the plain tets' faces
 * go into the translucent group.
 *
 * Returns { positions (Float32Array, 3 per corner, 4 corners per drawn tet),
 * centroids (Float32Array, the tet's centroid per corner, for the shrink
 * shader), colours (Uint8Array, 3 per corner), index (Uint32Array, 3 per
 * drawn face, opaque faces first), opaqueFaces (count), faceTet (Uint32Array,
 * the tet of each drawn face), edges (Uint32Array, corner pairs of the edges
 * of the opaque drawn faces, unless view.edges is false), drawnTets (tets with
 * a drawn face), keptTets }.
 */
export function extract(mesh, view) {
  const { vertices: V, tets: T, tetClass: C, minDihedral: D, nb } = mesh;
  const nt = T.length / 4;
  const [nx, ny, nz] = view.normal;
  const off = view.offset, bound = view.bound, rest = view.rest;
  const [ox, oy, oz] = view.origin || [0, 0, 0];
  if (!mesh.centroid) mesh.centroid = tetCentroids(V, T);
  const G = mesh.centroid;
  const kept = new Uint8Array(nt);  // 0 removed, 1 kept plain, 2 kept highlighted
  let keptTets = 0;
  const hide = rest === 'hide', clip = Boolean(view.clip);
  for (let t = 0; t < nt; ++t) {
    const hi = C[t] !== 0 || D[t] < bound;
    if (hide && !hi) continue;
    if (clip && G[3 * t] * nx + G[3 * t + 1] * ny + G[3 * t + 2] * nz > off) continue;
    kept[t] = hi ? 2 : 1;
    ++keptTets;
  }
  // Pass 1: the group of each face of each kept tet (0 not drawn, 1 opaque,
  // 2 faded; two bits per face), the counts, and the list of drawn tets.
  const fade = rest === 'fade', shrunk = Boolean(view.shrunk);
  const packed = new Uint8Array(nt);
  const drawnList = new Int32Array(keptTets);
  let nOpaque = 0, nFaded = 0, nDrawn = 0;
  for (let t = 0; t < nt; ++t) {
    const k = kept[t];
    if (!k) continue;
    const own = fade && k === 1 ? 2 : 1;
    let bits = 0;
    for (let i = 0; i < 4; ++i) {
      const n = nb[4 * t + i];
      const kn = n < 0 ? 0 : kept[n];
      const g = shrunk || kn === 0 ? own : fade && k === 2 && kn === 1 ? 1 : 0;
      if (g === 1) ++nOpaque; else if (g === 2) ++nFaded;
      bits |= g << (2 * i);
    }
    if (bits || shrunk) { packed[t] = bits; drawnList[nDrawn++] = t; }
  }
  const positions = new Float32Array(12 * nDrawn);
  const centroids = new Float32Array(12 * nDrawn);
  const colours = new Uint8Array(12 * nDrawn);
  const index = new Uint32Array(3 * (nOpaque + nFaded));
  const faceTet = new Uint32Array(nOpaque + nFaded);
  const wantEdges = view.edges !== false;
  const edgeBuf = new Uint32Array(wantEdges ? 12 * nDrawn : 0);
  let ne = 0;
  let fo = 0, ff = nOpaque;
  for (let d = 0; d < nDrawn; ++d) {
    const t = drawnList[d];
    const o = 4 * t;
    let cx = 0, cy = 0, cz = 0;
    for (let k = 0; k < 4; ++k) {
      const v = 3 * T[o + k];
      const p = 12 * d + 3 * k;
      positions[p] = V[v] - ox; positions[p + 1] = V[v + 1] - oy; positions[p + 2] = V[v + 2] - oz;
      cx += positions[p]; cy += positions[p + 1]; cz += positions[p + 2];
    }
    const col = t === view.selected ? LINEAR.selected
      : C[t] !== 0 ? BY_CLASS[C[t]] : D[t] < bound ? LINEAR.below : LINEAR.good;
    for (let k = 0; k < 4; ++k) {
      const p = 12 * d + 3 * k;
      centroids[p] = cx / 4; centroids[p + 1] = cy / 4; centroids[p + 2] = cz / 4;
      colours[p] = col[0]; colours[p + 1] = col[1]; colours[p + 2] = col[2];
    }
    let edgeMask = 0;
    for (let i = 0; i < 4; ++i) {
      const g = (packed[t] >> (2 * i)) & 3;
      if (!g) continue;
      const F = TET_FACES[i];
      const at = g === 1 ? fo++ : ff++;
      index[3 * at] = 4 * d + F[0]; index[3 * at + 1] = 4 * d + F[1]; index[3 * at + 2] = 4 * d + F[2];
      faceTet[at] = t;
      if (g === 1) edgeMask |= FACE_EDGES[i];
    }
    if (wantEdges) {
      for (let e = 0; e < 6; ++e) {
        if (!(edgeMask & (1 << e))) continue;
        edgeBuf[ne++] = 4 * d + EDGE_CORNERS[e][0];
        edgeBuf[ne++] = 4 * d + EDGE_CORNERS[e][1];
      }
    }
  }
  return { positions, centroids, colours, index, opaqueFaces: nOpaque, faceTet, drawnTets: nDrawn, keptTets,
           edges: edgeBuf.slice(0, ne) };
}

/** The centroid of every tet, 3 per tet (what decides the side of the plane). */
export function tetCentroids(V, T) {
  const nt = T.length / 4;
  const G = new Float64Array(3 * nt);
  for (let t = 0; t < nt; ++t) {
    const a = 3 * T[4 * t], b = 3 * T[4 * t + 1], c = 3 * T[4 * t + 2], d = 3 * T[4 * t + 3];
    G[3 * t] = (V[a] + V[b] + V[c] + V[d]) / 4;
    G[3 * t + 1] = (V[a + 1] + V[b + 1] + V[c + 1] + V[d + 1]) / 4;
    G[3 * t + 2] = (V[a + 2] + V[b + 2] + V[c + 2] + V[d + 2]) / 4;
  }
  return G;
}

/** Histogram of the smallest dihedral angle per tet: counts in `bins` bins of `width` degrees from 0. */
export function dihedralHistogram(minDihedral, width = 5, bins = 15) {
  const h = new Array(bins).fill(0);
  for (let t = 0; t < minDihedral.length; ++t) h[Math.min(bins - 1, Math.floor(minDihedral[t] / width))]++;
  return { width, counts: h };
}

/** The `n` tets with the smallest dihedral angles, worst first: [{ tet, minDihedral }]. */
export function worstTets(minDihedral, n = 12) {
  const best = [];  // sorted ascending, at most n
  for (let t = 0; t < minDihedral.length; ++t) {
    const d = minDihedral[t];
    if (best.length === n && d >= best[n - 1].minDihedral) continue;
    let i = best.length;
    while (i > 0 && best[i - 1].minDihedral > d) --i;
    best.splice(i, 0, { tet: t, minDihedral: d });
    if (best.length > n) best.pop();
  }
  return best;
}

/**
 * A structured test mesh (not the mesher's): the box [0, n]^3 cut into n^3
 * cubes, each cube into 6 positively oriented tets around its diagonal
 * (Kuhn's subdivision), 6 n^3 tets; classes and dihedral angles are made up
 * from the position so that every colour shows. For the size measurements
 * of the README and the browser tests of the clipping plane.
 */
export function gridMesh(n) {
  const m = n + 1;
  const vertices = new Float64Array(3 * m * m * m);
  for (let z = 0, v = 0; z < m; ++z) for (let y = 0; y < m; ++y) for (let x = 0; x < m; ++x, v += 3) {
    vertices[v] = x; vertices[v + 1] = y; vertices[v + 2] = z;
  }
  const id = (x, y, z) => x + m * (y + m * z);
  const tets = new Uint32Array(24 * n * n * n);
  // Kuhn: paths from corner 0 to corner 7 through the axes in each order.
  const perms = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];
  let o = 0;
  for (let z = 0; z < n; ++z) for (let y = 0; y < n; ++y) for (let x = 0; x < n; ++x) {
    for (const p of perms) {
      const c = [x, y, z];
      const q = [id(...c)];
      for (const a of p) { c[a] += 1; q.push(id(...c)); }
      // Orientation: even permutations of the axes are positive.
      const even = (p[0] === 0 && p[1] === 1) || (p[0] === 1 && p[1] === 2) || (p[0] === 2 && p[1] === 0);
      if (!even) [q[2], q[3]] = [q[3], q[2]];
      tets.set(q, o);
      o += 4;
    }
  }
  const nt = tets.length / 4;
  const tetClass = new Uint8Array(nt);
  const minDihedral = new Float64Array(nt);
  const radiusEdge = new Float64Array(nt);
  for (let t = 0; t < nt; ++t) {
    const h = Math.imul(t + 1, 2654435761) >>> 0;
    tetClass[t] = h % 97 === 0 ? 2 : h % 89 === 0 ? 1 : h % 499 === 0 ? 3 : 0;
    minDihedral[t] = tetClass[t] === 2 ? 1 + (h % 20) / 10 : 35.26 + (h % 100) / 10;
    radiusEdge[t] = tetClass[t] === 1 ? 3 : 0.87;
  }
  return { vertices, weights: new Float64Array(m * m * m), tets, tetClass, minDihedral, radiusEdge };
}
