// wqmesh: one wasm meshing run in its own Node process, for the benchmark
// (examples/node/benchmark.mjs), so that each run has its own time limit and
// peak memory. Loads the wasm module through wasm/index.mjs, meshes IN with
// loadWqmesh().mesh(bytes, options), writes the interior tets as Medit and
// the statistics (with wall_mesh_s, the time of the mesh() call,
// peak_rss_mb, this process's peak resident memory, and wasm_heap_mb, the
// module's memory after the run, which only grows: the run's peak) as JSON.
// Usage: node examples/node/wasm_runner.mjs IN OUT.mesh STATS.json
//          [--module build/wasm/wasm/wqmesh.mjs] [--max-vertices N] [--max-size H]
// Exit codes as the command line's: 0 done, 1 usage or internal error,
// 2 invalid input, 3 stopped by the vertex limit or out of wasm memory.
// SPDX-License-Identifier: GPL-3.0-or-later
import { closeSync, openSync, readFileSync, writeFileSync, writeSync } from 'node:fs';
import { resolve } from 'node:path';
import { performance } from 'node:perf_hooks';
import { pathToFileURL } from 'node:url';
import { loadWqmesh } from '../../wasm/index.mjs';

const usage = 'usage: node examples/node/wasm_runner.mjs IN OUT.mesh STATS.json ' +
  '[--module FILE] [--max-vertices N] [--max-size H]';
const args = process.argv.slice(2);
const positional = [];
const options = {};
let moduleUrl;
for (let i = 0; i < args.length; ++i) {
  const a = args[i];
  const value = () => {
    if (i + 1 >= args.length) fail(1, `${a} needs a value\n${usage}`);
    return args[++i];
  };
  if (a === '--module') moduleUrl = pathToFileURL(resolve(value())).href;
  else if (a === '--max-vertices') options.maxVertices = Number(value());
  else if (a === '--max-size') options.maxSize = Number(value());
  else if (a.startsWith('-')) fail(1, `unknown option '${a}'\n${usage}`);
  else positional.push(a);
}
if (positional.length !== 3) fail(1, usage);
const [input, out, statsPath] = positional;

function fail(code, message) {
  process.stderr.write(`wasm_runner: ${message}\n`);
  process.exit(code);
}

/** Writes the interior tets as Medit (1-based), in chunks. */
function writeMedit(path, vertices, tets) {
  const fd = openSync(path, 'w');
  const n = vertices.length / 3, m = tets.length / 4;
  let lines = [`MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n${n}`];
  const flush = (force) => {
    if (force || lines.length >= 65536) {
      writeSync(fd, `${lines.join('\n')}\n`);
      lines = [];
    }
  };
  for (let i = 0; i < n; ++i) {
    lines.push(`${vertices[3 * i]} ${vertices[3 * i + 1]} ${vertices[3 * i + 2]} 0`);
    flush(false);
  }
  lines.push(`\nTetrahedra\n${m}`);
  for (let i = 0; i < m; ++i) {
    lines.push(`${tets[4 * i] + 1} ${tets[4 * i + 1] + 1} ${tets[4 * i + 2] + 1} ${tets[4 * i + 3] + 1} 1`);
    flush(false);
  }
  lines.push('\nEnd');
  flush(true);
  closeSync(fd);
}

let bytes;
try {
  bytes = readFileSync(input);
} catch (e) {
  fail(2, `cannot open '${input}': ${e.message}`);
}
const wqmesh = await loadWqmesh(moduleUrl ? { moduleUrl } : {});
const t0 = performance.now();
let result;
try {
  result = wqmesh.mesh(bytes, options);
} catch (e) {
  const code = e.kind === 'internal' ? 1 : (e.kind === 'limit' ? 3 : 2);
  fail(code, e.message);
}
const wallMesh = (performance.now() - t0) / 1000;
const stats = { ...result.stats, wall_mesh_s: wallMesh };
if (stats.conforming) writeMedit(out, result.vertices, result.tets);
stats.peak_rss_mb = process.resourceUsage().maxRSS / 1024;
stats.wasm_heap_mb = result.memory.heapBytes / 1048576;
writeFileSync(statsPath, `${JSON.stringify(stats, null, 2)}\n`);
if (stats.stopped) fail(3, `stopped: ${stats.stopped}${stats.stop_message ? `: ${stats.stop_message}` : ''}`);
if (!stats.conforming) fail(1, 'the mesh does not conform to the input; not written');
