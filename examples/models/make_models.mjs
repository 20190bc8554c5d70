// wqmesh: writes the example polyhedra of examples/models as OFF files and
// checks each one (closed, consistently and outwardly oriented, planar faces,
// positive volume). Coordinates are binary fractions, so coplanar vertices are
// exactly coplanar in double precision.
// Usage: node examples/models/make_models.mjs   (no dependencies)
// SPDX-License-Identifier: GPL-3.0-or-later
import { writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));

// ---- Building blocks ---------------------------------------------------------

/** A polyhedron under construction: points by name, faces as lists of names. */
class Solid {
  constructor(name, comment) {
    this.name = name;
    this.comment = comment;
    this.points = [];
    this.index = new Map();
    this.faces = [];
  }
  /** Adds a named point (x, y, z). */
  point(id, x, y, z) {
    if (this.index.has(id)) throw new Error(`${this.name}: point ${id} defined twice`);
    this.index.set(id, this.points.length);
    this.points.push([x, y, z]);
    return id;
  }
  /** Adds a face, its vertices counter-clockwise seen from outside. */
  face(...ids) {
    this.faces.push(ids.map((id) => {
      const i = this.index.get(id);
      if (i === undefined) throw new Error(`${this.name}: unknown point ${id}`);
      return i;
    }));
  }
}

/**
 * A prism: the polygon `poly` (2D, counter-clockwise) of the (u, v) plane,
 * extruded along w from w0 to w1. `axes` maps (u, v, w) to (x, y, z) by a
 * cyclic permutation (orientation preserving): 'xyz', 'yzx' or 'zxy', meaning
 * that u, v, w are the first, second and third letters.
 */
function prism(name, comment, poly, w0, w1, axes = 'xyz') {
  if (!['xyz', 'yzx', 'zxy'].includes(axes)) throw new Error(`prism: axes ${axes} is not cyclic`);
  const s = new Solid(name, comment);
  const place = (u, v, w) => {
    const p = {};
    p[axes[0]] = u;
    p[axes[1]] = v;
    p[axes[2]] = w;
    return [p.x, p.y, p.z];
  };
  const n = poly.length;
  poly.forEach(([u, v], i) => {
    s.point(`b${i}`, ...place(u, v, w0));
    s.point(`t${i}`, ...place(u, v, w1));
  });
  s.face(...poly.map((_, i) => `b${n - 1 - i}`));  // bottom, seen from below
  s.face(...poly.map((_, i) => `t${i}`));          // top
  for (let i = 0; i < n; i++) {
    const j = (i + 1) % n;
    s.face(`b${i}`, `b${j}`, `t${j}`, `t${i}`);
  }
  return s;
}

// ---- The models ----------------------------------------------------------------

function box() {
  return prism('box', 'a plain box 2 x 1 x 1: right dihedral angles only',
               [[0, 0], [2, 0], [2, 1], [0, 1]], 0, 1);
}

function wedge() {
  // Cross-section: a triangle with a corner of atan(0.703125 / 4) = 9.97 degrees;
  // the edge through that corner has an internal dihedral angle of 9.97 degrees.
  return prism('thin_wedge', 'a thin wedge (triangular prism): acute dihedral angle of 9.97 degrees',
               [[0, 0], [4, 0], [4, 0.703125]], 0, 2);
}

function spike() {
  // A unit cube with a tall square pyramid on top (apex 4 above the cube):
  // adjacent edges at the apex meet at acos(16 / 16.5) = 14.1 degrees, opposite
  // ones at acos(15.5 / 16.5) = 20.0 degrees.
  const s = new Solid('spike', 'a cube with a tall square pyramid: edge-edge angles of 14.1 degrees at the apex');
  const c = [[0, 0], [1, 0], [1, 1], [0, 1]];
  c.forEach(([x, y], i) => {
    s.point(`b${i}`, x, y, 0);
    s.point(`m${i}`, x, y, 1);
  });
  s.point('apex', 0.5, 0.5, 5);
  s.face('b3', 'b2', 'b1', 'b0');
  for (let i = 0; i < 4; i++) {
    const j = (i + 1) % 4;
    s.face(`b${i}`, `b${j}`, `m${j}`, `m${i}`);
    s.face(`m${i}`, `m${j}`, 'apex');
  }
  return s;
}

