// wqmesh: the lists that must agree with the C++ sources: the input error
// kinds of error.h against wasm/index.d.ts (InputErrorKind) and against what
// the wasm module reports; the phases and stop reasons of names.h against the
// .d.ts; the version of the CMake project against package.json, the wasm
// module, wasm/options.mjs and the command line (`wqmesh --version`); the
// web page's words for every kind. WQMESH_CLI and WQMESH_MODULE choose other
// builds than build/native and build/wasm.
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { version as packagedVersion } from '../../wasm/options.mjs';
import { cmakeVersion, dtsUnion, errorKinds } from './lib/names.mjs';
import { cli, loadModule, root } from './lib/setup.mjs';

test('index.d.ts InputErrorKind is the list of error.h plus internal', () => {
  const kinds = errorKinds();
  assert.ok(kinds.includes('out_of_range') && kinds.includes('io'), kinds.join());
  assert.deepEqual(dtsUnion('InputErrorKind'), [...kinds, 'internal']);
});

test('error.cpp names every enumerator of error.h by its own name, in order', () => {
  const source = readFileSync(join(root, 'core/src/error.cpp'), 'utf8');
  const cases = [...source.matchAll(/case InputErrorKind::(\w+): return "(\w+)";/g)];
  for (const [, enumerator, name] of cases) assert.equal(name, enumerator);
  assert.deepEqual(cases.map((c) => c[1]), errorKinds());
});

test('index.d.ts Phase and stopped are the names of names.h', () => {
  const names = readFileSync(join(root, 'core/src/names.cpp'), 'utf8');
  const phases = [...names.matchAll(/case MeshPhase::\w+: return "(\w+)";/g)].map((m) => m[1]);
  assert.deepEqual(dtsUnion('Phase'), phases);
  const stops = [...names.matchAll(/case StopReason::\w+: return "(\w*)";/g)].map((m) => m[1]);
  const dts = readFileSync(join(root, 'wasm/index.d.ts'), 'utf8');
  const stopped = /^\s*stopped: ('[^;]*);/m.exec(dts);
  assert.ok(stopped, 'MeshStats.stopped not found');
  assert.deepEqual([...stopped[1].matchAll(/'([^']*)'/g)].map((m) => m[1]), stops);
});

test('the wasm module reports kinds of the list', async () => {
  const wqmesh = await loadModule();
  const kinds = errorKinds();
  for (const bytes of ['', 'OFF\n4 1 0\n0 0 0\n', 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n']) {
    const report = wqmesh.check(new TextEncoder().encode(bytes));
    assert.equal(report.valid, false);
    assert.ok(kinds.includes(report.error.kind), `${report.error.kind} is not in error.h`);
  }
});

test('package.json, the wasm module and the command line have the CMake project version', async () => {
  const version = cmakeVersion();
  assert.equal(JSON.parse(readFileSync(join(root, 'package.json'), 'utf8')).version, version);
  assert.equal(packagedVersion, version, 'wasm/options.mjs (scripts/package_wasm.mjs writes it from the module)');
  const wqmesh = await loadModule();
  assert.equal(wqmesh.version(), version);
  assert.ok(existsSync(cli), `the native command line is missing (${cli}): build it or set WQMESH_CLI`);
  const r = spawnSync(cli, ['--version'], { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  assert.equal(r.stdout.trim(), `wqmesh ${version}`);
});

test('the web page has words for every error kind of the list', async () => {
  const { ERROR_WORDS } = await import('../../web/surface.mjs');
  for (const kind of [...errorKinds(), 'options', 'limit', 'internal'])
    assert.equal(typeof ERROR_WORDS[kind], 'string', `web/surface.mjs ERROR_WORDS has no ${kind}`);
});
