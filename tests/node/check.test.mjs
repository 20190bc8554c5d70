// wqmesh: the wasm module (through the package entry, wasm/index.mjs) against
// the native command line (`wqmesh check FILE`): for every model of
// ../shared/models (skipped when absent) and examples/models, both must give
// the same report: integers, booleans, strings and array lengths exactly,
// floating values within 1e-12 (relative, or absolute near 0). Bad input must
// give `valid: false` with an error kind, never an exception.
// Run: node --test tests/node/
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync, readdirSync, readFileSync } from 'node:fs';
import { join, relative } from 'node:path';
import { test } from 'node:test';

import { cli, loadModule, root } from './lib/setup.mjs';

const modelDirs = [join(root, '../shared/models'), join(root, 'examples/models')];
const TOLERANCE = 1e-12;

const wqmesh = await loadModule();

function models() {
  const files = [];
  for (const dir of modelDirs) {
    if (!existsSync(dir)) continue;
    for (const name of readdirSync(dir).sort()) {
      if (/\.(off|stl)$/i.test(name)) files.push(join(dir, name));
    }
  }
  return files;
}

/**
 * Compares two parsed reports. Numbers that are safe integers on both sides
 * (counts, indices, and floating values that happen to be whole) must be
 * equal; other numbers must agree within TOLERANCE.
 */
function compare(native, wasm, path = '$') {
  if (typeof native === 'number' && typeof wasm === 'number') {
    if (native === wasm) return;
    if (Number.isSafeInteger(native) && Number.isSafeInteger(wasm)) {
      assert.fail(`${path}: native ${native}, wasm ${wasm}`);
    }
    const scale = Math.max(Math.abs(native), Math.abs(wasm));
    const limit = scale < 1 ? TOLERANCE : TOLERANCE * scale;
    assert.ok(Math.abs(native - wasm) <= limit, `${path}: native ${native}, wasm ${wasm}`);
    return;
  }
  assert.equal(typeof wasm, typeof native, `${path}: type`);
  if (Array.isArray(native)) {
    assert.ok(Array.isArray(wasm), `${path}: wasm is not an array`);
    assert.equal(wasm.length, native.length, `${path}: array length`);
    native.forEach((x, i) => compare(x, wasm[i], `${path}[${i}]`));
  } else if (native !== null && typeof native === 'object') {
    assert.ok(wasm !== null && !Array.isArray(wasm), `${path}: wasm is not an object`);
    assert.deepEqual(Object.keys(wasm), Object.keys(native), `${path}: keys`);
    for (const k of Object.keys(native)) compare(native[k], wasm[k], `${path}.${k}`);
  } else {
    assert.equal(wasm, native, path);
  }
}

test('version() is a semantic version', () => {
  assert.match(wqmesh.version(), /^\d+\.\d+\.\d+/);
});

test('the models give the same report in wasm and natively', async (t) => {
  const files = models();
  assert.ok(files.length > 0, 'no model found');
  // The comparison is the point of the test: no native build is a failure.
  assert.ok(existsSync(cli), `the native command line is missing (${cli}): build it or set WQMESH_CLI`);
  for (const file of files) {
    await t.test(relative(root, file), () => {
      const bytes = readFileSync(file);
      const report = wqmesh.check(bytes);
      assert.equal(typeof report.valid, 'boolean');
      if (!report.valid) assert.equal(typeof report.error?.kind, 'string', 'invalid without an error kind');
      const run = spawnSync(cli, ['check', file], { encoding: 'utf8', maxBuffer: 1 << 30 });
      assert.ok(run.status === 0 || run.status === 2,
                `wqmesh check exited with ${run.status} ${run.signal ?? ''}: ${run.stderr}`);
      if (run.status === 2) {
        assert.equal(report.valid, false, `native rejects (${run.stderr.trim()}), wasm accepts`);
        assert.ok(run.stderr.includes(report.error.kind),
                  `native error (${run.stderr.trim()}) does not name wasm's kind ${report.error.kind}`);
      } else {
        assert.equal(report.valid, true, `native accepts, wasm rejects: ${JSON.stringify(report.error)}`);
      }
      compare(JSON.parse(run.stdout), report);
    });
  }
});

test('bad input gives valid: false with an error kind, without throwing', () => {
  const cube = readFileSync(join(root, 'examples/models/box.off'));
  const cases = {
    empty: new Uint8Array(0),
    garbage: Uint8Array.from({ length: 4096 }, (_, i) => (i * 2654435761) >>> 24),
    'text garbage': 'this is not a polyhedron\n',
    'truncated OFF': cube.subarray(0, Math.floor(cube.length * 0.6)),
    'OFF header only': 'OFF\n8 6 0\n',
  };
  for (const [name, bytes] of Object.entries(cases)) {
    let report;
    assert.doesNotThrow(() => { report = wqmesh.check(bytes); }, name);
    assert.equal(report.valid, false, `${name}: accepted`);
    assert.equal(typeof report.error.kind, 'string', `${name}: no error kind`);
    assert.ok(report.error.kind.length > 0, `${name}: empty error kind`);
    assert.equal(typeof report.error.message, 'string', `${name}: no message`);
  }
  assert.equal(wqmesh.check(new Uint8Array(0)).error.kind, 'empty');
});

test('check accepts every kind of byte container and checkJson matches check', () => {
  const bytes = readFileSync(join(root, 'examples/models/thin_wedge.off'));
  const reference = wqmesh.check(bytes);
  const copy = new Uint8Array(bytes);
  for (const input of [copy, copy.buffer, new DataView(copy.buffer), bytes.toString('latin1')]) {
    assert.deepEqual(wqmesh.check(input), reference);
  }
  assert.deepEqual(JSON.parse(wqmesh.checkJson(bytes, { pretty: true })), reference);
  assert.throws(() => wqmesh.check(42), TypeError);
});
