// wqmesh: the benchmark (issues 4 and 14). Prints figures; it is not a test.
// For every closed model of ../shared/models (broken ones, those that
// `wqmesh check` rejects with exit code 2, are skipped) and examples/models,
// runs each tool under a time limit per model:
//   wqmesh         the native command line (build/native/bin/wqmesh mesh),
//                  with the improvement phase after PUMP (the default) and,
//                  as "wqmesh no-improve", with --no-improve (the paper's
//                  WQMESH output); a binary whose `wqmesh mesh` does not
//                  know --no-improve (neither in its usage nor when given)
//                  has no improvement phase: one row, and the report says so;
//   wqmesh-wasm    the wasm module under Node (examples/node/wasm_runner.mjs,
//                  one process per run);
//   Mesh_3         CGAL make_mesh_3 (tests/benchmark/mesh3_peer.cpp, built on
//                  demand), one size s for edges, facets and cells (facet
//                  distance s/10), s bisected so that its tet count is within
//                  20% of wqmesh's;
//   TetGen         Debian's /usr/bin/tetgen, -pq2.2/0 and -pq1.414/10.
// Every mesh is then measured by the same code, `wqmesh measure`, and one
// table is printed, followed by issue 14's goals per model (met or not met,
// with the figures), the improvement phase against WQMESH alone, wqmesh's
// ratio to a plain Delaunay triangulation of its vertices, the wasm/native
// time ratio, the Mesh_3 sizes, and a growth series (one model at several
// --max-size bounds). Progress goes to stderr, the report (Markdown tables)
// to stdout.
//
// Usage: node examples/node/benchmark.mjs [--timeout S] [--build DIR] [--wasm FILE]
//          [--tools wqmesh,wasm,mesh3,tetgen] [--wasm-all] [--mesh3-steps K]
//          [--bisect-timeout S] [--growth-model FILE] [--growth-sizes H,H,...]
//          [--growth-timeout S] [--no-growth] [--growth-only] [--keep]
//          [--quick] [--baseline DIR] [MODEL ...]
// --quick: only the models whose smallest local feature size (`wqmesh check`'s
// analysis.lfs) is at least 1/200 of the input box's diagonal (the example
// models and the small shared ones; a smaller feature makes a large mesh).
// --baseline DIR: stats files DIR/<model file name>.json of an earlier run
// (`wqmesh mesh --stats`, e.g. /work/baseline/<commit>/), whose tet counts are
// printed beside the goals as the reference "today" of issue 14.
// SPDX-License-Identifier: GPL-3.0-or-later
import { spawnSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync }
  from 'node:fs';
import { cpus, loadavg, tmpdir, totalmem } from 'node:os';
import { basename, dirname, extname, join, resolve } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..');
const shared = join(root, '..', 'shared', 'models');
const TIME = '/usr/bin/time';
const TETGEN = '/usr/bin/tetgen';
const TETGEN_SETTINGS = ['-pq2.2/0', '-pq1.414/10'];

// ---- Options ----------------------------------------------------------------
const opt = {
  timeout: 300, build: join(root, 'build', 'native'), wasm: join(root, 'build', 'wasm', 'wasm', 'wqmesh.mjs'),
  tools: ['wqmesh', 'wasm', 'mesh3', 'tetgen'], wasmAll: false, mesh3Steps: 12, bisectTimeout: 0,
  growthModel: join(root, 'examples', 'models', 'spike.off'),
  growthSizes: [0.1, 0.07, 0.05, 0.04, 0.03, 0.025, 0.021], growthTimeout: 1200, growth: true, table: true,
  keep: false, maxVertices: 1000000, models: [], quick: false, baseline: null,
};
const usage = 'usage: node examples/node/benchmark.mjs [--timeout S] [--build DIR] [--wasm FILE] ' +
  '[--tools wqmesh,wasm,mesh3,tetgen] [--wasm-all] [--mesh3-steps K] [--bisect-timeout S] ' +
  '[--growth-model FILE] [--growth-sizes H,H,...] [--growth-timeout S] [--no-growth] [--growth-only] ' +
  '[--keep] [--quick] [--baseline DIR] [MODEL ...]';
{
  const args = process.argv.slice(2);
  for (let i = 0; i < args.length; ++i) {
    const a = args[i];
    const value = () => {
      if (i + 1 >= args.length) die(`${a} needs a value\n${usage}`);
      return args[++i];
    };
    const positive = () => {
      const v = Number(value());
      if (!(v > 0)) die(`${a} needs a positive number`);
      return v;
    };
    if (a === '--timeout') opt.timeout = positive();
    else if (a === '--build') opt.build = resolve(value());
    else if (a === '--wasm') opt.wasm = resolve(value());
    else if (a === '--tools') opt.tools = value().split(',');
    else if (a === '--wasm-all') opt.wasmAll = true;
    else if (a === '--mesh3-steps') opt.mesh3Steps = positive();
    else if (a === '--bisect-timeout') opt.bisectTimeout = positive();
    else if (a === '--growth-model') opt.growthModel = resolve(value());
    else if (a === '--growth-sizes') opt.growthSizes = value().split(',').map(Number);
    else if (a === '--growth-timeout') opt.growthTimeout = positive();
    else if (a === '--no-growth') opt.growth = false;
    else if (a === '--growth-only') opt.table = false;
    else if (a === '--keep') opt.keep = true;
    else if (a === '--quick') opt.quick = true;
    else if (a === '--baseline') opt.baseline = resolve(value());
    else if (a === '--help' || a === '-h') { console.log(usage); process.exit(0); }
    else if (a.startsWith('-')) die(`unknown option '${a}'\n${usage}`);
    else opt.models.push(resolve(a));
  }
  for (const t of opt.tools)
    if (!['wqmesh', 'wasm', 'mesh3', 'tetgen'].includes(t)) die(`unknown tool '${t}' (wqmesh, wasm, mesh3, tetgen)`);
  if (opt.growthSizes.some((h) => !(h > 0))) die('--growth-sizes needs positive numbers');
  if (!opt.bisectTimeout) opt.bisectTimeout = 3 * opt.timeout;
  if (opt.baseline && !existsSync(opt.baseline)) die(`--baseline ${opt.baseline}: no such folder`);
}
const cli = join(opt.build, 'bin', 'wqmesh');
const peer = join(opt.build, 'bin', 'wqmesh_mesh3_peer');
const runner = join(root, 'examples', 'node', 'wasm_runner.mjs');

