// wqmesh: where the time of a wasm run goes, against the native command line,
// in paired, alternating runs (native, package 1, package 2, native, ...), each
// in a fresh process, so that a machine whose speed drifts moves every side.
// A measurement, not a test. Per run of a package it records:
//   start-up: import of wqmesh.mjs and instantiation of the module;
//   core:     the run's own stats.time_s (reading, checking, meshing), and
//             the time of each phase;
//   call:     the module's mesh() call as a whole; call - core is what the
//             bindings add (options, copying the input into the heap, the
//             stats JSON, the result arrays copied out of the heap);
//   parse:    JSON.parse of the stats;
//   worker:   with --worker, mesh() of the package's index.mjs, in a fresh
//             worker_threads worker: worker start-up, module load, posting
//             the input, the run and the transfer of the result, as the
//             caller sees it (worker - its core is the worker's cost).
// A package is a folder holding index.mjs, core.mjs, worker.mjs, options.mjs
// and wqmesh.mjs (e.g. wasm/ of a checkout after scripts/build.sh wasm).
// Usage: node examples/node/wasm_cost.mjs [--runs N] [--worker] [--cli BIN]
//          [--pkg DIR]... MODEL...
//   defaults: --runs 3, --cli build/native/bin/wqmesh, --pkg wasm
// SPDX-License-Identifier: GPL-3.0-or-later
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const args = process.argv.slice(2);

// ---- The child: one run of one package on one model, figures as JSON on stdout.
if (args[0] === '--child') {
  const [, pkg, model, worker] = args;
  const bytes = readFileSync(model);
  let t = performance.now();
  const factory = (await import(pathToFileURL(join(pkg, 'wqmesh.mjs')).href)).default;
  const module = await factory();
  const startup = (performance.now() - t) / 1000;
  t = performance.now();
  const r = module.mesh(bytes, {}, undefined);
  const call = (performance.now() - t) / 1000;
  if (r.error) throw new Error(`${r.error.kind}: ${r.error.message}`);
  t = performance.now();
  const stats = JSON.parse(r.stats);
  const parse = (performance.now() - t) / 1000;
  const out = {
    startup, call, parse, core: stats.time_s, tets: stats.tets, heap_mb: module.memoryStats().heapBytes / 1048576,
    phases: Object.fromEntries(stats.phases.map((p) => [p.name, p.time_s])),
  };
  if (worker === 'worker') {
    const { mesh } = await import(pathToFileURL(join(pkg, 'index.mjs')).href);
    t = performance.now();
    const w = await mesh(bytes);
    out.worker = (performance.now() - t) / 1000;
    out.worker_core = w.stats.time_s;
  }
  process.stdout.write(JSON.stringify(out));
  process.exit(0);
}

// ---- The parent.
let runs = 3;
let worker = false;
let cli = join(root, 'build/native/bin/wqmesh');
const pkgs = [];
const models = [];
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--runs') runs = Number(args[++i]);
  else if (args[i] === '--worker') worker = true;
  else if (args[i] === '--cli') cli = resolve(args[++i]);
  else if (args[i] === '--pkg') pkgs.push(resolve(args[++i]));
  else models.push(resolve(args[i]));
}
if (!pkgs.length) pkgs.push(join(root, 'wasm'));
if (!models.length || !(runs >= 1)) {
  console.error('usage: node examples/node/wasm_cost.mjs [--runs N] [--worker] [--cli BIN] [--pkg DIR]... MODEL...');
  process.exit(1);
}

const work = mkdtempSync(join(tmpdir(), 'wqmesh-cost-'));
function native(model) {
  const stats = join(work, 'stats.json');
  const t = performance.now();
  const r = spawnSync(cli, ['mesh', model, '-o', join(work, 'out.mesh'), '--stats', stats, '--quiet'], { encoding: 'utf8' });
  const wall = (performance.now() - t) / 1000;
  if (r.status !== 0) throw new Error(`native ${model}: exit ${r.status}: ${r.stderr}`);
  const s = JSON.parse(readFileSync(stats, 'utf8'));
  return { wall, core: s.time_s, tets: s.tets, phases: Object.fromEntries(s.phases.map((p) => [p.name, p.time_s])) };
}
function wasm(pkg, model) {
  const t = performance.now();
  const r = spawnSync(process.execPath, [fileURLToPath(import.meta.url), '--child', pkg, model, worker ? 'worker' : ''],
                      { encoding: 'utf8', maxBuffer: 1 << 24 });
  const wall = (performance.now() - t) / 1000;
  if (r.status !== 0) throw new Error(`wasm ${pkg} ${model}: exit ${r.status}: ${r.stderr}`);
  return { wall, ...JSON.parse(r.stdout) };
}

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const spread = (xs) => `${median(xs).toFixed(3)} [${Math.min(...xs).toFixed(3)}-${Math.max(...xs).toFixed(3)}]`;
console.log(`runs ${runs}, paired and alternating; figures: median [min-max] in s; ratios: median of the pairs' ratios`);
for (const model of models) {
  const n = [];
  const w = pkgs.map(() => []);
  for (let k = 0; k < runs; ++k) {
    n.push(native(model));
    pkgs.forEach((p, j) => w[j].push(wasm(p, model)));
  }
  console.log(`\n${basename(model)}: ${n[0].tets} tets; native core ${spread(n.map((x) => x.core))}, ` +
              `process ${spread(n.map((x) => x.wall))}`);
  pkgs.forEach((p, j) => {
    const xs = w[j];
    const ratio = (f) => median(xs.map((x, k) => f(x) / n[k].core)).toFixed(2);
    console.log(`  ${p}: ${xs[0].tets} tets${xs[0].tets === n[0].tets ? '' : ' (NOT the native count)'}`);
    console.log(`    core ${spread(xs.map((x) => x.core))}, wasm/native ${ratio((x) => x.core)}`);
    console.log(`    call ${spread(xs.map((x) => x.call))} (call - core ${spread(xs.map((x) => x.call - x.core))}), ` +
                `call/native ${ratio((x) => x.call)}`);
    console.log(`    start-up ${spread(xs.map((x) => x.startup))}, stats parse ${spread(xs.map((x) => x.parse))}, ` +
                `process ${spread(xs.map((x) => x.wall))}, heap ${xs[0].heap_mb} MB`);
    for (const ph of Object.keys(xs[0].phases))
      console.log(`    ${ph.padEnd(10)} wasm ${spread(xs.map((x) => x.phases[ph]))}, native ${spread(n.map((x) => x.phases[ph]))}, ` +
                  `ratio ${median(xs.map((x, k) => x.phases[ph] / n[k].phases[ph])).toFixed(2)}`);
    if (worker)
      console.log(`    worker mesh() ${spread(xs.map((x) => x.worker))} (minus its core ${spread(xs.map((x) => x.worker - x.worker_core))}), ` +
                  `worker core/native ${ratio((x) => x.worker_core)}`);
  });
}
rmSync(work, { recursive: true, force: true });
