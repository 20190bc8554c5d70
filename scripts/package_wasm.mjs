// wqmesh: puts the built wasm module beside the package entry: copies
// build/wasm/wasm/wqmesh.mjs to wasm/wqmesh.mjs, writes wasm/wqmesh.wasm, the
// binary inlined in that module as a file of its own (the package compiles it
// once per instance, with WebAssembly.compileStreaming in browsers:
// wasm/index.mjs), and wasm/options.mjs, the option table as the module
// itself returns it (optionTable(), from the core's table in
// core/src/options.cpp) and the module's version. The files are build
// outputs (see .gitignore), never committed. Run by
// `scripts/build.sh wasm` and so by `npm pack` (prepack).
// Usage: node scripts/package_wasm.mjs [BUILD_DIR]   (default build/wasm)
// SPDX-License-Identifier: GPL-3.0-or-later
import { copyFileSync, existsSync, readFileSync, renameSync, statSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const build = resolve(root, process.argv[2] ?? 'build/wasm');
const built = join(build, 'wasm/wqmesh.mjs');
if (!existsSync(built)) {
  console.error(`package_wasm: error: ${built} is missing (run: bash scripts/build.sh wasm)`);
  process.exit(1);
}
const target = join(root, 'wasm/wqmesh.mjs');
copyFileSync(built, `${target}.tmp`);
renameSync(`${target}.tmp`, target);  // a page or a test never sees half a file
// The single-file module holds its binary as one base64 data URI.
const inlined = readFileSync(target, 'utf8').match(/data:application\/octet-stream;base64,([A-Za-z0-9+/=]+)/);
if (!inlined) {
  console.error(`package_wasm: error: ${built} has no inlined wasm binary (is it linked with -sSINGLE_FILE=1?)`);
  process.exit(1);
}
const binary = Buffer.from(inlined[1], 'base64');
const wasmTarget = join(root, 'wasm/wqmesh.wasm');
writeFileSync(`${wasmTarget}.tmp`, binary);
renameSync(`${wasmTarget}.tmp`, wasmTarget);

const module = await (await import(pathToFileURL(target).href)).default();
const table = JSON.parse(module.optionTable());
const text = '// wqmesh: the option table and the version of wqmesh.mjs, written by\n' +
             '// scripts/package_wasm.mjs from the module (core/src/options.cpp). Do not edit.\n' +
             '// SPDX-License-Identifier: GPL-3.0-or-later\n' +
             `export const version = ${JSON.stringify(module.version())};\n` +
             `export default ${JSON.stringify(table, null, 2)};\n`;
writeFileSync(join(root, 'wasm/options.mjs'), text);
console.log(`package_wasm: wasm/wqmesh.mjs (${statSync(target).size} bytes), wasm/wqmesh.wasm (${binary.length} bytes) and wasm/options.mjs ` +
            `(${table.length} options) written`);
