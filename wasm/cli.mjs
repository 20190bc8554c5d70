#!/usr/bin/env node
// wqmesh: the Node command line of the package (`npx wqmesh ...`), the native
// command line's `check` and `mesh` on the wasm module:
//   wqmesh check IN [--compact] [--box-margin M]
//   wqmesh mesh IN -o OUT.(mesh|vtu|ele) [--stats STATS.json] [--quiet] [options]
// The options are the native flags, read from the option table the module
// shares with the native command line (options.mjs); the JSON and the exit
// codes are the native ones: 0 done or valid, 1 usage or internal error (and
// a memory limit), 2 invalid input, 3 stopped by the vertex limit (the mesh is
// written only if it conforms), 130 interrupted (Ctrl-C stops the run at once
// and writes nothing). Progress goes to stderr: a bar on a terminal, a line
// per phase and second otherwise.
// SPDX-License-Identifier: GPL-3.0-or-later
import { readFile, stat, writeFile } from 'node:fs/promises';

import { loadWqmesh, mesh, options as optionTable, version, writeMedit, writeTetgen, writeVtu } from './index.mjs';

const MAX_INPUT_BYTES = 1024 ** 3;  // InputLimits::max_bytes, refused before reading

function flagLines(command) {
  return optionTable.filter((o) => o.flag && o.commands.includes(command)).map((o) => {
    const value = o.type === 'boolean' ? '' : o.type === 'integer' ? ' N' : ' X';
    const range = o.type === 'boolean' ? '' : ` (${o.min} to ${o.max}, default ${o.default})`;
    return `      ${o.flag}${value}: ${o.doc}${range}\n`;
  }).join('');
}

const usage =
  'usage: wqmesh <command> [options]     (the wqmesh npm package, on WebAssembly)\n\n' +
  'commands:\n' +
  '  check IN [--compact] [options]\n' +
  '      Validate and analyse the polyhedron IN (OFF or STL, by content); the JSON\n' +
  '      report on stdout (--compact: one line). Exit code 0 valid, 2 invalid\n' +
  '      input (the message on stderr), 1 usage or internal error.\n' + flagLines('check') +
  '  mesh IN -o OUT [--stats STATS.json] [--quiet] [options]\n' +
  '      Mesh IN with WQMESH. OUT ends in .mesh (Medit), .vtu (VTK) or .ele\n' +
  '      (TetGen .node, .ele, .face and .edge). Exit code 0 done, 1 usage or\n' +
  '      internal error or out of memory, 2 invalid input, 3 stopped by the\n' +
  '      vertex limit (OUT written only if the mesh conforms), 130 interrupted.\n' +
  flagLines('mesh') +
  '  --help, --version\n';

class UsageError extends Error {}

function readOptionFlag(args, i, command, target) {
  const spec = optionTable.find((o) => o.flag === args[i] && o.commands.includes(command));
  if (!spec) return 0;
  if (spec.type === 'boolean') {
    // The flag sets the value other than the default (--no-pump, --measure-floor).
    target[spec.name] = !spec.default;
    return 1;
  }
  const text = args[i + 1];
  const what = `${spec.type === 'integer' ? 'a whole number' : 'a number'} in [${spec.min}, ${spec.max}]`;
  if (text === undefined || text.trim() === '' || !Number.isFinite(Number(text)))
    throw new UsageError(`${spec.flag} needs ${what}`);
  // The range is the module's to check (the same table): out of range is an
  // options error naming the option.
  target[spec.name] = Number(text);
  return 2;
}

function parse(args, command) {
  const out = { input: '', output: '', stats: '', quiet: false, compact: false, options: {} };
  for (let i = 0; i < args.length;) {
    const a = args[i];
    const used = readOptionFlag(args, i, command, out.options);
    if (used) {
      i += used;
    } else if (command === 'mesh' && (a === '-o' || a === '--stats') && i + 1 < args.length) {
      out[a === '-o' ? 'output' : 'stats'] = args[i + 1];
      i += 2;
    } else if (command === 'mesh' && a === '--quiet') {
      out.quiet = true;
      ++i;
    } else if (command === 'check' && a === '--compact') {
      out.compact = true;
      ++i;
    } else if (a.startsWith('-') && a !== '-') {
      throw new UsageError(`unknown option '${a}' for ${command}`);
    } else if (!out.input) {
      out.input = a;
      ++i;
    } else {
      throw new UsageError(`${command} takes one input file, got '${out.input}' and '${a}'`);
    }
  }
  if (!out.input) throw new UsageError(`${command} needs an input file`);
  if (command === 'mesh') {
    if (!out.output) throw new UsageError('mesh needs -o OUT.mesh, OUT.vtu or OUT.ele');
    if (!/\.(mesh|vtu|ele)$/.test(out.output))
      throw new UsageError(`the output '${out.output}' must end in .mesh, .vtu or .ele`);
  }
  return out;
}

/** The input's bytes, or an exit code after printing why not (io, too_large: exit code 2). */
async function readInput(path) {
  try {
    const info = await stat(path);
    if (info.isDirectory()) throw new Error('it is a folder');
    if (info.isFile() && info.size > MAX_INPUT_BYTES)
      return { kind: 'too_large', message: `'${path}' has ${info.size} bytes, beyond the limit of ${MAX_INPUT_BYTES}` };
    return { bytes: await readFile(path) };
  } catch (e) {
    return { kind: 'io', message: `cannot read '${path}': ${e.code === 'ENOENT' ? 'No such file or directory' : e.message}` };
  }
}

