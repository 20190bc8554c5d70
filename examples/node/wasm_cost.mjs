// wqmesh: where the time of a wasm run goes, against the native command line,
// in paired, alternating runs (native, package 1, package 2, native, ...), each
// in a fresh process, so that a machine whose speed drifts moves every side.
// A measurement, not a test. Per run of a package it records:
//   start-up: import of wqmesh.mjs and instantiation of the module (with a
//             separate wqmesh.wasm: compile, the WebAssembly.compile of its
//             bytes, apart);
//   core:     the run's own stats.time_s (reading, checking, meshing), and
//             the time of each phase;
//   call:     the module's mesh() call as a whole; call - core is what the
//             bindings add (options, copying the input into the heap, the
//             stats JSON, the result arrays copied out of the heap);
//   parse:    JSON.parse of the stats;
//   --calls N: N mesh() calls in the same process, one after the other (the
//             1st is cold: V8 compiles and tiers up the code as it runs; the
//             later ones are warm);
//   --cpu:    CPU seconds as well, for a machine loaded by others, where wall
//             times swing with the load (Linux only: /proc, /usr/bin/time):
//             native, the command line's user + system (one thread); wasm,
//             the main thread's CPU during each mesh() call (10 ms ticks) and
//             that of all the process's threads (V8's background compiler
//             threads included: on a quiet machine the wall time follows
//             this one);
//   --worker: after the calls, mesh() of the package's index.mjs in a fresh
//             worker_threads worker: worker start-up, module load, posting
//             the input, the run and the transfer of the result, as the
//             caller sees it (worker - its core is the worker's cost);
//   --flags:  V8 flags for the wasm processes, e.g. "--no-liftoff".
// A package is a folder holding index.mjs, core.mjs, worker.mjs, options.mjs
// and wqmesh.mjs (and wqmesh.wasm, unless the module is a single file), e.g.
// wasm/ of a checkout after scripts/build.sh wasm.
// Usage: node examples/node/wasm_cost.mjs [--runs N] [--calls N] [--cpu] [--worker]
//          [--flags "V8 FLAGS"] [--cli BIN] [--pkg DIR]... MODEL...
//   defaults: --runs 3, --calls 1, --cli build/native/bin/wqmesh, --pkg wasm
// SPDX-License-Identifier: GPL-3.0-or-later
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { median, nativeRun, pairArgs, spread } from './wasm_pairs.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const args = process.argv.slice(2);

