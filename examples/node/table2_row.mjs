// wqmesh: meshes one model through the npm package (`import { mesh } from
// 'wqmesh'`, in a worker) and prints its row of the paper's Table 2: input
// points, sharp elements, points inserted, the tets by R/l (0.6-1.4,
// 1.4-2.2, above 2.2) and by smallest dihedral angle (0-3, 3-5, 5-10
// degrees), with the slivers before and after PUMP and the time.
// Usage: node examples/node/table2_row.mjs MODEL [--json] [--max-vertices N] [--no-pump]
// SPDX-License-Identifier: GPL-3.0-or-later
import { readFile } from 'node:fs/promises';
import { basename } from 'node:path';

import { mesh } from 'wqmesh';

const args = process.argv.slice(2);
const options = {};
let json = false;
let model = '';
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--json') json = true;
  else if (args[i] === '--no-pump') options.pump = false;
  else if (args[i] === '--max-vertices') options.maxVertices = Number(args[++i]);
  else if (!model) model = args[i];
  else {
    console.error(`table2_row: unexpected argument '${args[i]}'`);
    process.exit(1);
  }
}
if (!model) {
  console.error('usage: node examples/node/table2_row.mjs MODEL [--json] [--max-vertices N] [--no-pump]');
  process.exit(1);
}

const s = (await mesh(await readFile(model), options)).stats;
const row = {
  model: basename(model),
  input_points: s.input_points,
  sharp_elements: s.sharp_elements,
  points_inserted: s.points_inserted,
  tets: s.tets,
  radius_edge: [s.radius_edge_bins['0.6-1.4'], s.radius_edge_bins['1.4-2.2'], s.radius_edge_bins['>2.2']],
  dihedral: [s.dihedral_bins['0-3'], s.dihedral_bins['3-5'], s.dihedral_bins['5-10']],
  slivers_before_pump: s.slivers_before_pump,
  slivers: s.slivers,
  stopped: s.stopped,
  time_s: s.time_s,
};
if (json) {
  console.log(JSON.stringify(row));
} else {
  console.log('model            points sharp inserted    tets | R/l 0.6-1.4 1.4-2.2  >2.2 | dih 0-3  3-5  5-10 | slivers before/after   time');
  console.log(`${row.model.padEnd(16)} ${String(row.input_points).padStart(6)} ${String(row.sharp_elements).padStart(5)} ` +
              `${String(row.points_inserted).padStart(8)} ${String(row.tets).padStart(7)} | ` +
              `${row.radius_edge.map((n, k) => String(n).padStart(k === 2 ? 5 : 7)).join(' ')}     | ` +
              `${row.dihedral.map((n) => String(n).padStart(4)).join(' ')}  | ` +
              `${String(row.slivers_before_pump).padStart(7)} / ${String(row.slivers).padStart(5)}  ${row.time_s.toFixed(2)} s` +
              (row.stopped ? `  (stopped: ${row.stopped})` : ''));
}