function edgeFacet() {
  // A slab 8 x 4 x 1 with a leaning square column on it: the column's base is
  // the square [1,2] x [1.5,2.5] on the slab's top, its top is shifted by
  // (3.5, 0, 2), so its side edges make atan(2 / 3.5) = 29.7 degrees with the
  // slab's top facet, which they touch only at their lower ends.
  const s = new Solid('edge_facet',
                      'a slab with a leaning column: edge-facet angles of 29.7 degrees at the column foot');
  const outer = [[0, 0], [8, 0], [8, 4], [0, 4]];
  outer.forEach(([x, y], i) => {
    s.point(`s${i}`, x, y, 0);
    s.point(`u${i}`, x, y, 1);
  });
  const foot = [[1, 1.5], [2, 1.5], [2, 2.5], [1, 2.5]];
  foot.forEach(([x, y], i) => {
    s.point(`f${i}`, x, y, 1);
    s.point(`h${i}`, x + 3.5, y, 3);
  });
  s.face('s3', 's2', 's1', 's0');  // slab bottom
  for (let i = 0; i < 4; i++) {
    const j = (i + 1) % 4;
    s.face(`s${i}`, `s${j}`, `u${j}`, `u${i}`);  // slab sides
    s.face(`u${i}`, `u${j}`, `f${j}`, `f${i}`);  // slab top, in four quads around the foot
    s.face(`f${i}`, `f${j}`, `h${j}`, `h${i}`);  // column sides (parallelograms)
  }
  s.face('h0', 'h1', 'h2', 'h3');  // column top
  return s;
}

function slit() {
  // A block 4 x 2 x 1 with a V-shaped slit 1.5 deep and 0.25 wide at the top:
  // the slit's opening is 2 atan(0.125 / 1.5) = 9.53 degrees, so the internal
  // dihedral angle at its bottom edge is 350.47 degrees.
  return prism('slit', 'a block with a thin V slit: reflex dihedral angle of 350.47 degrees',
               [[0, 0], [4, 0], [4, 2], [2.125, 2], [2, 0.5], [1.875, 2], [0, 2]], 0, 1);
}

function bracket() {
  // An L-bracket: a plate [0,6] x [0,4] x [0,1] and a flange [0,1] x [0,4] x [1,5],
  // with a square hole [3,4.5] x [1.25,2.75] through the plate (genus 1).
  // The plate's top and bottom around the hole are four quads each.
  const s = new Solid('bracket',
                      'an L-bracket with a square through hole: right and 270-degree dihedral angles, genus 1');
  const profile = [[0, 0], [6, 0], [6, 1], [1, 1], [1, 5], [0, 5]];  // (x, z)
  profile.forEach(([x, z], i) => {
    s.point(`a${i}`, x, 0, z);
    s.point(`b${i}`, x, 4, z);
  });
  const hole = [[3, 1.25], [4.5, 1.25], [4.5, 2.75], [3, 2.75]];  // (x, y)
  hole.forEach(([x, y], i) => {
    s.point(`h${i}`, x, y, 0);
    s.point(`g${i}`, x, y, 1);
  });
  s.face('a0', 'a1', 'a2', 'a3', 'a4', 'a5');  // y = 0
  s.face('b5', 'b4', 'b3', 'b2', 'b1', 'b0');  // y = 4
  s.face('h0', 'h1', 'a1', 'a0');              // bottom (z = 0), around the hole
  s.face('h1', 'h2', 'b1', 'a1');
  s.face('h2', 'h3', 'b0', 'b1');
  s.face('h3', 'h0', 'a0', 'b0');
  s.face('a3', 'a2', 'g1', 'g0');              // plate top (z = 1), around the hole
  s.face('a2', 'b2', 'g2', 'g1');
  s.face('b2', 'b3', 'g3', 'g2');
  s.face('b3', 'a3', 'g0', 'g3');
  s.face('a1', 'b1', 'b2', 'a2');              // x = 6
  s.face('a3', 'b3', 'b4', 'a4');              // flange inside, x = 1
  s.face('a4', 'b4', 'b5', 'a5');              // flange top, z = 5
  s.face('a0', 'a5', 'b5', 'b0');              // back, x = 0
  for (let i = 0; i < 4; i++) {                // the hole's walls
    const j = (i + 1) % 4;
    s.face(`h${i}`, `g${i}`, `g${j}`, `h${j}`);
  }
  return s;
}

