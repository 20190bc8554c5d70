// wqmesh: meshes every OFF and STL file of a folder through the npm package
// (one worker, reused from one model to the next), printing a progress line
// per file and writing MODEL.vtu beside each one in OUT (when given). A file
// that is not a valid polyhedron gets its error code and message, and the
// others go on. Ctrl-C stops the current run at once.
// Usage: node examples/node/mesh_folder.mjs FOLDER [--out OUT] [--max-vertices N]
// Exit code 0 when every file meshed (or stopped at the vertex limit), 2 when
// some were invalid, 1 on a usage error.
// SPDX-License-Identifier: GPL-3.0-or-later
import { mkdir, readFile, readdir, writeFile } from 'node:fs/promises';
import { basename, extname, join } from 'node:path';

import { WqmeshError, mesh, writeVtu } from 'wqmesh';

const args = process.argv.slice(2);
let folder = '';
let out = '';
const options = {};
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--out') out = args[++i];
  else if (args[i] === '--max-vertices') options.maxVertices = Number(args[++i]);
  else if (!folder) folder = args[i];
}
if (!folder) {
  console.error('usage: node examples/node/mesh_folder.mjs FOLDER [--out OUT] [--max-vertices N]');
  process.exit(1);
}
if (out) await mkdir(out, { recursive: true });

const controller = new AbortController();
process.on('SIGINT', () => controller.abort());
const files = (await readdir(folder)).filter((f) => /\.(off|stl)$/i.test(f)).sort();
let invalid = 0;
for (const [k, file] of files.entries()) {
  const tag = `[${k + 1}/${files.length}] ${file}`;
  const started = Date.now();
  try {
    const r = await mesh(await readFile(join(folder, file)), options, { signal: controller.signal });
    const s = r.stats;
    if (out && s.conforming) await writeFile(join(out, `${basename(file, extname(file))}.vtu`), await writeVtu(r, { bytes: true }));
    console.log(`${tag}: ${s.vertices} vertices, ${s.tets} tets, ${s.slivers} slivers, ${s.violations} violations, ` +
                `${((Date.now() - started) / 1000).toFixed(2)} s${s.stopped ? ` (stopped: ${s.stopped})` : ''}`);
  } catch (e) {
    if (e.name === 'AbortError') {
      console.log(`${tag}: interrupted`);
      process.exit(130);
    }
    if (!(e instanceof WqmeshError)) throw e;
    ++invalid;
    console.log(`${tag}: ${e.message}`);
  }
}
process.exitCode = invalid ? 2 : 0;
