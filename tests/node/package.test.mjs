// wqmesh: the npm package as a new user gets it. `npm pack` (its prepack step
// builds the wasm module and puts it beside index.mjs) gives a tarball with
// exactly the files of package.json's `files` (no C++ sources, tests or
// corpus); installed into an empty temporary folder, with nothing else:
// - the binary is in it once: wasm/wqmesh.wasm (a wasm binary, its size in
//   the tarball's list) beside a glue wasm/wqmesh.mjs that inlines no copy;
// - `import { mesh, check } from 'wqmesh'` meshes a model in Node (in a
//   worker), the mesh conforming and keeping the input volume;
// - `npx wqmesh --help`, `npx wqmesh mesh IN -o OUT --stats S.json` work from there (exit code 0,
//   the output and the native stats keys), `npx wqmesh check` prints the report;
// - the examples of examples/node (Table 2 row, a folder with a line per
//   file) run against the installed package;
// - esbuild bundles an app with the worker as a second entry point
//   (`worker=node_modules/wqmesh/wasm/worker.mjs`), and the bundle meshes with
//   nothing but dist/ and wqmesh.wasm copied into it (no path into build/ or
//   the package); without that copy, a clear error naming wqmesh.wasm.
// The tarball's size is printed. Needs npm (and the wasm toolchain for prepack).
// Run: node --test tests/node/package.test.mjs
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, statSync,
         writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { after, before, test } from 'node:test';
import { fileURLToPath } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const work = mkdtempSync(join(tmpdir(), 'wqmesh-package-'));
const app = join(work, 'app');
after(() => rmSync(work, { recursive: true, force: true }));

const EXPECTED_FILES = ['LICENSE', 'README.md', 'package.json', 'wasm/cli.mjs', 'wasm/core.mjs', 'wasm/index.d.ts',
  'wasm/index.mjs', 'wasm/options.mjs', 'wasm/worker.mjs', 'wasm/wqmesh.mjs', 'wasm/wqmesh.wasm'];

function run(cmd, args, options = {}) {
  const r = spawnSync(cmd, args, { encoding: 'utf8', maxBuffer: 64 * 2 ** 20, ...options });
  if (r.error) throw r.error;
  return r;
}

let tarball = '';
let packed = null;