// ---- Checks ------------------------------------------------------------------------

const SCALE = 2 ** 20;

/** Exact integer coordinates (every coordinate is a multiple of 2^-20). */
function exact(p) {
  return p.map((c) => {
    const s = c * SCALE;
    if (!Number.isInteger(s)) throw new Error(`coordinate ${c} is not a multiple of 2^-20`);
    return BigInt(s);
  });
}
const sub = (a, b) => a.map((x, i) => x - b[i]);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const norm = (a) => Math.sqrt(dot(a, a));
const zero = (a) => a.every((x) => x === 0n);

/** The exact normal of a planar polygon (Newell's sum, integer arithmetic). */
function exactNormal(pts) {
  const n = [0n, 0n, 0n];
  for (let i = 0; i < pts.length; i++) {
    const p = pts[i], q = pts[(i + 1) % pts.length];
    n[0] += (p[1] - q[1]) * (p[2] + q[2]);
    n[1] += (p[2] - q[2]) * (p[0] + q[0]);
    n[2] += (p[0] - q[0]) * (p[1] + q[1]);
  }
  return n;
}

/**
 * Checks a solid; throws with a message on the first defect. Returns facts
 * for the log: counts, Euler characteristic, volume, angles at feature edges
 * (edges whose two faces are not coplanar).
 */
