// wqmesh: the readers say the truth, the same through the native command
// line (`wqmesh check FILE`) and the wasm module (`check(bytes)`): a UTF-8
// byte order mark is skipped; LF, CRLF and CR line ends are all read; bytes
// that are neither OFF nor STL are "not an OFF or STL file" (syntax), quoting
// what was seen, never a binary-STL triangle count; a NUL inside a number is
// quoted escaped; a four-vertex ASCII STL facet is a syntax error; a
// 60,000-point cylinder is checked (near-linear analysis) and a pyramid over
// a 100,000-gon is refused at once by a named budget (README, Limits). Each
// input is generated here; both interfaces must agree on valid/invalid and
// the error kind, and match the expected message.
// WQMESH_CLI and WQMESH_MODULE (the path of wqmesh.mjs) choose other builds
// than build/native and build/wasm.
// Run: node --test tests/node/readers.test.mjs
// SPDX-License-Identifier: GPL-3.0-or-later
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { cli, loadModule, skipCli, workDir } from './lib/setup.mjs';

const wqmesh = await loadModule({ build: true });
const work = workDir('readers');

const BOM = Buffer.from([0xef, 0xbb, 0xbf]);
const CUBE_OFF = 'OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n' +
  '4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n';
const TET = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]];
const TET_FACES = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
const asciiStl = (faces) => 'solid t\n' + faces.map((f) => ' facet normal 0 0 0\n  outer loop\n' +
  f.map((v) => `   vertex ${TET[v].join(' ')}\n`).join('') + '  endloop\n endfacet\n').join('') + 'endsolid t\n';
const lineEnds = (text, end) => text.replaceAll('\n', end);

/** Deterministic bytes (a linear congruential generator). */
function randomBytes(n, seed) {
  const out = Buffer.alloc(n);
  let s = seed >>> 0;
  for (let i = 0; i < n; i++) {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    out[i] = s >>> 24;
  }
  return out;
}

function offText(points, faces) {
  return `OFF\n${points.length} ${faces.length} 0\n` + points.map((p) => p.join(' ')).join('\n') + '\n' +
    faces.map((f) => `${f.length} ${f.join(' ')}`).join('\n') + '\n';
}
const circle = (n, z) => Array.from({ length: n }, (_, i) => [Math.cos(2 * Math.PI * i / n), Math.sin(2 * Math.PI * i / n), z]);

function cylinder(n) {
  const faces = [Array.from({ length: n }, (_, i) => n - 1 - i), Array.from({ length: n }, (_, i) => n + i)];
  for (let i = 0; i < n; i++) faces.push([i, (i + 1) % n, n + (i + 1) % n, n + i]);
  return offText([...circle(n, 0), ...circle(n, 1)], faces);
}

function pyramid(n) {
  const faces = [Array.from({ length: n }, (_, i) => n - 1 - i)];
  for (let i = 0; i < n; i++) faces.push([i, (i + 1) % n, n]);
  return offText([...circle(n, 0), [0, 0, 1]], faces);
}

const random = randomBytes(4096, 12345);
const declared = random.readUInt32LE(80);
assert.notEqual(84 + 50 * declared, random.length, 'the random bytes must not be a binary STL by size');
const shortStl = Buffer.alloc(84, 0xfe);
shortStl.writeUInt32LE(20_000_000, 80);

// name -> [bytes, expected: { valid, vertices } or { kind, message }]
const cases = {
  'bom.off': [Buffer.concat([BOM, Buffer.from(CUBE_OFF)]), { valid: true, vertices: 8 }],
  'bom.stl': [Buffer.concat([BOM, Buffer.from(asciiStl(TET_FACES))]), { valid: true, vertices: 4 }],
  'cr.off': [lineEnds(CUBE_OFF, '\r'), { valid: true, vertices: 8 }],
  'crlf.off': [lineEnds(CUBE_OFF, '\r\n'), { valid: true, vertices: 8 }],
  'cr.stl': [lineEnds(asciiStl(TET_FACES), '\r'), { valid: true, vertices: 4 }],
  'cr-error.off': [lineEnds('OFF\n4 4 6\n0 0 0\n1 nan 0\n0 1 0\n0 0 1\n', '\r'),
                   { kind: 'non_finite', message: /line 4: vertex 1/ }],
  'random.bin': [random, { kind: 'syntax', message: new RegExp(
    `not an OFF or STL file: it starts with '.{24,}\\.\\.\\.' \\(4096 bytes\\).*declaring ${declared} ` +
    `triangles would make it ${84 + 50 * declared} bytes long`) }],
  'short.stl': [shortStl, { kind: 'syntax', message: /not an OFF or STL file: it starts with '\\xfe\\xfe.*would make it 1000000084 bytes long/ }],
  'nul.off': [Buffer.from('OFF\n4 4 6\n0 0 0\n1\u00005 0 0\n0 1 0\n0 0 1\n', 'latin1'),
              { kind: 'syntax', message: /line 4: vertex 1: bad coordinate '1\\x005'/ }],
  'quad.stl': ['solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\n' +
               'endloop\nendfacet\nendsolid q\n',
               { kind: 'syntax', message: /line 7: triangle 0 has a fourth 'vertex': an STL facet has exactly three/ }],
  'cylinder.off': [cylinder(30_000), { valid: true, vertices: 60_000 }],
  'pyramid.off': [pyramid(100_000), { kind: 'too_large', message:
    /the vertex \(0, 0, 1\) is in 100000 triangles\), beyond the self-intersection test's budget of 200000000 pairs/ }],
};

function expectReport(report, expected, where) {
  if (expected.valid) {
    assert.equal(report.valid, true, `${where}: ${JSON.stringify(report.error)}`);
    assert.equal(report.plc.vertices, expected.vertices, where);
  } else {
    assert.equal(report.valid, false, where);
    assert.equal(report.error.kind, expected.kind, `${where}: ${report.error.message}`);
    assert.match(report.error.message, expected.message, where);
  }
}

for (const [name, [content, expected]] of Object.entries(cases)) {
  const bytes = typeof content === 'string' ? Buffer.from(content, 'latin1') : content;
  test(`${name}: the command line and the wasm module say the same`, { skip: skipCli }, () => {
    const path = join(work, name);
    writeFileSync(path, bytes);
    const r = spawnSync(cli, ['check', path, '--compact'], { encoding: 'utf8', timeout: 120_000, maxBuffer: 1 << 30 });
    assert.equal(r.status, expected.valid ? 0 : 2, `${name}: ${r.stderr}`);
    const native = JSON.parse(r.stdout);
    expectReport(native, expected, `${name} (command line)`);
    const wasm = wqmesh.check(new Uint8Array(bytes));
    expectReport(wasm, expected, `${name} (wasm)`);
    assert.equal(wasm.valid, native.valid, name);
    if (!native.valid) assert.equal(wasm.error.kind, native.error.kind, name);
    else assert.deepEqual(wasm.analysis.counts, native.analysis.counts, name);
  });
}