function die(message) {
  process.stderr.write(`benchmark: ${message}\n`);
  process.exit(1);
}
const say = (message) => process.stderr.write(`benchmark: ${message}\n`);
const firstLine = (text) => (text || '').trim().split('\n').map((l) => l.trim()).find(Boolean) || '';

// ---- Running a process under a time limit, with its peak memory -------------
/**
 * Runs argv[0] with argv[1..] under `timeout` (TERM after `seconds`, KILL 5 s
 * later) and GNU time (peak resident memory of the process tree's largest
 * process, %M). Returns {status, timedOut, wall (s), peakMb, stdout, stderr}.
 */
function runTimed(argv, seconds, cwd = root) {
  const memFile = join(work, `mem-${process.pid}-${Math.random().toString(36).slice(2)}.txt`);
  const limited = ['timeout', '-k', '5', String(seconds), ...argv];
  const full = haveTime ? [TIME, '-f', '%M', '-o', memFile, ...limited] : limited;
  const t0 = performance.now();
  const r = spawnSync(full[0], full.slice(1), { cwd, encoding: 'utf8', maxBuffer: 256 << 20 });
  const wall = (performance.now() - t0) / 1000;
  let peakMb = null;
  if (haveTime && existsSync(memFile)) {
    const kb = readFileSync(memFile, 'utf8').trim().split('\n').map(Number).filter((n) => n > 0).pop();
    if (kb) peakMb = kb / 1024;
    rmSync(memFile, { force: true });
  }
  if (r.error) return { status: -1, timedOut: false, wall, peakMb, stdout: '', stderr: r.error.message };
  return { status: r.status, timedOut: r.status === 124 || (r.status === 137 && wall >= seconds), wall, peakMb,
    stdout: r.stdout || '', stderr: r.stderr || '' };
}

/** A failure note: the time limit, or the exit code and the first line of the error. */
function failure(r, what = '') {
  if (r.timedOut) return `timeout ${opt.timeout} s`;
  // Exit 3 (the vertex limit): the line that names the cause; else stderr's
  // first line, or TetGen's first error line on stdout.
  const stop = r.status === 3 && r.stderr.split('\n').find((l) => /stopped: /.test(l));
  const stdoutError = r.stdout.split('\n').filter((l) => /error|fail|invalid/i.test(l)).join('\n');
  const line = (stop && stop.replace(/^.*?stopped: /, 'stopped: ')) || firstLine(r.stderr) ||
    firstLine(stdoutError) || firstLine(r.stdout);
  const signals = { 134: 'SIGABRT', 135: 'SIGBUS', 136: 'SIGFPE', 137: 'SIGKILL', 139: 'SIGSEGV' };
  const how = signals[r.status] ? `killed by ${signals[r.status]}` : `exit ${r.status}`;
  return `${what}${how}${line ? `: ${line.slice(0, 160)}` : ''}`;
}

/**
 * `wqmesh measure` of a mesh file against the input model: the parsed JSON or
 * {error}. With `stats` (wqmesh's own statistics of that mesh) and a
 * `wqmesh measure` that takes --stats (issue 14 item 3: the classes recounted
 * from the written mesh and the stats' protecting balls), that recount too.
 */
function measure(meshPath, model, stats = null) {
  const args = ['measure', meshPath, '--input', model, '--json'];
  if (stats && cliHas.measureStats) args.push('--stats', stats);
  const r = spawnSync(cli, args, { encoding: 'utf8', maxBuffer: 64 << 20 });
  if (r.status !== 0) return { error: `measure: ${firstLine(r.stderr)}` };
  return JSON.parse(r.stdout);
}

/**
 * The violations of a recount by `wqmesh measure --stats`, wherever its JSON
 * puts them (top level or under a "recount" or "classes" object), or null
 * when the measure made no recount.
 */
function recountViolations(m) {
  if (!m || m.error || !cliHas.measureStats) return null;
  for (const o of [m.recount, m.classes, m]) if (o && Number.isInteger(o.violations)) return o.violations;
  return null;
}

