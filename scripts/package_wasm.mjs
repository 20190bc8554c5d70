// wqmesh: puts the built wasm module beside the package entry: copies
// build/wasm/wasm/wqmesh.mjs (the Emscripten glue) and wqmesh.wasm (its
// binary, the one copy the package ships) to wasm/, and writes
// wasm/options.mjs, the option table as the module itself returns it
// (optionTable(), from the core's table in core/src/options.cpp) and the
// module's version. Refuses a glue with a binary inlined (a SINGLE_FILE
// link would ship the code twice). The files are build outputs (see
// .gitignore), never committed. Run by `scripts/build.sh wasm` and so by
// `npm pack` (prepack).
// Usage: node scripts/package_wasm.mjs [BUILD_DIR]   (default build/wasm)
// SPDX-License-Identifier: GPL-3.0-or-later
import { copyFileSync, existsSync, readFileSync, renameSync, statSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { compileWasm, instantiateModule } from '../wasm/core.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const build = resolve(root, process.argv[2] ?? 'build/wasm');
const fail = (message) => {
  console.error(`package_wasm: error: ${message}`);
  process.exit(1);
};
const built = { glue: join(build, 'wasm/wqmesh.mjs'), binary: join(build, 'wasm/wqmesh.wasm') };
for (const f of Object.values(built)) if (!existsSync(f)) fail(`${f} is missing (run: bash scripts/build.sh wasm)`);
// A data URI of the binary (the glue always names the prefix
// "data:application/octet-stream;base64,"; the binary itself starts with
// "\0asm", "AGFzbQ" in base64): a SINGLE_FILE link.
if (/base64,AGFzbQ/.test(readFileSync(built.glue, 'utf8')))
  fail(`${built.glue} has the wasm binary inlined (linked with -sSINGLE_FILE=1?): the package ships it once, as wqmesh.wasm`);

/** Copies `from` to `to` through a temporary file, so that a page or a test never sees half a file. */
const place = (from, to) => {
  copyFileSync(from, `${to}.tmp`);
  renameSync(`${to}.tmp`, to);
};
const target = { glue: join(root, 'wasm/wqmesh.mjs'), binary: join(root, 'wasm/wqmesh.wasm') };
place(built.binary, target.binary);
place(built.glue, target.glue);

const factory = (await import(pathToFileURL(target.glue).href)).default;
const module = await instantiateModule(factory, await compileWasm(pathToFileURL(target.binary)));
const table = JSON.parse(module.optionTable());
const text = '// wqmesh: the option table and the version of wqmesh.mjs, written by\n' +
             '// scripts/package_wasm.mjs from the module (core/src/options.cpp). Do not edit.\n' +
             '// SPDX-License-Identifier: GPL-3.0-or-later\n' +
             `export const version = ${JSON.stringify(module.version())};\n` +
             `export default ${JSON.stringify(table, null, 2)};\n`;
writeFileSync(join(root, 'wasm/options.mjs'), text);
console.log(`package_wasm: wasm/wqmesh.mjs (${statSync(target.glue).size} bytes), wasm/wqmesh.wasm ` +
            `(${statSync(target.binary).size} bytes) and wasm/options.mjs (${table.length} options) written`);