function check(s) {
  const P = s.points.map(exact);
  const where = (f) => `${s.name}: face ${f} [${s.faces[f].join(' ')}]`;
  const normals = s.faces.map((face, f) => {
    if (face.length < 3) throw new Error(`${where(f)} has fewer than 3 vertices`);
    if (new Set(face).size !== face.length) throw new Error(`${where(f)} repeats a vertex`);
    const pts = face.map((i) => P[i]);
    const n = exactNormal(pts);
    if (zero(n)) throw new Error(`${where(f)} has zero area`);
    for (const p of pts) {
      if (dot(n, sub(p, pts[0])) !== 0n) throw new Error(`${where(f)} is not planar`);
    }
    return n;
  });
  // Closed and consistently oriented: every directed edge once, its reverse once.
  const directed = new Map();
  s.faces.forEach((face, f) => {
    face.forEach((a, k) => {
      const b = face[(k + 1) % face.length];
      const key = `${a},${b}`;
      if (directed.has(key)) throw new Error(`${where(f)}: edge ${a}->${b} is in two faces with the same direction`);
      directed.set(key, f);
    });
  });
  const edges = [];
  for (const [key, f] of directed) {
    const [a, b] = key.split(',').map(Number);
    const g = directed.get(`${b},${a}`);
    if (g === undefined) throw new Error(`${where(f)}: edge ${a}-${b} has only one face (open)`);
    if (a < b) edges.push({ a, b, f, g });
  }
  const used = new Set(s.faces.flat());
  if (used.size !== s.points.length) throw new Error(`${s.name}: a point is in no face`);
  // Volume: divergence theorem over fans (exact, in units of 2^-60 / 6).
  let vol6 = 0n;
  for (const face of s.faces) {
    for (let k = 1; k + 1 < face.length; k++) {
      vol6 += dot(P[face[0]], cross(P[face[k]], P[face[k + 1]]));
    }
  }
  if (vol6 <= 0n) throw new Error(`${s.name}: volume is not positive (faces point inwards?)`);
  const volume = Number(vol6) / 6 / SCALE ** 3;
  // Internal dihedral angles at feature edges: f holds a->b, g holds b->a.
  const X = s.points;
  const unit = (n) => { const v = n.map(Number); const l = norm(v); return v.map((x) => x / l); };
  const dihedrals = [];
  const feature = [];
  for (const { a, b, f, g } of edges) {
    if (zero(cross(normals[f], normals[g])) && dot(normals[f], normals[g]) > 0n) continue;  // coplanar
    const n1 = unit(normals[f]), n2 = unit(normals[g]);
    const e = unit(sub(X[b], X[a]).map((x) => x * SCALE).map(BigInt));
    const w1 = cross(n1, e);              // into face f, away from the edge
    const w2 = cross(n2, e.map((x) => -x));  // into face g
    const inward = n1.map((x) => -x);
    let angle = Math.atan2(dot(w2, inward), dot(w2, w1)) * 180 / Math.PI;
    if (angle < 0) angle += 360;
    dihedrals.push(angle);
    feature.push([a, b]);
  }
  // Smallest angle between two feature edges at a common vertex.
  let minEdgeEdge = 180;
  const around = new Map();
  for (const [a, b] of feature) {
    for (const [u, v] of [[a, b], [b, a]]) {
      if (!around.has(u)) around.set(u, []);
      around.get(u).push(sub(X[v], X[u]));
    }
  }
  for (const dirs of around.values()) {
    for (let i = 0; i < dirs.length; i++) {
      for (let j = i + 1; j < dirs.length; j++) {
        const c = dot(dirs[i], dirs[j]) / norm(dirs[i]) / norm(dirs[j]);
        minEdgeEdge = Math.min(minEdgeEdge, Math.acos(Math.max(-1, Math.min(1, c))) * 180 / Math.PI);
      }
    }
  }
  return {
    points: s.points.length,
    faces: s.faces.length,
    edges: edges.length,
    euler: s.points.length - edges.length + s.faces.length,
    volume,
    minDihedral: Math.min(...dihedrals),
    maxDihedral: Math.max(...dihedrals),
    minEdgeEdge,
  };
}

function toOff(s) {
  const lines = ['OFF', `# ${s.name}.off: ${s.comment}`,
                 '# Written by examples/models/make_models.mjs (wqmesh).', '# SPDX-License-Identifier: GPL-3.0-or-later',
                 `${s.points.length} ${s.faces.length} 0`];
  for (const p of s.points) lines.push(p.join(' '));
  for (const f of s.faces) lines.push(`${f.length} ${f.join(' ')}`);
  return lines.join('\n') + '\n';
}

// ---- Main ------------------------------------------------------------------------

const models = [box(), wedge(), spike(), edgeFacet(), slit(), bracket()];
let failed = false;
for (const s of models) {
  let facts;
  try {
    facts = check(s);
  } catch (e) {
    console.error(`make_models: ${e.message}`);
    failed = true;
    continue;
  }
  const file = join(here, `${s.name}.off`);
  writeFileSync(file, toOff(s));
  const f = (x) => x.toFixed(2);
  console.log(`${s.name}.off: V=${facts.points} F=${facts.faces} E=${facts.edges} ` +
              `Euler=${facts.euler} volume=${facts.volume} dihedral ${f(facts.minDihedral)}..` +
              `${f(facts.maxDihedral)} min edge-edge ${f(facts.minEdgeEdge)} deg`);
}
if (failed) process.exit(1);
