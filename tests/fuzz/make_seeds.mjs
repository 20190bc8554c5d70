// SPDX-License-Identifier: GPL-3.0-or-later
// wqmesh: writes STL seeds for the fuzz targets from the project's own OFF
// models: for every examples/models/NAME.off, OUT/NAME.ascii.stl and
// OUT/NAME.binary.stl with the same surface, each polygon cut into triangles
// (ear clipping in the coordinate plane most parallel to it, orientation
// kept). The models are small, simple polygons; coordinates are written as
// float32 in both files so that ASCII and binary hold the same points.
// Usage: node tests/fuzz/make_seeds.mjs OUT_DIR
import { mkdirSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { basename, dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const out = process.argv[2];
if (!out) {
  console.error('usage: node tests/fuzz/make_seeds.mjs OUT_DIR');
  process.exit(2);
}

/** Parses an OFF file into { points: [[x,y,z]], faces: [[i...]] } (no checks beyond need). */
function parseOff(text) {
  const tokens = text
    .split('\n')
    .map((l) => l.replace(/#.*/, ''))
    .join(' ')
    .split(/\s+/)
    .filter((t) => t.length > 0);
  let at = 1; // after the header keyword
  const nv = Number(tokens[at++]);
  const nf = Number(tokens[at++]);
  at++; // edge count
  const points = [];
  for (let i = 0; i < nv; i++) points.push([0, 1, 2].map((k) => Number(tokens[at + k]))), (at += 3);
  const faces = [];
  for (let f = 0; f < nf; f++) {
    const n = Number(tokens[at++]);
    faces.push(tokens.slice(at, at + n).map(Number));
    at += n;
  }
  return { points, faces };
}

/** Triangles of the simple polygon `face` (indices), counter-clockwise as the polygon is. */
function triangulate(points, face) {
  // Newell normal: the dropped axis is its largest component.
  const nrm = [0, 0, 0];
  for (let i = 0; i < face.length; i++) {
    const p = points[face[i]];
    const q = points[face[(i + 1) % face.length]];
    nrm[0] += (p[1] - q[1]) * (p[2] + q[2]);
    nrm[1] += (p[2] - q[2]) * (p[0] + q[0]);
    nrm[2] += (p[0] - q[0]) * (p[1] + q[1]);
  }
  const axis = [0, 1, 2].reduce((a, b) => (Math.abs(nrm[b]) > Math.abs(nrm[a]) ? b : a));
  const u = (axis + 1) % 3;
  const v = (axis + 2) % 3;
  const sense = nrm[axis] > 0 ? 1 : -1;
  const at = (i) => [points[i][u], points[i][v]];
  const cross = (a, b, c) => sense * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  const ring = face.slice();
  const tris = [];
  while (ring.length > 3) {
    let clipped = false;
    for (let i = 0; i < ring.length && !clipped; i++) {
      const a = ring[(i + ring.length - 1) % ring.length];
      const b = ring[i];
      const c = ring[(i + 1) % ring.length];
      if (cross(at(a), at(b), at(c)) <= 0) continue;
      const inside = ring.some(
        (r) => r !== a && r !== b && r !== c &&
          cross(at(a), at(b), at(r)) >= 0 && cross(at(b), at(c), at(r)) >= 0 && cross(at(c), at(a), at(r)) >= 0,
      );
      if (inside) continue;
      tris.push([a, b, c]);
      ring.splice(i, 1);
      clipped = true;
    }
    if (!clipped) throw new Error(`polygon ${face.join(' ')} has no ear`);
  }
  tris.push(ring);
  return tris;
}

const f32 = (x) => Math.fround(x);

function asciiStl(name, points, tris) {
  const lines = [`solid ${name}`];
  for (const t of tris) {
    lines.push('  facet normal 0 0 0', '    outer loop');
    for (const i of t) lines.push(`      vertex ${points[i].map(f32).join(' ')}`);
    lines.push('    endloop', '  endfacet');
  }
  lines.push(`endsolid ${name}`, '');
  return lines.join('\n');
}

function binaryStl(name, points, tris) {
  const buf = Buffer.alloc(84 + 50 * tris.length);
  buf.write(`binary STL of ${name}, written by tests/fuzz/make_seeds.mjs`.slice(0, 80), 0, 'latin1');
  buf.writeUInt32LE(tris.length, 80);
  tris.forEach((t, k) => {
    const rec = 84 + 50 * k; // normal (left 0), three corners, attribute count (0)
    t.forEach((i, c) => points[i].forEach((x, d) => buf.writeFloatLE(x, rec + 12 + 12 * c + 4 * d)));
  });
  return buf;
}

mkdirSync(out, { recursive: true });
const models = join(root, 'examples', 'models');
let written = 0;
for (const file of readdirSync(models).filter((f) => f.endsWith('.off')).sort()) {
  const name = basename(file, '.off');
  const { points, faces } = parseOff(readFileSync(join(models, file), 'utf8'));
  const tris = faces.flatMap((face) => triangulate(points, face));
  writeFileSync(join(out, `${name}.ascii.stl`), asciiStl(name, points, tris));
  writeFileSync(join(out, `${name}.binary.stl`), binaryStl(name, points, tris));
  written += 2;
}
console.log(`make_seeds: ${written} STL seeds in ${out}`);