before(() => {
  // npm pack runs prepack (scripts/build.sh wasm: incremental, then the copy
  // beside index.mjs), so the tarball holds the module built from this tree.
  // WQMESH_PACK_NO_BUILD=1 packs the files already beside index.mjs without
  // the prepack build (for a tree whose C++ is being edited).
  const noBuild = process.env.WQMESH_PACK_NO_BUILD ? ['--ignore-scripts'] : [];
  const r = run('npm', ['pack', '--json', ...noBuild, '--pack-destination', work], { cwd: root });
  assert.equal(r.status, 0, r.stderr);
  // The build's log comes first on stdout; npm's JSON starts at a line of its own.
  packed = JSON.parse(r.stdout.slice(r.stdout.search(/^\[$/m)))[0];
  tarball = join(work, packed.filename);
  mkdirSync(app);
  // An empty folder and the tarball, nothing else (no registry needed: the package has no dependencies).
  const i = run('npm', ['install', '--no-audit', '--no-fund', '--offline', tarball], { cwd: app });
  assert.equal(i.status, 0, i.stderr);
});

test('npm pack: only the files list, the wasm binary in it once; its size', () => {
  const files = packed.files.map((f) => f.path).sort();
  assert.deepEqual(files, EXPECTED_FILES);
  const size = (path) => packed.files.find((f) => f.path === path).size;
  const glue = size('wasm/wqmesh.mjs');
  const binary = size('wasm/wqmesh.wasm');
  assert.ok(binary > 500000, `the wasm binary is in the tarball (${binary} bytes)`);
  // A glue with the binary inlined (base64) would be larger than the binary itself.
  assert.ok(glue < binary / 4, `wasm/wqmesh.mjs (${glue} bytes) holds no copy of the binary (${binary} bytes)`);
  const installed = join(app, 'node_modules/wqmesh/wasm');
  const wasm = readFileSync(join(installed, 'wqmesh.wasm'));
  assert.equal(wasm.length, binary);
  assert.ok(wasm.subarray(0, 4).equals(Buffer.from([0, 97, 115, 109])), 'wqmesh.wasm is a wasm binary');
  // "\0asm" in base64 is "AGFzbQ"; the installed package's JS holds no data URI of it.
  for (const f of ['wqmesh.mjs', 'index.mjs', 'worker.mjs', 'core.mjs'])
    assert.ok(!/base64,AGFzbQ/.test(readFileSync(join(installed, f), 'utf8')), `${f} inlines no binary`);
  console.log(`# tarball ${packed.filename}: ${statSync(tarball).size} bytes packed, ${packed.unpackedSize} unpacked, ` +
              `${files.length} files; wasm/wqmesh.mjs ${glue} bytes, wasm/wqmesh.wasm ${binary} bytes`);
});

test('installed into an empty folder: import { mesh, check } from "wqmesh" meshes in Node', () => {
  copyFileSync(join(root, 'examples/models/spike.off'), join(app, 'spike.off'));
  writeFileSync(join(app, 'use.mjs'), `
import { readFile } from 'node:fs/promises';
import { check, mesh, WqmeshError } from 'wqmesh';
const bytes = await readFile('spike.off');
const report = await check(bytes);
const r = await mesh(bytes, { rho: 2.2 });
let volume = 0, negative = 0;
const v = r.vertices, t = r.tets;
for (let i = 0; i < t.length; i += 4) {
  const p = [0, 1, 2, 3].map((k) => [v[3 * t[i + k]], v[3 * t[i + k] + 1], v[3 * t[i + k] + 2]]);
  const a = [0, 1, 2].map((c) => p[1][c] - p[0][c]), b = [0, 1, 2].map((c) => p[2][c] - p[0][c]),
        d = [0, 1, 2].map((c) => p[3][c] - p[0][c]);
  const o = a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) + a[2] * (b[0] * d[1] - b[1] * d[0]);
  if (o <= 0) ++negative;
  volume += o / 6;
}
let code = '';
try { await mesh('spike.off'); } catch (e) { code = e.name; }
try { await mesh(bytes, { rhoo: 1 }); } catch (e) { code += ' ' + (e instanceof WqmeshError ? e.code : e); }
console.log(JSON.stringify({ valid: report.valid, stats: r.stats, volume, negative, code }));
`);
  const r = run(process.execPath, ['use.mjs'], { cwd: app });
  assert.equal(r.status, 0, r.stderr);
  const out = JSON.parse(r.stdout);
  assert.equal(out.valid, true);
  assert.equal(out.stats.conforming, true);
  assert.equal(out.negative, 0);
  assert.ok(Math.abs(out.volume - out.stats.volume_input) <= 1e-9 * out.stats.volume_input);
  assert.equal(out.code, 'TypeError options');
});

test('npx wqmesh --help, mesh and check work from the installed package', () => {
  const help = run('npx', ['--no', '--', 'wqmesh', '--help'], { cwd: app });
  assert.equal(help.status, 0, help.stderr);
  assert.match(help.stdout, /mesh IN -o OUT/);
  copyFileSync(join(root, 'examples/models/spike.off'), join(app, 'spike.off'));
  const r = run('npx', ['--no', '--', 'wqmesh', 'mesh', 'spike.off', '-o', 'spike.vtu', '--stats', 'spike.json'], { cwd: app });
  assert.equal(r.status, 0, r.stderr);
  assert.match(readFileSync(join(app, 'spike.vtu'), 'utf8'), /<VTKFile type="UnstructuredGrid"/);
  const s = JSON.parse(readFileSync(join(app, 'spike.json'), 'utf8'));
  for (const k of ['input_points', 'sharp_elements', 'points_inserted', 'vertices', 'tets', 'radius_edge_bins',
                   'dihedral_bins', 'slivers', 'violations', 'stopped', 'time_s', 'phases']) assert.ok(k in s, k);
  const c = run('npx', ['--no', '--', 'wqmesh', 'check', 'spike.off', '--compact'], { cwd: app });
  assert.equal(c.status, 0, c.stderr);
  assert.equal(JSON.parse(c.stdout).valid, true);
  const bad = run('npx', ['--no', '--', 'wqmesh', 'mesh', 'spike.off', '-o', 'x.vtu', '--rhoo', '2'], { cwd: app });
  assert.equal(bad.status, 1);
});

test('the examples run against the installed package', () => {
  const examples = join(app, 'examples');
  mkdirSync(examples, { recursive: true });
  for (const f of ['table2_row.mjs', 'mesh_folder.mjs']) copyFileSync(join(root, 'examples/node', f), join(examples, f));
  const row = run(process.execPath, [join(examples, 'table2_row.mjs'), join(root, 'examples/models/thin_wedge.off'), '--json'],
                  { cwd: app });
  assert.equal(row.status, 0, row.stderr);
  const r = JSON.parse(row.stdout);
  assert.equal(r.model, 'thin_wedge.off');
  assert.ok(r.tets > 0);
  assert.equal(r.radius_edge.reduce((a, b) => a + b, 0), r.tets, 'the R/l bins hold every tet');
  assert.ok(r.dihedral.reduce((a, b) => a + b, 0) <= r.tets);
  assert.ok(r.slivers <= r.tets);
  const folder = join(work, 'models');
  mkdirSync(folder);
  for (const f of ['box.off', 'spike.off', 'slit.off']) copyFileSync(join(root, 'examples/models', f), join(folder, f));
  writeFileSync(join(folder, 'open.off'), 'OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n');
  const out = join(work, 'vtus');
  const all = run(process.execPath, [join(examples, 'mesh_folder.mjs'), folder, '--out', out], { cwd: app });
  assert.equal(all.status, 2, 'one invalid file: exit code 2');
  const lines = all.stdout.trim().split('\n');
  assert.equal(lines.length, 4, all.stdout);
  for (const [k, name] of ['box.off', 'open.off', 'slit.off', 'spike.off'].entries()) {
    assert.ok(lines[k].startsWith(`[${k + 1}/4] ${name}: `), lines[k]);
  }
  assert.match(lines[1], /open_boundary/);
  assert.deepEqual(readdirSync(out).sort(), ['box.vtu', 'slit.vtu', 'spike.vtu']);
});

test('esbuild: an app bundled with the worker as a second entry meshes from dist/ alone', () => {
  const esbuild = join(root, 'node_modules/esbuild/bin/esbuild');
  if (!existsSync(esbuild)) return;  // a devDependency (npm ci installs it)
  writeFileSync(join(app, 'bundled.mjs'), `
import { mesh } from 'wqmesh';
const text = ${JSON.stringify(readFileSync(join(root, 'examples/models/box.off'), 'utf8'))};
const r = await mesh(text);
console.log(JSON.stringify({ tets: r.stats.tets, conforming: r.stats.conforming }));
`);
  const dist = join(work, 'dist');
  const b = run(esbuild, ['bundled=bundled.mjs', 'worker=node_modules/wqmesh/wasm/worker.mjs', '--bundle',
                                   '--platform=node', '--format=esm', `--outdir=${dist}`, '--out-extension:.js=.mjs',
                                   '--log-level=error'], { cwd: app });
  assert.equal(b.status, 0, b.stderr);
  const bundle = readFileSync(join(dist, 'bundled.mjs'), 'utf8');
  assert.ok(!bundle.includes('../build/'), 'no path into a build tree');
  // The app's bundle holds what it uses (mesh: the worker side only); the
  // worker's bundle holds the wasm module.
  assert.ok(readFileSync(join(dist, 'worker.mjs'), 'utf8').includes('createWqmeshModule'), 'the wasm module is in the worker bundle');
  // Move dist/ away from the package: only the bundle and the worker remain,
  // and the binary, which a bundle needs beside it (esbuild does not copy it).
  const binary = readFileSync(join(app, 'node_modules/wqmesh/wasm/wqmesh.wasm'));
  rmSync(join(app, 'node_modules'), { recursive: true, force: true });
  const missing = run(process.execPath, [join(dist, 'bundled.mjs')], { cwd: work });
  assert.notEqual(missing.status, 0, 'no wqmesh.wasm beside the bundle: an error');
  assert.match(missing.stderr, /cannot load the wasm binary .*dist\/wqmesh\.wasm/s);
  writeFileSync(join(dist, 'wqmesh.wasm'), binary);
  const r = run(process.execPath, [join(dist, 'bundled.mjs')], { cwd: work });
  assert.equal(r.status, 0, r.stderr);
  const out = JSON.parse(r.stdout);
  assert.equal(out.conforming, true);
  assert.ok(out.tets > 0);
  // For the browser, the same bundle builds (the worker_threads import is left to Node).
  const web = run(esbuild, [join(root, 'wasm/index.mjs'), '--bundle', '--platform=browser',
                                     '--format=esm', `--outfile=${join(work, 'web.mjs')}`, '--log-level=error']);
  assert.equal(web.status, 0, web.stderr);
});