// ---- The child: the calls of one package on one model, figures as JSON on stdout.
if (args[0] === '--child') {
  const [, pkg, model, worker = '-', calls = '1'] = args;  // (a profile: --child PKG MODEL)
  const bytes = readFileSync(model);
  // utime + stime of the main thread, s (fields 14 and 15 of its stat line).
  const mainCpu = () => {
    const s = readFileSync(`/proc/self/task/${process.pid}/stat`, 'utf8');
    const f = s.slice(s.lastIndexOf(')') + 2).split(' ');
    return (Number(f[11]) + Number(f[12])) / 100;
  };
  const allCpu = () => {
    const c = process.cpuUsage();
    return (c.user + c.system) / 1e6;
  };
  const out = {};
  let t = performance.now();
  const factory = (await import(pathToFileURL(join(pkg, 'wqmesh.mjs')).href)).default;
  let module;
  const wasmFile = join(pkg, 'wqmesh.wasm');
  if (existsSync(wasmFile)) {
    const wasmBytes = readFileSync(wasmFile);
    const c = performance.now();
    const compiled = await WebAssembly.compile(wasmBytes);
    out.compile = (performance.now() - c) / 1000;
    module = await factory({
      instantiateWasm(imports, receive) {
        WebAssembly.instantiate(compiled, imports).then((instance) => receive(instance, compiled));
        return {};
      },
    });
  } else {
    module = await factory();
  }
  out.startup = (performance.now() - t) / 1000;
  out.calls = [];
  for (let k = 0; k < Number(calls); ++k) {
    const m0 = mainCpu();
    const a0 = allCpu();
    t = performance.now();
    const r = module.mesh(bytes, {}, undefined);
    const call = (performance.now() - t) / 1000;
    const main = mainCpu() - m0;
    const all = allCpu() - a0;
    if (r.error) throw new Error(`${r.error.kind}: ${r.error.message}`);
    t = performance.now();
    const stats = JSON.parse(r.stats);
    const parse = (performance.now() - t) / 1000;
    out.calls.push({ call, parse, main, all, core: stats.time_s, tets: stats.tets,
                     phases: Object.fromEntries(stats.phases.map((p) => [p.name, p.time_s])) });
  }
  out.heap_mb = module.memoryStats().heapBytes / 1048576;
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
let worker = false;
let cpu = false;
let flags = [];
const { runs, calls, cli, pkgs, models } = pairArgs(args, {
  root,
  usage: 'usage: node examples/node/wasm_cost.mjs [--runs N] [--calls N] [--cpu] [--worker] [--flags "V8 FLAGS"] ' +
         '[--cli BIN] [--pkg DIR]... MODEL...',
  flags: {
    '--worker': () => { worker = true; },
    '--cpu': () => { cpu = true; },
    '--flags': (next) => { flags = next().split(/\s+/).filter(Boolean); },
  },
});

const work = mkdtempSync(join(tmpdir(), 'wqmesh-cost-'));
const native = (model) => nativeRun(cli, model, work, cpu);
function wasm(pkg, model) {
  const t = performance.now();
  const r = spawnSync(process.execPath, [...flags, fileURLToPath(import.meta.url), '--child', pkg, model, worker ? 'worker' : '-',
                                         String(calls)], { encoding: 'utf8', maxBuffer: 1 << 24 });
  const wall = (performance.now() - t) / 1000;
  if (r.status !== 0) throw new Error(`wasm ${pkg} ${model}: exit ${r.status}: ${r.stderr}`);
  return { wall, ...JSON.parse(r.stdout) };
}

console.log(`runs ${runs}, paired and alternating; figures: median [min-max] in s; ratios: median of the pairs' ratios` +
            (flags.length ? `; wasm under node ${flags.join(' ')}` : ''));
for (const model of models) {
  const n = [];
  const w = pkgs.map(() => []);
  for (let k = 0; k < runs; ++k) {
    n.push(native(model));
    pkgs.forEach((p, j) => w[j].push(wasm(p, model)));
  }
  console.log(`\n${basename(model)}: ${n[0].tets} tets; native core ${spread(n.map((x) => x.core))}, ` +
              `process ${spread(n.map((x) => x.wall))}${cpu ? `, cpu ${spread(n.map((x) => x.cpu))}` : ''}`);
  pkgs.forEach((p, j) => {
    const xs = w[j];
    const ratio = (f, g = (y) => y.core) => median(xs.map((x, k) => f(x) / g(n[k]))).toFixed(3);
    const tets = xs[0].calls[0].tets;
    console.log(`  ${p}: ${tets} tets${tets === n[0].tets ? '' : ' (NOT the native count)'}`);
    console.log(`    start-up ${spread(xs.map((x) => x.startup))}` +
                (xs[0].compile !== undefined ? ` (WebAssembly.compile ${spread(xs.map((x) => x.compile))})` : '') +
                `, process ${spread(xs.map((x) => x.wall))}, heap ${xs[0].heap_mb} MB`);
    for (let c = 0; c < calls; ++c) {
      const at = (x) => x.calls[c];
      console.log(`    call ${c + 1}: core ${spread(xs.map((x) => at(x).core))}, wasm/native ${ratio((x) => at(x).core)}; ` +
                  `call - core ${spread(xs.map((x) => at(x).call - at(x).core))}, stats parse ${spread(xs.map((x) => at(x).parse))}`);
      if (cpu) {
        console.log(`      cpu: main thread ${spread(xs.map((x) => at(x).main))}, /native cpu ${ratio((x) => at(x).main, (y) => y.cpu)}; ` +
                    `all threads ${spread(xs.map((x) => at(x).all))}, /native cpu ${ratio((x) => at(x).all, (y) => y.cpu)}`);
      }
      for (const ph of Object.keys(at(xs[0]).phases))
        console.log(`      ${ph.padEnd(10)} wasm ${spread(xs.map((x) => at(x).phases[ph]))}, native ${spread(n.map((x) => x.phases[ph]))}, ` +
                    `ratio ${median(xs.map((x, k) => at(x).phases[ph] / n[k].phases[ph])).toFixed(2)}`);
    }
    if (worker)
      console.log(`    worker mesh() ${spread(xs.map((x) => x.worker))} (minus its core ${spread(xs.map((x) => x.worker - x.worker_core))}), ` +
                  `worker core/native ${ratio((x) => x.worker_core)}`);
  });
}
rmSync(work, { recursive: true, force: true });
