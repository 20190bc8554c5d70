// wqmesh: what the paired wasm/native measurements share (wasm_cost.mjs in
// Node, wasm_browser.mjs in Chromium): the command line, the native run, the
// medians, and the browser's processes. Not a measurement of its own.
// SPDX-License-Identifier: GPL-3.0-or-later
import { spawnSync } from 'node:child_process';
import { readFileSync, readdirSync } from 'node:fs';
import { join, resolve } from 'node:path';

/**
 * The common arguments: --runs N, --calls N, --cli BIN, --pkg DIR (repeated)
 * and the models; `flags` maps the script's own flags to a handler(next)
 * that takes its value with next(). Exits with `usage` on bad input.
 */
export function pairArgs(args, { root, runs = 3, calls = 1, usage, flags = {} }) {
  const o = { runs, calls, cli: join(root, 'build/native/bin/wqmesh'), pkgs: [], models: [] };
  for (let i = 0; i < args.length; ++i) {
    const next = () => args[++i];
    if (args[i] === '--runs') o.runs = Number(next());
    else if (args[i] === '--calls') o.calls = Number(next());
    else if (args[i] === '--cli') o.cli = resolve(next());
    else if (args[i] === '--pkg') o.pkgs.push(resolve(next()));
    else if (flags[args[i]]) flags[args[i]](next);
    else o.models.push(resolve(args[i]));
  }
  if (!o.pkgs.length) o.pkgs.push(join(root, 'wasm'));
  if (!o.models.length || !(o.runs >= 1) || !(o.calls >= 1)) {
    console.error(usage);
    process.exit(1);
  }
  return o;
}

/**
 * One run of the native command line on `model` in folder `work`: its
 * stats.time_s, tets and phases, the process's wall time and, with `cpu`,
 * its user + system CPU seconds (from /usr/bin/time; NaN without).
 */
export function nativeRun(cli, model, work, cpu) {
  const stats = join(work, 'stats.json');
  const meshArgs = ['mesh', model, '-o', join(work, 'out.mesh'), '--stats', stats, '--quiet'];
  const t = performance.now();
  const r = cpu ? spawnSync('/usr/bin/time', ['-f', '%U %S', cli, ...meshArgs], { encoding: 'utf8' })
    : spawnSync(cli, meshArgs, { encoding: 'utf8' });
  const wall = (performance.now() - t) / 1000;
  if (r.status !== 0) throw new Error(`native ${model}: exit ${r.status}: ${r.stderr}`);
  const [user, sys] = cpu ? r.stderr.trim().split('\n').pop().split(' ').map(Number) : [NaN, NaN];
  const s = JSON.parse(readFileSync(stats, 'utf8'));
  return { wall, cpu: user + sys, core: s.time_s, tets: s.tets, phases: Object.fromEntries(s.phases.map((p) => [p.name, p.time_s])) };
}

export const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
/** "median [min-max]" of xs, 3 decimals. */
export const spread = (xs) => `${median(xs).toFixed(3)} [${Math.min(...xs).toFixed(3)}-${Math.max(...xs).toFixed(3)}]`;

/**
 * The PIDs (as strings) of the processes below `root` (its children, theirs,
 * ...), from the parent PIDs in /proc: e.g. the browser that playwright
 * started from this process, and not another user's browser.
 */
export function descendantPids(root = process.pid) {
  const parent = new Map();
  for (const pid of readdirSync('/proc').filter((d) => /^\d+$/.test(d))) {
    try {
      const s = readFileSync(`/proc/${pid}/stat`, 'utf8');
      parent.set(pid, s.slice(s.lastIndexOf(')') + 2).split(' ')[1]);
    } catch {
      // the process ended meanwhile
    }
  }
  const out = [];
  let level = [String(root)];
  while (level.length) {
    level = [...parent].filter(([, pp]) => level.includes(pp)).map(([pid]) => pid);
    out.push(...level);
  }
  return out;
}