// ---- Inputs for TetGen: a clean OFF (comments dropped, STL converted) ------
/** Reads OFF or STL (ASCII or binary) as {points, faces}; STL corners merged when identical. */
function readSoup(path) {
  const buf = readFileSync(path);
  const text = buf.toString('latin1');
  const firstToken = text.replace(/#[^\n]*/g, ' ').trim().split(/\s+/)[0] || '';
  if (/^[STCN]*OFF$/.test(firstToken)) {
    const tokens = text.split('\n').map((l) => l.replace(/#.*/, '')).join(' ').trim().split(/\s+/);
    let k = 1;
    const nv = Number(tokens[k++]), nf = Number(tokens[k++]);
    k++;  // edges
    const points = [];
    for (let i = 0; i < nv; ++i) { points.push([tokens[k], tokens[k + 1], tokens[k + 2]]); k += 3; }
    // Colours after a vertex would break this; no model here has them.
    const faces = [];
    for (let i = 0; i < nf; ++i) {
      const n = Number(tokens[k++]);
      faces.push(tokens.slice(k, k + n).map(Number));
      k += n;
    }
    return { points, faces };
  }
  const points = [], faces = [], index = new Map();
  const corner = (xyz) => {
    const key = xyz.join(' ');
    if (!index.has(key)) { index.set(key, points.length); points.push(xyz); }
    return index.get(key);
  };
  const n = buf.length >= 84 ? buf.readUInt32LE(80) : -1;
  if (buf.length === 84 + 50 * n) {
    for (let t = 0; t < n; ++t) {
      const o = 84 + 50 * t + 12;
      const f = [];
      for (let c = 0; c < 3; ++c)
        f.push(corner([0, 1, 2].map((d) => String(buf.readFloatLE(o + 12 * c + 4 * d)))));
      faces.push(f);
    }
  } else {
    const re = /vertex\s+(\S+)\s+(\S+)\s+(\S+)/gi;
    let m, f = [];
    while ((m = re.exec(text)) !== null) {
      f.push(corner([m[1], m[2], m[3]].map((v) => String(Number(v)))));
      if (f.length === 3) { faces.push(f); f = []; }
    }
  }
  return { points, faces };
}

function writeCleanOff(model, path) {
  const { points, faces } = readSoup(model);
  const lines = ['OFF', `${points.length} ${faces.length} 0`, ...points.map((p) => p.join(' ')),
    ...faces.map((f) => `${f.length} ${f.join(' ')}`)];
  writeFileSync(path, `${lines.join('\n')}\n`);
}

// ---- The tools --------------------------------------------------------------
/** wqmesh natively; improve false: with --no-improve (the paper's WQMESH output alone). */
function runWqmesh(model, name, improve = true) {
  const tag = improve ? 'wqmesh' : 'wqmesh-no-improve';
  const out = join(work, `${name}.${tag}.mesh`), stats = join(work, `${name}.${tag}.json`);
  const r = runTimed([cli, 'mesh', model, '-o', out, '--stats', stats, '--quiet', '--measure-floor',
    '--max-vertices', String(opt.maxVertices), ...(improve ? [] : ['--no-improve'])], opt.timeout);
  const s = existsSync(stats) ? JSON.parse(readFileSync(stats, 'utf8')) : null;
  const row = { tool: improve ? 'wqmesh' : 'wqmesh no-improve', wall: r.wall, peakMb: r.peakMb, stats: s,
    timedOut: r.timedOut };
  if (r.status !== 0) row.note = failure(r);  // exit 3: stopped by the vertex limit, with its cause
  if (existsSync(out) && r.status === 0) row.m = measure(out, model, stats);
  if (improve && s && r.status === 0) row.timeRuns = phaseRuns(model, name, s);
  return row;
}

// The time goal of issue 14 (the improve phase under REFINE + PUMP) on a model whose phases take milliseconds:
// one run is at the mercy of a single preemption (a 1 ms phase read as 5 ms), so such a model is run again and
// judged by the median ratio. A model whose REFINE + PUMP took at least REPEAT_BELOW_S keeps its one run.
const REPEAT_BELOW_S = 0.5, REPEAT_RUNS = 9, REPEAT_BUDGET_S = 5;
/**
 * The phases of the default run `first` (its stats) and, when its REFINE + PUMP is under REPEAT_BELOW_S, of more
 * runs of the same command (REPEAT_RUNS in all, or fewer once REPEAT_BUDGET_S of wall time is spent): a list of
 * { improve, rp } in seconds, one per run.
 */
function phaseRuns(model, name, first) {
  const runs = [improveTimes(first)];
  if (runs[0].improve === null || !(runs[0].rp < REPEAT_BELOW_S)) return runs;
  const out = join(work, `${name}.repeat.mesh`), stats = join(work, `${name}.repeat.json`);
  const t0 = performance.now();
  while (runs.length < REPEAT_RUNS && performance.now() - t0 < 1000 * REPEAT_BUDGET_S) {
    const r = spawnSync(cli, ['mesh', model, '-o', out, '--stats', stats, '--quiet',
      '--max-vertices', String(opt.maxVertices)], { encoding: 'utf8', timeout: 1000 * opt.timeout });
    if (r.status !== 0 || !existsSync(stats)) break;
    runs.push(improveTimes(JSON.parse(readFileSync(stats, 'utf8'))));
  }
  return runs;
}

function runWasm(model, name, native) {
  if (!opt.wasmAll && native && native.timedOut)
    return { tool: 'wqmesh-wasm', note: `not run: native timed out (--wasm-all runs it)` };
  const out = join(work, `${name}.wasm.mesh`), stats = join(work, `${name}.wasm.json`);
  const r = runTimed([process.execPath, runner, model, out, stats, '--module', opt.wasm,
    '--max-vertices', String(opt.maxVertices)], opt.timeout);
  const s = existsSync(stats) ? JSON.parse(readFileSync(stats, 'utf8')) : null;
  const row = { tool: 'wqmesh-wasm', wall: r.wall, peakMb: r.peakMb, stats: s, timedOut: r.timedOut };
  if (r.status !== 0) row.note = failure(r);
  if (existsSync(out) && r.status === 0) row.m = measure(out, model);
  return row;
}

function runMesh3(model, name, target, diagonal) {
  const row = { tool: 'Mesh_3' };
  let size = null;
  if (target) {
    const r = runTimed([peer, model, '--target-tets', String(target), '--max-steps', String(opt.mesh3Steps)],
      opt.bisectTimeout);
    const lines = r.stdout.trim().split('\n').filter(Boolean).map((l) => JSON.parse(l));
    const probes = lines.filter((l) => 'probe' in l);
    const answer = lines.find((l) => !('probe' in l));
    row.sizing = { target, probes: probes.length };
    if (answer) {
      size = answer.size;
      Object.assign(row.sizing, { size, steps: answer.steps, tets: answer.tets, within: answer.within_tolerance });
      if (answer.saturated)
        row.sizing.note = `larger s stops lowering the count: Mesh_3 needs about ${answer.tets} tets at any size`;
    } else if (probes.length) {  // stopped mid-way: the probe nearest the target so far
      const best = probes.reduce((a, b) => (Math.abs(Math.log(b.tets / target)) <
        Math.abs(Math.log(a.tets / target)) ? b : a));
      size = best.size;
      Object.assign(row.sizing, { size, steps: probes.length, tets: best.tets,
        within: Math.abs(best.tets - target) <= 0.2 * target, note: r.timedOut
          ? `bisection stopped by its limit (${opt.bisectTimeout} s)` : failure(r, 'bisection ') });
    } else {
      row.note = r.timedOut ? `bisection: no probe within ${opt.bisectTimeout} s` : failure(r, 'bisection ');
      return row;
    }
  } else {
    size = diagonal / 20;
    row.sizing = { size, steps: 0, note: 'no wqmesh tet count: s = bounding box diagonal / 20' };
  }
  const out = join(work, `${name}.mesh3.mesh`);
  const r = runTimed([peer, model, '--size', String(size), '-o', out], opt.timeout);
  Object.assign(row, { wall: r.wall, peakMb: r.peakMb, timedOut: r.timedOut });
  if (r.status !== 0) row.note = failure(r);
  else row.m = measure(out, model);
  return row;
}

function runTetgen(model, name, setting) {
  const dir = join(work, `tetgen${setting}`.replace(/[^\w.]/g, '_'));
  mkdirSync(dir, { recursive: true });
  const off = join(dir, `${name.replace(/\.[^.]*$/, '')}.off`);
  writeCleanOff(model, off);
  const r = runTimed([TETGEN, setting, basename(off)], opt.timeout, dir);
  const base = off.replace(/\.off$/, '.1');
  const row = { tool: `TetGen ${setting.slice(2)}`, wall: r.wall, peakMb: r.peakMb, timedOut: r.timedOut };
  if (r.status !== 0 || !existsSync(`${base}.ele`)) row.note = failure(r);
  else row.m = measure(`${base}.ele`, model);
  return row;
}

// ---- The report -------------------------------------------------------------
/** A Markdown table; the first `left` columns and the last (a note) are left-aligned. */
function table(header, rows, left = 1, note = false) {
  const widths = header.map((h, i) => Math.max(h.length, ...rows.map((r) => String(r[i]).length)));
  const isLeft = (i) => i < left || (note && i === header.length - 1);
  const line = (cells) => `| ${cells.map((c, i) => (isLeft(i) ? String(c).padEnd(widths[i])
    : String(c).padStart(widths[i]))).join(' | ')} |`.replace(/ +\|$/, ' |');
  console.log(line(header));
  console.log(`|${widths.map((w, i) => (isLeft(i) ? `${'-'.repeat(w + 2)}` : `${'-'.repeat(w + 1)}:`)).join('|')}|`);
  for (const r of rows) console.log(line(r));
}

const fixed = (v, d) => (v === null || v === undefined || Number.isNaN(v) ? '-' : Number(v).toFixed(d));
/** An angle in degrees: 2 decimals, or 2 significant digits below 0.01 (a flat tet shows as such). */
const angle = (v) => (v === null || v === undefined ? '-' : (v < 0.01 && v !== 0 ? Number(v).toExponential(1)
  : Number(v).toFixed(2)));
const exp = (v) => (v === null || v === undefined ? '-' : Number(v).toExponential(1));

function resultRow(model, r) {
  const m = r.m && !r.m.error ? r.m : null;
  const note = [r.note, r.m && r.m.error].filter(Boolean).join('; ');
  const time = r.timedOut ? `>${opt.timeout}` : (r.wall !== undefined ? fixed(r.wall, 2) : '-');
  return [r.tool, model, time,
    m ? m.vertices : '-', m ? m.tets : '-', m ? angle(m.min_dihedral_deg) : '-',
    m ? m.dihedral_below_3 : '-', m ? m.dihedral_below_5 : '-', m ? m.dihedral_below_10 : '-',
    m ? m.radius_edge_above_2_2 : '-', m ? exp(m.relative_volume_error) : '-',
    r.peakMb ? Math.round(r.peakMb) : '-', note];
}

// ---- Issue 14's goals --------------------------------------------------------
const VOLUME_TOLERANCE = 1e-12;  // relative volume error of an exactly conforming mesh (rounding only)
const ANGLE_ROUNDING = 1e-12;  // relative difference of two angles that is rounding only
const num = (v) => (v === null || v === undefined ? '-' : (Math.abs(v) < 0.01 && v !== 0
  ? Number(v).toExponential(1) : Number(v).toFixed(2)));
/** A goal's cell: "met (a >= b)" or "not met (a < b)"; "n/a (why)" when it does not apply. */
const verdict = (ok, a, op, b) => `${ok ? 'met' : 'not met'} (${a} ${ok ? op : { '>=': '<', '<=': '>', '<': '>=', '=': '!=' }[op]} ${b})`;
const na = (why) => `n/a (${why})`;
/**
 * The "min dih" goal when wqmesh's smallest dihedral angle w is below TetGen's t by rounding only, both at the
 * bound theta (the smallest internal dihedral angle of the input: the tets around a subsegment of that edge fill
 * its wedge, so one of them has at most theta, in every conforming mesh): "met (w = t ...)" with the figures in
 * full, since no mesh can do better than theta there. A point on a slanted facet is rounded to doubles, which
 * moves the angle of the tet spanning the wedge by about 1e-15 relative to theta either way (wedge.off and
 * wedge-1.off). Null when this does not apply (the plain comparison decides).
 */
function tieAtBound(w, t, theta) {
  if (!(w < t) || !Number.isFinite(theta) || !(w >= theta * (1 - ANGLE_ROUNDING)) ||
    !(t <= theta * (1 + ANGLE_ROUNDING))) return null;
  return `met (${num(w)} = ${num(t)} to ${ANGLE_ROUNDING} at the bound: ${w} and ${t}, the sharpest input edge's ` +
    `${theta})`;
}
/** Seconds: 3 decimals, or 2 significant digits under 0.01 s. */
const secs = (v) => (v >= 0.01 || v === 0 ? v.toFixed(3) : v.toExponential(1));
/** Tets under 5 degrees per 1000 tets of a measure. */
const per1000 = (m) => (1000 * m.dihedral_below_5) / m.tets;
/** The time of phase `name` in wqmesh's stats, or null. */
const phase = (stats, name) => {
  const p = stats && (stats.phases || []).find((x) => x.name === name);
  return p ? p.time_s : null;
};
/** The time goal's figures in wqmesh's stats: the improve phase's seconds (null without it) and REFINE + PUMP's. */
const improveTimes = (stats) =>
  ({ improve: phase(stats, 'improve'), rp: (phase(stats, 'refine') ?? 0) + (phase(stats, 'pump') ?? 0) });
/** The tet count of model `name` in the --baseline folder (its stats file), or null. */
function baselineTets(name) {
  if (!opt.baseline) return null;
  const f = join(opt.baseline, `${name}.json`);
  if (!existsSync(f)) return null;
  try { return JSON.parse(readFileSync(f, 'utf8')).tets ?? null; } catch { return null; }
}

/**
 * Prints issue 14's goals, one row per model that wqmesh and TetGen
 * -pq1.414/10 both meshed, each goal "met" or "not met" with its figures, and
 * the rate of tets under 5 degrees over all those models together; then the
 * improvement phase beside WQMESH alone (--no-improve) per model.
 */
function goals(results) {
  console.log('\n## Goals of issue 14, per model\n');
  console.log('wqmesh: the default run' + (cliHas.improve ? ' (improvement on)' : ' (this binary has no improvement ' +
    'phase)') + '; TetGen: -pq1.414/10; both measured by `wqmesh measure` (unweighted, on the written mesh). ' +
    'min dih: smallest dihedral angle >= TetGen\'s (or equal to it to ' +
    `${ANGLE_ROUNDING} relative when both are the sharpest input edge's dihedral angle, the bound of every ` +
    'conforming mesh); <5/1000: tets under 5 degrees per 1000 tets <= TetGen\'s; ' +
    '>=10 (15): smallest dihedral >= 10 degrees (stretch 15) where the smallest input angle (phi_m of `wqmesh ' +
    'check`) is at least 10 degrees; violations: the stats\' count' + (cliHas.measureStats
    ? ' and the recount by `wqmesh measure --stats`' : ' (no recount in this binary)') + ' = 0; conforms: ' +
    `the stats say conforming and vol err <= ${VOLUME_TOLERANCE}; tets: at most 10% more than --no-improve` +
    (opt.baseline ? ' (the baseline\'s count beside it, a reference only)' : '') + '; time: the improve phase ' +
    'under REFINE + PUMP (the stats\' phases; where REFINE + PUMP took under ' + `${REPEAT_BELOW_S} s, the median ` +
    `ratio of up to ${REPEAT_RUNS} runs).\n`);
  const rows = [];
  const all = { w5: 0, wt: 0, t5: 0, tt: 0, n: 0 };
  let met = 0, judged = 0;
  const count = (cell) => {
    if (cell.startsWith('met')) { ++met; ++judged; } else if (cell.startsWith('not met')) ++judged;
    return cell;
  };
  for (const { model, rows: tools, native, plain } of results) {
    const w = native && native.m && !native.m.error ? native.m : null;
    const tg = tools.find((r) => r.tool === 'TetGen q1.414/10');
    const t = tg && tg.m && !tg.m.error ? tg.m : null;
    if (!w || !t) continue;
    const s = native.stats || {};
    all.w5 += w.dihedral_below_5; all.wt += w.tets; all.t5 += t.dihedral_below_5; all.tt += t.tets; ++all.n;
    const minDih = tieAtBound(w.min_dihedral_deg, t.min_dihedral_deg, model.theta) ??
      verdict(w.min_dihedral_deg >= t.min_dihedral_deg, num(w.min_dihedral_deg), '>=', num(t.min_dihedral_deg));
    const rate = verdict(per1000(w) <= per1000(t), per1000(w).toFixed(2), '<=', per1000(t).toFixed(2));
    let ten;
    if (!(model.phiM >= 10)) ten = na(`input angle ${num(model.phiM)}`);
    else {
      ten = verdict(w.min_dihedral_deg >= 10, num(w.min_dihedral_deg), '>=', '10');
      if (w.min_dihedral_deg >= 10) ten += w.min_dihedral_deg >= 15 ? ', stretch 15 met' : ', stretch 15 not met';
    }
    const recount = recountViolations(w);
    const v = Number.isInteger(s.violations) ? s.violations : null;
    const violations = v === null ? na('no stats') : verdict(v === 0 && (recount === null || recount === 0),
      recount === null ? `${v}` : `${v} / recount ${recount}`, '=', '0');
    const vol = w.relative_volume_error;
    const conforms = verdict(s.conforming === true && vol <= VOLUME_TOLERANCE,
      `${s.conforming === true ? 'conforming' : 'not conforming'}, vol err ${exp(vol)}`, '<=', exp(VOLUME_TOLERANCE));
    const p = plain && plain.m && !plain.m.error ? plain.m : null;
    const base = baselineTets(model.name);
    const ref = base ? `; baseline ${base}, ${w.tets >= base ? '+' : ''}${(100 * (w.tets / base - 1)).toFixed(1)}%` : '';
    const tets = p ? verdict(w.tets <= 1.1 * p.tets, `${w.tets}`, '<=', `1.1 x ${p.tets}${ref}`)
      : na(`${cliHas.improve ? 'no --no-improve mesh' : 'no improvement phase'}; ${w.tets} tets${ref}`);
    const { improve: imp, rp } = improveTimes(s);
    const runs = native.timeRuns || [];
    let time;
    if (imp === null) time = na('no improve phase in the stats');
    else if (runs.length > 1) {
      // Judged by the median ratio of the runs (phaseRuns): milliseconds are noise in one run.
      const ratios = runs.map((x) => x.improve / x.rp).sort((a, b) => a - b);
      const med = ratios[Math.floor(ratios.length / 2)];
      time = verdict(med < 1, `median ${med.toFixed(2)}`, '<', `1, improve / (REFINE + PUMP) of ${ratios.length} ` +
        `runs: ${ratios[0].toFixed(2)}-${ratios[ratios.length - 1].toFixed(2)}`);
    } else time = verdict(imp < rp, `${secs(imp)} s`, '<', `${secs(rp)} s`);
    rows.push([model.name, num(model.phiM), ...[minDih, rate, ten, violations, conforms, tets, time].map(count)]);
  }
  table(['model', 'phi_m', 'min dih', '<5/1000', '>=10 (15)', 'violations', 'conforms', 'tets', 'time'], rows, 9);
  if (all.n) {
    const w = (1000 * all.w5) / all.wt, t = (1000 * all.t5) / all.tt;
    console.log(`\n- all ${all.n} models together, tets under 5 degrees per 1000: wqmesh ${w.toFixed(2)} ` +
      `(${all.w5} of ${all.wt}), TetGen ${t.toFixed(2)} (${all.t5} of ${all.tt}): ` +
      `${count(verdict(w <= 1.0, w.toFixed(2), '<=', '1.00'))}; ${count(verdict(w <= t, w.toFixed(2), '<=', t.toFixed(2)))}`);
    console.log(`- goals met: ${met} of ${judged} judged`);
  }

  console.log('\n## The improvement phase against WQMESH alone (--no-improve)\n');
  if (!cliHas.improve) console.log('This wqmesh has no improvement phase: one figure per cell, the WQMESH run\'s.\n');
  console.log('tets, min dih, <5: `wqmesh measure` of the --no-improve mesh -> the default mesh; refine, pump, ' +
    'improve: the phases\' seconds in the default run\'s stats; operations: the non-zero counts of the stats\' ' +
    '"improve" object' +
    (opt.baseline ? '; baseline tets: the --baseline stats\' count' : '') + '.\n');
  // The operation counts (integers; the stats' *_before classes and angles are in the other columns): passes, and
  // every operation that was done at least once.
  const ops = (o) => (o && typeof o === 'object' ? Object.entries(o).filter(([k, x]) => Number.isInteger(x) &&
    !/before|after/.test(k) && (x > 0 || k === 'passes')).map(([k, x]) => `${k} ${x}`).join(', ') : '');
  table(['model', 'baseline tets', 'tets', 'min dih', '<5', 'refine s', 'pump s', 'improve s', 'operations'],
    results.map(({ model, native, plain }) => {
      const w = native && native.m && !native.m.error ? native.m : null;
      const p = plain && plain.m && !plain.m.error ? plain.m : null;
      const s = native && native.stats;
      const pair = (f) => (p && w ? `${f(p)} -> ${f(w)}` : (w ? f(w) : '-'));
      return [model.name, baselineTets(model.name) ?? '-', pair((m) => m.tets), pair((m) => num(m.min_dihedral_deg)),
        pair((m) => m.dihedral_below_5), fixed(phase(s, 'refine'), 3), fixed(phase(s, 'pump'), 3),
        fixed(phase(s, 'improve'), 3), ops(s && s.improve)];
    }), 1, true);
}

// ---- Main -------------------------------------------------------------------
const haveTime = existsSync(TIME);
const work = mkdtempSync(join(tmpdir(), 'wqmesh-bench-'));
if (!existsSync(cli)) die(`${cli} is missing: run bash scripts/build.sh native (or pass --build DIR)`);
const tools = new Set(opt.tools);
if (tools.has('wasm') && !existsSync(opt.wasm)) {
  say(`${opt.wasm} is missing (bash scripts/build.sh wasm): wqmesh-wasm not run`);
  tools.delete('wasm');
}
if (tools.has('tetgen') && !existsSync(TETGEN)) {
  say(`${TETGEN} is missing (apt-get install tetgen): TetGen not run`);
  tools.delete('tetgen');
}
if (!haveTime) say(`${TIME} is missing (apt-get install time): no peak memory`);
// What this binary can do: the improvement phase (--no-improve) and the
// recount of the classes (`measure --stats`), read from its usage (`wqmesh
// mesh --help` prints it) or, when the usage does not list the option, from
// whether the command accepts it (on a tetrahedron; a binary without it
// answers "unknown option").
const cliHas = (() => {
  const u = spawnSync(cli, ['mesh', '--help'], { encoding: 'utf8' });
  const text = `${u.stdout || ''}\n${u.stderr || ''}`;
  const entry = (command) => (text.match(new RegExp(`^ {2}${command} [\\s\\S]*?(?=^ {2}\\S)`, 'm')) || [''])[0];
  const tet = join(work, 'probe.off');
  writeFileSync(tet, 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n');
  const accepts = (args) => !/unknown option/.test(spawnSync(cli, args, { encoding: 'utf8' }).stderr || '');
  const improve = /--no-improve\b/.test(entry('mesh')) ||
    accepts(['mesh', tet, '-o', join(work, 'probe.mesh'), '--stats', join(work, 'probe.json'),
      '--quiet', '--no-improve']);
  const measureStats = /--stats\b/.test(entry('measure')) || (existsSync(join(work, 'probe.mesh')) &&
    accepts(['measure', join(work, 'probe.mesh'), '--json', '--stats', join(work, 'probe.json')]));
  return { improve, measureStats };
})();

const git = (...a) => spawnSync('git', ['-C', root, ...a], { encoding: 'utf8' }).stdout.trim();
console.log('# wqmesh benchmark\n');
console.log(`- date: ${new Date().toISOString()}; machine: ${cpus().length} x ${cpus()[0].model}, ` +
  `${Math.round(totalmem() / 2 ** 30)} GiB; load average at start ${loadavg().map((v) => v.toFixed(1)).join(' ')}`);
console.log(`- wqmesh ${git('rev-parse', '--short', 'HEAD')}${git('status', '--porcelain', '--untracked-files=no')
  ? ' (with uncommitted changes)' : ''}; build ${opt.build}; node ${process.version}`);
console.log(`- time limit per model and tool ${opt.timeout} s (Mesh_3 bisection ${opt.bisectTimeout} s, ` +
  `at most ${opt.mesh3Steps} probes); wqmesh --max-vertices ${opt.maxVertices}; tools: ${[...tools].join(', ')}`);
console.log(cliHas.improve
  ? '- wqmesh has the improvement phase: "wqmesh" is the default run (improvement on), "wqmesh no-improve" ' +
    'the same with --no-improve (the paper\'s WQMESH output)'
  : '- this wqmesh has no improvement phase (`wqmesh mesh` does not know --no-improve): "wqmesh" is the ' +
    'WQMESH output, and the goals are judged on it');
console.log(cliHas.measureStats
  ? '- `wqmesh measure` takes --stats: the violations are also recounted from the written mesh'
  : '- `wqmesh measure` takes no --stats: the violations are the stats\' own, not recounted');
if (opt.baseline) console.log(`- baseline (reference tet counts): ${opt.baseline}`);

if (tools.has('mesh3') && opt.table && existsSync(peer) && !existsSync(join(opt.build, 'CMakeCache.txt'))) {
  say(`${peer}: used as it is (${opt.build} is no CMake build folder)`);
} else if (tools.has('mesh3') && opt.table) {
  say(`building the Mesh_3 peer: cmake --build ${opt.build} --target wqmesh_mesh3_peer -j 2`);
  const t0 = performance.now();
  const b = spawnSync('cmake', ['--build', opt.build, '--target', 'wqmesh_mesh3_peer', '-j', '2'],
    { stdio: ['ignore', 'ignore', 'inherit'] });
  if (b.status !== 0 || !existsSync(peer)) {
    say('the Mesh_3 peer did not build: Mesh_3 not run');
    tools.delete('mesh3');
  } else {
    say(`Mesh_3 peer ready (${((performance.now() - t0) / 1000).toFixed(0)} s)`);
  }
}

if (opt.table) {
  const list = (dir) => (existsSync(dir)
    ? readdirSync(dir).filter((f) => /\.(off|stl)$/i.test(f)).sort().map((f) => join(dir, f)) : []);
  if (!existsSync(shared) && !opt.models.length) say(`${shared} is absent: only examples/models`);
  const candidates = opt.models.length ? opt.models : [...list(shared), ...list(join(root, 'examples', 'models'))];
  const models = [], skipped = [], small = [];
  for (const model of candidates) {
    const r = spawnSync(cli, ['check', model, '--compact'], { encoding: 'utf8', maxBuffer: 256 << 20 });
    if (r.status === 2) {
      skipped.push(`${basename(model)} (${firstLine(r.stderr.split('\n').filter((l) => !/warning/.test(l))
        .join('\n')).replace(/^wqmesh: [^:]*: /, '').slice(0, 100)})`);
      continue;
    }
    if (r.status !== 0) { skipped.push(`${basename(model)} (check exit ${r.status})`); continue; }
    const analysis = JSON.parse(r.stdout).analysis;
    const box = analysis.input_box;
    const diagonal = Math.hypot(...box.hi.map((v, i) => v - box.lo[i]));
    // The smallest local feature size f(u) at a sharp vertex (no sharp vertex: none smaller than the box).
    const lfs = Math.min(diagonal, ...(analysis.lfs || []).map((x) => x.f));
    if (opt.quick && lfs < diagonal / 200) { small.push(basename(model)); continue; }
    // The sharpest input edge's internal dihedral angle: no conforming mesh's smallest dihedral angle is larger
    // (the tets at a subsegment of that edge fill its wedge; tieAtBound).
    const theta = Math.min(...(analysis.dihedral || []).map((d) => d.internal));
    models.push({ path: model, name: basename(model), diagonal, phiM: analysis.phi_m_degrees, theta });
  }
  console.log(`- skipped, rejected by \`wqmesh check\` (exit 2): ${skipped.join('; ') || 'none'}`);
  if (opt.quick) console.log(`- --quick: left out, smallest f(u) under 1/200 of the diagonal: ${small.join(', ') || 'none'}`);
  console.log('');

  const results = [];
  for (const model of models) {
    const rows = [];
    const log = (r) => say(`${model.name} ${r.tool}: ${r.timedOut ? 'timeout' : fixed(r.wall, 2) + ' s'}` +
      `${r.m && r.m.tets ? `, ${r.m.tets} tets` : ''}${r.note ? `, ${r.note}` : ''}`);
    let native = null, wasm = null, plain = null;
    if (tools.has('wqmesh')) {
      native = runWqmesh(model.path, model.name);
      rows.push(native);
      log(native);
      if (cliHas.improve) { plain = runWqmesh(model.path, model.name, false); rows.push(plain); log(plain); }
    }
    if (tools.has('wasm')) { wasm = runWasm(model.path, model.name, native); rows.push(wasm); log(wasm); }
    if (tools.has('mesh3')) {
      const target = [native, wasm].map((r) => r && r.m && r.m.tets).find(Boolean);
      const r = runMesh3(model.path, model.name, target, model.diagonal);
      rows.push(r);
      log(r);
    }
    if (tools.has('tetgen'))
      for (const setting of TETGEN_SETTINGS) {
        const r = runTetgen(model.path, model.name, setting);
        rows.push(r);
        log(r);
      }
    results.push({ model, rows, native, wasm, plain });
  }

  console.log('## All tools, measured by `wqmesh measure`\n');
  console.log('time: wall-clock seconds of the whole process (reading, meshing, writing); R/l and angles ' +
    'unweighted; vol err: |V_mesh - V_input| / V_input; MB: peak resident memory.\n');
  table(['tool', 'model', 'time s', 'vertices', 'tets', 'min dih', '<3', '<5', '<10', 'R/l>2.2', 'vol err', 'MB',
    'failure'], results.flatMap(({ model, rows }) => rows.map((r) => resultRow(model.name, r))), 2, true);

  if (tools.has('wqmesh')) goals(results);

  if (tools.has('wqmesh')) {
    console.log('\n## wqmesh: run vs Delaunay floor, wasm vs native\n');
    console.log('core s: time_s of the statistics (reading, checking and meshing, no writing); x Delaunay: ' +
      'core s / a plain Delaunay triangulation of the final vertex set (--measure-floor); wasm s: the ' +
      'mesh() call in Node.\n');
    table(['model', 'core s', 'Delaunay s', 'x Delaunay', 'wasm s', 'wasm/native'],
      results.map(({ model, native, wasm }) => {
        const s = native && native.stats && !native.note ? native.stats : null;
        const w = wasm && wasm.stats && !wasm.note ? wasm.stats : null;
        return [model.name, s ? fixed(s.time_s, 3) : '-', s ? fixed(s.delaunay_floor_s, 4) : '-',
          s && s.ratio_to_delaunay ? fixed(s.ratio_to_delaunay, 0) : '-', w ? fixed(w.wall_mesh_s, 3) : '-',
          s && w ? fixed(w.wall_mesh_s / s.time_s, 2) : '-'];
      }));
  }

  if (tools.has('mesh3')) {
    console.log('\n## Mesh_3 sizes\n');
    console.log('One size s: edge_size = facet_size = cell_size = s, facet_distance = s/10, facet_angle 25, ' +
      'cell_radius_edge_ratio 2.2; s bisected (log scale) until the tet count is within 20% of wqmesh\'s, at ' +
      `most ${opt.mesh3Steps} probes.\n`);
    table(['model', 'target tets', 's', 'probes', 'tets at s', 'within 20%', 'note'],
      results.map(({ model, rows }) => {
        const r = rows.find((x) => x.tool === 'Mesh_3');
        const z = (r && r.sizing) || {};
        return [model.name, z.target || '-', z.size ? Number(z.size).toPrecision(4) : '-', z.steps ?? '-',
          z.tets ?? '-', z.within === undefined ? '-' : (z.within ? 'yes' : 'no'),
          z.note || (r && !z.size ? r.note : '') || ''];
      }), 1, true);
  }
}

// ---- Growth series ----------------------------------------------------------
if (opt.growth) {
  console.log(`\n## Growth: wqmesh native on ${basename(opt.growthModel)} at several --max-size bounds\n`);
  console.log(`time limit ${opt.growthTimeout} s per run; --max-vertices 20000000; time: wall-clock of the ` +
    'process; core s: the statistics\' time_s.\n');
  const rows = [];
  for (const h of opt.growthSizes) {
    const out = join(work, `growth-${h}.mesh`), stats = join(work, `growth-${h}.json`);
    const r = runTimed([cli, 'mesh', opt.growthModel, '-o', out, '--stats', stats, '--quiet', '--measure-floor',
      '--max-size', String(h), '--max-vertices', '20000000'], opt.growthTimeout);
    const s = existsSync(stats) ? JSON.parse(readFileSync(stats, 'utf8')) : null;
    const note = r.status === 0 ? '' : (r.timedOut ? `timeout ${opt.growthTimeout} s` : failure(r));
    rows.push([String(h), r.timedOut ? `>${opt.growthTimeout}` : fixed(r.wall, 2), s ? fixed(s.time_s, 2) : '-',
      s ? s.vertices : '-', s ? s.tets : '-', r.peakMb ? Math.round(r.peakMb) : '-',
      s ? Math.round(s.tets / s.time_s) : '-', s && s.ratio_to_delaunay ? fixed(s.ratio_to_delaunay, 0) : '-', note]);
    say(`growth ${h}: ${rows[rows.length - 1].join(' ')}`);
    rmSync(out, { force: true });
    if (r.timedOut) break;
  }
  table(['--max-size', 'time s', 'core s', 'vertices', 'tets', 'MB', 'tets/s', 'x Delaunay', 'failure'], rows, 1,
    true);
}

if (opt.keep) say(`meshes kept in ${work}`);
else rmSync(work, { recursive: true, force: true });