async function runCheck(args) {
  const a = parse(args, 'check');
  const input = await readInput(a.input);
  if (!input.bytes) {
    const report = { valid: false, error: { kind: input.kind, message: input.message } };
    console.log(a.compact ? JSON.stringify(report) : JSON.stringify(report, null, 2));
    console.error(`wqmesh: ${a.input}: ${input.kind}: ${input.message}`);
    return 2;
  }
  // check is quick: in this thread, printing the module's own JSON text (the
  // native command line's, byte for byte).
  const wqmesh = await loadWqmesh();
  const text = wqmesh.checkJson(input.bytes, { ...a.options, pretty: !a.compact });
  const report = JSON.parse(text);
  if (!report.valid && report.error.kind === 'options') throw new UsageError(report.error.message);
  for (const w of report.warnings ?? []) console.error(`wqmesh: warning: ${w}`);
  console.log(text);
  if (!report.valid) {
    console.error(`wqmesh: ${a.input}: ${report.error.kind}: ${report.error.message}`);
    return 2;
  }
  return 0;
}

/** Progress on stderr: a bar redrawn in place on a terminal, else a line per phase and second. */
function progressPrinter(quiet) {
  if (quiet) return { update: () => {}, end: () => {} };
  const tty = Boolean(process.stderr.isTTY);
  let lastPhase = '';
  let lastTime = 0;
  let drawn = false;
  return {
    update(p) {
      const now = Date.now();
      if (tty) {
        if (now - lastTime < 100 && p.phase === lastPhase) return;
        const width = 30;
        const full = Math.round(p.fraction * width);
        const line = `wqmesh: [${'#'.repeat(full)}${'.'.repeat(width - full)}] ${(100 * p.fraction).toFixed(0).padStart(3)}% ` +
                     `${p.phase} ${p.vertices} vertices`;
        process.stderr.write(`\r${line}\x1b[K`);
        drawn = true;
      } else if (p.phase !== lastPhase || now - lastTime >= 1000) {
        process.stderr.write(`wqmesh: ${p.phase}: ${p.vertices} vertices\n`);
      }
      lastPhase = p.phase;
      lastTime = now;
    },
    end() {
      if (drawn) process.stderr.write('\n');
      drawn = false;
    },
  };
}

async function runMesh(args) {
  const a = parse(args, 'mesh');
  const input = await readInput(a.input);
  if (!input.bytes) {
    console.error(`wqmesh: ${a.input}: ${input.kind}: ${input.message}`);
    return 2;
  }
  const controller = new AbortController();
  let interrupts = 0;
  const onSigint = () => {
    // The first Ctrl-C terminates the worker (the run stops at once); a second one exits now.
    if (++interrupts > 1) process.exit(130);
    controller.abort();
  };
  process.on('SIGINT', onSigint);
  const progress = progressPrinter(a.quiet);
  let r;
  try {
    r = await mesh(input.bytes, a.options, { signal: controller.signal, onProgress: (p) => progress.update(p) });
  } catch (e) {
    progress.end();
    if (e?.name === 'AbortError') {
      console.error(`wqmesh: interrupted; '${a.output}' not written`);
      return 130;
    }
    if (e?.code === 'options') throw new UsageError(e.message.replace(/^wqmesh: options: /, ''));
    if (e?.code === 'limit') {
      console.error(`wqmesh: out of memory: ${e.message}`);
      return 1;
    }
    if (e?.code === 'internal' || !e?.code) throw e;
    console.error(`wqmesh: ${a.input}: ${e.message.replace(/^wqmesh: /, '')}`);
    return 2;
  } finally {
    process.off('SIGINT', onSigint);
  }
  progress.end();
  const s = r.stats;
  if (s.conforming) {
    if (a.output.endsWith('.ele')) {
      const files = await writeTetgen(r, { bytes: true });
      const base = a.output.slice(0, -'.ele'.length);
      for (const ext of ['node', 'ele', 'face', 'edge']) await writeFile(`${base}.${ext}`, files[ext]);
    } else {
      await writeFile(a.output, await (a.output.endsWith('.mesh') ? writeMedit : writeVtu)(r, { bytes: true }));
    }
  } else if (s.stopped && s.all_vertices === 0) {
    console.error(`wqmesh: stopped before meshing; '${a.output}' not written`);
  } else {
    console.error(`wqmesh: the mesh does not conform to the input; '${a.output}' not written`);
  }
  if (a.stats) await writeFile(a.stats, `${JSON.stringify(s, null, 2)}\n`);
  if (!a.quiet)
    console.error(`wqmesh: ${s.vertices} vertices, ${s.tets} tets, ${s.slivers} slivers, ${s.skinny} skinny, ` +
                  `${s.violations} violations, ${s.time_s} s`);
  if (s.stopped) {
    console.error(`wqmesh: stopped: ${s.stopped}${s.stop_message ? `: ${s.stop_message}` : ''}`);
    return 3;
  }
  return s.conforming ? 0 : 1;
}

async function main(argv) {
  const [command, ...args] = argv;
  try {
    if (command === undefined) throw new UsageError('no command given');
    if (command === '--help' || command === '-h' || command === 'help') {
      process.stdout.write(usage);
      return 0;
    }
    if (command === '--version') {
      console.log(`wqmesh ${version} (wasm)`);
      return 0;
    }
    if (command === 'check') return await runCheck(args);
    if (command === 'mesh') return await runMesh(args);
    if (command === 'measure') throw new UsageError("'measure' is in the native command line only (build/native/bin/wqmesh)");
    throw new UsageError(`unknown command '${command}'`);
  } catch (e) {
    if (e instanceof UsageError) {
      console.error(`wqmesh: ${e.message}\n\n${usage}`);
      return 1;
    }
    console.error(`wqmesh: internal error: ${e?.message ?? e}`);
    return 1;
  }
}

process.exitCode = await main(process.argv.slice(2));
