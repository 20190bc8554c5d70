// wqmesh: where a profiled run of `wqmesh mesh` spends its time, by phase and
// by function (issue 15, item 1). Reads a `perf record -g` file (call graphs;
// `--call-graph dwarf` for a build without frame pointers) through
// `perf script` and prints Markdown tables:
//   - the samples of each phase: a sample belongs to the phase whose Mesher
//     method (initialize, conform, refine, pump, extract) is on its stack
//     nearest the root; the extraction before PUMP (it counts QMESH's
//     slivers) is told from the final one by its time (before PUMP's first
//     sample); samples in no phase are reading/checking, writing, or other;
//   - per phase, the functions with the most samples of their own (self) and
//     on the stack under the phase's method (inclusive, each function counted
//     once per sample), as percentages of the whole run. A stack deeper than
//     perf's copy of the stack (dwarf,8192: 8 KB) loses its root, and with it
//     its phase: such samples count as "other".
// A profiling tool, not a test: it asserts nothing.
//
// Usage: node tests/benchmark/perf_phases.mjs PERF.data [--top N] [--inline]
//   --top N: functions per phase and list (default 12); --inline: inlined
//   functions as their own frames (perf script --inline; slow on a large
//   profile, needs debug info).
// SPDX-License-Identifier: GPL-3.0-or-later
import { spawn } from 'node:child_process';
import { createInterface } from 'node:readline';

const args = process.argv.slice(2);
let file = null, top = 12, inline = false;
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--top') top = Number(args[++i]);
  else if (args[i] === '--inline') inline = true;
  else if (!args[i].startsWith('-') && !file) file = args[i];
  else {
    process.stderr.write('usage: node tests/benchmark/perf_phases.mjs PERF.data [--top N] [--inline]\n');
    process.exit(1);
  }
}
if (!file || !(top > 0)) {
  process.stderr.write('usage: node tests/benchmark/perf_phases.mjs PERF.data [--top N] [--inline]\n');
  process.exit(1);
}

/** A function's name without its namespaces wqmesh::(mesher::), template arguments and parameters. */
function short(sym) {
  let s = sym.replace(/\+0x[0-9a-f]+$/, '');
  // Drop template arguments and parameter lists, innermost first.
  for (let k = 0; k < 20; ++k) {
    const t = s.replace(/<[^<>]*>/g, '').replace(/\([^()]*\)/g, '');
    if (t === s) break;
    s = t;
  }
  return s.replace(/\s+const$/, '').replace(/^wqmesh::(mesher::)?/, '').replace(/^(\w+::)*\{lambda\}.*$/, 'lambda')
    .replace(/ \[clone [^\]]*\]/g, '').trim() || sym;
}

const PHASES = ['initialize', 'conform', 'refine', 'pump', 'extract', 'improve'];
const phaseOf = (name) => {
  if (name === 'improve_phase') return 'improve';  // improve.cpp, after PUMP's extraction
  const m = /^Mesher::(initialize|conform|refine|pump|extract)$/.exec(name);
  return m ? m[1] : null;
};

// Per sample: its time, its stack from the leaf to the root (short names).
const samples = [];
let stack = null, time = 0;
const flush = () => {
  if (stack && stack.length) samples.push({ time, stack });
  stack = null;
};
const perf = spawn('perf', ['script', '-i', file, '-F', 'time,ip,sym', ...(inline ? ['--inline'] : ['--no-inline'])],
  { stdio: ['ignore', 'pipe', 'inherit'] });
const lines = createInterface({ input: perf.stdout });
lines.on('line', (line) => {
  if (!line.trim()) { flush(); return; }
  if (!/^\s/.test(line) || /^\s*\d+\.\d+:\s*$/.test(line)) {  // a sample's header: its time
    flush();
    time = Number((/(\d+\.\d+):/.exec(line) || [0, 0])[1]);
    stack = [];
    return;
  }
  const m = /^\s*[0-9a-f]+\s+(.*?)\s*(\([^()]*\))?\s*$/.exec(line);
  if (stack && m) stack.push(short(m[1]));
});
perf.on('close', (code) => {
  flush();
  if (code !== 0 || !samples.length) {
    process.stderr.write(`perf_phases: perf script exited ${code} with ${samples.length} samples\n`);
    process.exit(1);
  }
  report();
});

function report() {
  // The phase of a sample: the phase method nearest the root of its stack.
  const firstPump = Math.min(...samples.filter((s) => s.stack.some((f) => phaseOf(f) === 'pump'))
    .map((s) => s.time), Infinity);
  const byPhase = new Map();
  for (const s of samples) {
    let p = null;
    s.below = s.stack.length;  // the frames under the phase's method (its callees), for the inclusive list
    for (let i = s.stack.length - 1; i >= 0 && !p; --i) {
      p = phaseOf(s.stack[i]);
      if (p) s.below = i;
    }
    if (p === 'extract') p = s.time < firstPump ? 'extract before PUMP' : 'extract (final)';
    if (!p) {
      const all = s.stack.join(' ');
      p = /write|output/i.test(all) ? 'writing' : /analy|read|plc|check|validat/i.test(all)
        ? 'reading and checking' : 'other';
    }
    if (!byPhase.has(p)) byPhase.set(p, []);
    byPhase.get(p).push(s);
  }
  const n = samples.length;
  const pct = (k) => (100 * k / n).toFixed(1);
  const order = ['initialize', 'conform', 'refine', 'extract before PUMP', 'pump', 'extract (final)',
    'improve', 'reading and checking', 'writing', 'other'];
  console.log(`${n} samples (${file})\n`);
  console.log('| phase | samples | % of the run |');
  console.log('|---|---:|---:|');
  for (const p of order) if (byPhase.has(p)) console.log(`| ${p} | ${byPhase.get(p).length} | ${pct(byPhase.get(p).length)} |`);
  for (const p of order) {
    const list = byPhase.get(p);
    if (!list || list.length < n / 100) continue;  // phases under 1% of the run: no breakdown
    const self = new Map(), incl = new Map();
    for (const s of list) {
      self.set(s.stack[0], (self.get(s.stack[0]) || 0) + 1);
      for (const f of new Set(s.stack.slice(0, s.below))) incl.set(f, (incl.get(f) || 0) + 1);
    }
    const best = (m) => [...m].sort((a, b) => b[1] - a[1]).slice(0, top);
    console.log(`\n### ${p}: ${pct(list.length)}% of the run\n`);
    console.log('| self | % | inclusive | % |');
    console.log('|---|---:|---|---:|');
    const s = best(self), c = best(incl);
    for (let i = 0; i < Math.max(s.length, c.length); ++i)
      console.log(`| ${s[i] ? `\`${s[i][0]}\`` : ''} | ${s[i] ? pct(s[i][1]) : ''} | ${c[i] ? `\`${c[i][0]}\`` : ''} | ` +
        `${c[i] ? pct(c[i][1]) : ''} |`);
  }
}
