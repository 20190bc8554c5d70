// wqmesh: the paper's tables for every closed model. For each model of
// ../shared/models (the broken ones excepted) and examples/models, meshes it
// with the native command line twice, with PUMP off (QMESH alone) and on
// (WQMESH), and prints:
//   Table 2: input points, sharp elements, points inserted, R/l bins,
//            smallest-dihedral bins (of the WQMESH mesh);
//   Table 1: slivers with PUMP off and on;
//   and time, tets, tets per second, peak memory, violations, and the ratio
//   of the whole run to a plain Delaunay triangulation of the final vertex
//   set ("x Del", the floor no refinement can beat).
// Usage: node examples/node/tables.mjs [--timeout SECONDS] [--max-vertices N] [MODEL ...]
// SPDX-License-Identifier: GPL-3.0-or-later
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, readdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const cli = join(root, 'build', 'native', 'bin', 'wqmesh');
const shared = join(root, '..', 'shared', 'models');
const broken = new Set(['cubes.off', 'cube-ouvert.off', 'self_intersecting.off',
  'issue1580-zero-area-triangle.stl', 'bad-stl-pcbvicebar.stl']);

const args = process.argv.slice(2);
let timeout = 300;
let maxVertices = 1000000;
const named = [];
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--timeout') timeout = Number(args[++i]);
  else if (args[i] === '--max-vertices') maxVertices = Number(args[++i]);
  else named.push(args[i]);
}
if (!existsSync(cli)) {
  console.error(`tables: ${cli} is missing: run bash scripts/build.sh native`);
  process.exit(1);
}

const list = (dir) => existsSync(dir)
  ? readdirSync(dir).filter((f) => /\.(off|stl)$/i.test(f) && !broken.has(f)).sort().map((f) => join(dir, f))
  : [];
const models = named.length ? named : [...list(shared), ...list(join(root, 'examples', 'models'))];
const work = mkdtempSync(join(tmpdir(), 'wqmesh-tables-'));

function run(model, pump) {
  const stats = join(work, `${basename(model)}.${pump ? 'on' : 'off'}.json`);
  const argv = ['mesh', model, '-o', join(work, 'out.mesh'), '--stats', stats, '--quiet',
    '--max-vertices', String(maxVertices)];
  if (!pump) argv.push('--no-pump');
  else argv.push('--measure-floor');
  const r = spawnSync(cli, argv, { timeout: timeout * 1000, encoding: 'utf8' });
  if (r.error && r.error.code === 'ETIMEDOUT') return { failed: `timeout ${timeout} s` };
  if (!existsSync(stats)) return { failed: (r.stderr || '').trim().split('\n').pop() };
  const s = JSON.parse(readFileSync(stats, 'utf8'));
  if (s.stopped) s.failed = `stopped: ${s.stopped}`;
  else if (!s.conforming) s.failed = 'not conforming';
  return s;
}

const pad = (v, n) => String(v).padStart(n);
console.log(`wqmesh tables: rho0 2.2, theta 3 deg, timeout ${timeout} s, max vertices ${maxVertices}`);
console.log(['model'.padEnd(24), pad('in pts', 7), pad('sharp', 6), pad('inserted', 9),
  pad('R/l .6-1.4', 11), pad('1.4-2.2', 8), pad('>2.2', 6), pad('dih 0-3', 8), pad('3-5', 6), pad('5-10', 6),
  pad('QMESH sl', 9), pad('WQMESH sl', 10), pad('viol', 5), pad('tets', 8), pad('time s', 8),
  pad('tets/s', 8), pad('MB', 6), pad('x Del', 6), '  note'].join(' '));
for (const model of models) {
  const off = run(model, false);
  const on = run(model, true);
  const s = on.failed && !on.vertices ? off : on;
  const row = [basename(model).padEnd(24)];
  if (!s.vertices) {
    console.log(`${row[0]} failed: ${on.failed || off.failed}`);
    continue;
  }
  row.push(pad(s.input_points, 7), pad(s.sharp_elements, 6), pad(s.points_inserted, 9),
    pad(s.radius_edge_bins['0.6-1.4'], 11), pad(s.radius_edge_bins['1.4-2.2'], 8), pad(s.radius_edge_bins['>2.2'], 6),
    pad(s.dihedral_bins['0-3'], 8), pad(s.dihedral_bins['3-5'], 6), pad(s.dihedral_bins['5-10'], 6),
    pad(off.vertices ? off.slivers : '-', 9), pad(on.vertices ? on.slivers : '-', 10), pad(s.violations, 5),
    pad(s.tets, 8), pad(s.time_s.toFixed(2), 8), pad(Math.round(s.tets_per_second), 8),
    pad(Math.round(s.peak_memory_mb), 6), pad(s.ratio_to_delaunay ? s.ratio_to_delaunay.toFixed(0) : '-', 6), `  ${[off.failed && `QMESH ${off.failed}`, on.failed && `WQMESH ${on.failed}`].filter(Boolean).join('; ')}`);
  console.log(row.join(' '));
}
