// wqmesh: wasm against native in CPU time, for a machine loaded by others,
// where wall times swing with the load (BENCHMARKS.md, "Build levers").
// Paired, alternating runs (native, package 1, package 2, native, ...), each
// in a fresh process. A measurement, not a test; Linux only (/proc). Per run:
//   native: user + system CPU of the command line's process (single-threaded;
//           read with /usr/bin/time) and its stats.time_s;
//   wasm:   the CPU of the main thread during the module's mesh() call (from
//           /proc/self/task/PID/stat, 10 ms ticks); the CPU of all threads
//           of the process during the call (with V8's background compiler
//           threads: on a quiet machine the wall time was this one, not the
//           main thread's), and the run's stats.time_s (wall).
// A package is a folder holding wqmesh.mjs (e.g. wasm/ of a checkout).
// Usage: node examples/node/wasm_cpu.mjs [--runs N] [--cli BIN] [--pkg DIR]... MODEL...
//   defaults: --runs 3, --cli build/native/bin/wqmesh, --pkg wasm
// SPDX-License-Identifier: GPL-3.0-or-later
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const args = process.argv.slice(2);

// ---- The child: one mesh() of one package on one model, figures as JSON.
if (args[0] === '--child') {
  const [, pkg, model] = args;
  const bytes = readFileSync(model);
  // utime + stime of one thread, s (fields 14 and 15 of its stat line).
  const mainCpu = () => {
    const s = readFileSync(`/proc/self/task/${process.pid}/stat`, 'utf8');
    const f = s.slice(s.lastIndexOf(')') + 2).split(' ');
    return (Number(f[11]) + Number(f[12])) / 100;
  };
  const allCpu = () => {
    const c = process.cpuUsage();
    return (c.user + c.system) / 1e6;
  };
  const factory = (await import(pathToFileURL(join(pkg, 'wqmesh.mjs')).href)).default;
  const module = await factory();
  const m0 = mainCpu();
  const a0 = allCpu();
  const r = module.mesh(bytes, {}, undefined);
  const main = mainCpu() - m0;
  const all = allCpu() - a0;
  if (r.error) throw new Error(`${r.error.kind}: ${r.error.message}`);
  const stats = JSON.parse(r.stats);
  process.stdout.write(JSON.stringify({ main, all, core: stats.time_s, tets: stats.tets }));
  process.exit(0);
}

// ---- The parent.
let runs = 3;
let cli = join(root, 'build/native/bin/wqmesh');
const pkgs = [];
const models = [];
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--runs') runs = Number(args[++i]);
  else if (args[i] === '--cli') cli = resolve(args[++i]);
  else if (args[i] === '--pkg') pkgs.push(resolve(args[++i]));
  else models.push(resolve(args[i]));
}
if (!pkgs.length) pkgs.push(join(root, 'wasm'));
if (!models.length || !(runs >= 1)) {
  console.error('usage: node examples/node/wasm_cpu.mjs [--runs N] [--cli BIN] [--pkg DIR]... MODEL...');
  process.exit(1);
}

const work = mkdtempSync(join(tmpdir(), 'wqmesh-cpu-'));
function native(model) {
  const stats = join(work, 'stats.json');
  const r = spawnSync('/usr/bin/time', ['-f', '%U %S', cli, 'mesh', model, '-o', join(work, 'out.mesh'), '--stats', stats,
                                         '--quiet'], { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`native ${model}: exit ${r.status}: ${r.stderr}`);
  const [user, sys] = r.stderr.trim().split('\n').pop().split(' ').map(Number);
  const s = JSON.parse(readFileSync(stats, 'utf8'));
  return { cpu: user + sys, core: s.time_s, tets: s.tets };
}
function wasm(pkg, model) {
  const r = spawnSync(process.execPath, [fileURLToPath(import.meta.url), '--child', pkg, model], { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`wasm ${pkg} ${model}: exit ${r.status}: ${r.stderr}`);
  return JSON.parse(r.stdout);
}

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const spread = (xs) => `${median(xs).toFixed(2)} [${Math.min(...xs).toFixed(2)}-${Math.max(...xs).toFixed(2)}]`;
console.log(`runs ${runs}, paired and alternating; figures: median [min-max] in s; ratios: median of the pairs' ratios`);
for (const model of models) {
  const n = [];
  const w = pkgs.map(() => []);
  for (let k = 0; k < runs; ++k) {
    n.push(native(model));
    pkgs.forEach((p, j) => w[j].push(wasm(p, model)));
  }
  console.log(`\n${basename(model)}: ${n[0].tets} tets; native cpu ${spread(n.map((x) => x.cpu))}, ` +
              `time_s ${spread(n.map((x) => x.core))}`);
  pkgs.forEach((p, j) => {
    const xs = w[j];
    const ratio = (f, g) => median(xs.map((x, k) => f(x) / g(n[k]))).toFixed(3);
    console.log(`  ${p}: ${xs[0].tets} tets${xs[0].tets === n[0].tets ? '' : ' (NOT the native count)'}`);
    console.log(`    main thread ${spread(xs.map((x) => x.main))}, /native cpu ${ratio((x) => x.main, (y) => y.cpu)}`);
    console.log(`    all threads ${spread(xs.map((x) => x.all))}, /native cpu ${ratio((x) => x.all, (y) => y.cpu)}`);
    console.log(`    time_s      ${spread(xs.map((x) => x.core))}, /native time_s ${ratio((x) => x.core, (y) => y.core)}`);
  });
}
rmSync(work, { recursive: true, force: true });
