// wqmesh page: the build. Copies the page (web/), three.js and OrbitControls
// (node_modules/three), the package's JS (wasm/*.mjs) and the wasm module
// (build/wasm/wasm/wqmesh.mjs, the Emscripten glue, and wqmesh.wasm, its
// binary, beside it) and the
// example models into one folder that any static host can serve as is:
// build/web/ (nothing is fetched from another host). The bare specifiers
// 'three' and 'three/addons/...' are rewritten to relative paths as the
// files are copied, so the page needs no inline import map and runs under
// a strict Content-Security-Policy (script-src 'self' 'wasm-unsafe-eval').
// The package keeps its layout inside pkg/ so that its
// import.meta.url-relative paths hold.
// Usage: node web/build.mjs [--out DIR] [--module PATH/wqmesh.mjs] [--pkg DIR (default wasm/)]
// SPDX-License-Identifier: GPL-3.0-or-later
import { copyFileSync, existsSync, mkdirSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const args = process.argv.slice(2);
const opt = (name, def) => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : def; };
const out = resolve(opt('--out', join(root, 'build/web')));
const pkg = resolve(opt('--pkg', join(root, 'wasm')));
// The module: given, or beside the package entry (scripts/package_wasm.mjs
// puts it there), or in a build folder.
const candidates = [opt('--module', process.env.WQMESH_MODULE), join(pkg, 'wqmesh.mjs'),
  join(root, 'build/wasm/wasm/wqmesh.mjs'), join(root, 'build/h5wasm/wasm/wqmesh.mjs')].filter(Boolean);
const module = candidates.find((p) => existsSync(p));
if (!module) {
  console.error(`web/build: no wasm module (looked for ${candidates.join(', ')}); run 'bash scripts/build.sh wasm'`);
  process.exit(1);
}
// Its binary: the file of the same name ending in .wasm beside it (the glue holds no copy).
const binary = module.replace(/\.mjs$/, '.wasm');
if (!existsSync(binary)) {
  console.error(`web/build: ${binary}, the binary of ${module}, is missing; run 'bash scripts/build.sh wasm'`);
  process.exit(1);
}

const copy = (from, to) => {
  mkdirSync(dirname(to), { recursive: true });
  copyFileSync(from, to);
};
/** Copies a JS module with its imports of 'three' made relative to `threeBuild` and `addons` (URL paths). */
const copyModule = (from, to, threeBuild, addons) => {
  mkdirSync(dirname(to), { recursive: true });
  const text = readFileSync(from, 'utf8')
    .replace(/from 'three'/g, `from '${threeBuild}'`)
    .replace(/from 'three\/addons\/([^']+)'/g, (_, f) => `from '${addons}${f}'`);
  writeFileSync(to, text);
};
rmSync(out, { recursive: true, force: true });
mkdirSync(out, { recursive: true });

// The page.
for (const f of readdirSync(join(root, 'web'))) {
  if (f === 'build.mjs' || f === 'measure.mjs' || f === 'README.md') continue;  // Node scripts
  if (/\.mjs$/.test(f)) copyModule(join(root, 'web', f), join(out, f), './vendor/three/build/three.module.js', './vendor/three/examples/jsm/');
  else if (/\.(html|css)$/.test(f)) copy(join(root, 'web', f), join(out, f));
}
// three.js: the module build and the one addon the page uses.
const three = join(root, 'node_modules/three');
if (!existsSync(join(three, 'build/three.module.js'))) {
  console.error('web/build: node_modules/three is missing; run npm ci');
  process.exit(1);
}
for (const f of ['build/three.module.js', 'build/three.core.js', 'LICENSE']) copy(join(three, f), join(out, 'vendor/three', f));
copyModule(join(three, 'examples/jsm/controls/OrbitControls.js'), join(out, 'vendor/three/examples/jsm/controls/OrbitControls.js'),
           '../../../build/three.module.js', '../');
// The package: its JS files, and the module both where index.mjs looks for it
// in the build tree and beside index.mjs.
// (The package's command line, cli.mjs, is for Node: not served.)
for (const f of readdirSync(pkg)) {
  if (/\.(mjs|d\.ts)$/.test(f) && f !== 'cli.mjs' && !/^wqmesh-mem32/.test(f)) copy(join(pkg, f), join(out, 'pkg/wasm', f));
}
// Generated JS beside the module (e.g. an options table), if the build writes any.
for (const f of readdirSync(dirname(module))) {
  if (/\.mjs$/.test(f) && !/^wqmesh/.test(f) && f !== 'cli.mjs' && !existsSync(join(out, 'pkg/wasm', f))) {
    copy(join(dirname(module), f), join(out, 'pkg/wasm', f));
  }
}
copy(module, join(out, 'pkg/wasm/wqmesh.mjs'));
copy(binary, join(out, 'pkg/wasm/wqmesh.wasm'));
if (readFileSync(join(pkg, 'index.mjs'), 'utf8').includes('../build/wasm/wasm/wqmesh.mjs')) {
  copy(module, join(out, 'pkg/build/wasm/wasm/wqmesh.mjs'));  // an entry that looks in the build tree
  copy(binary, join(out, 'pkg/build/wasm/wasm/wqmesh.wasm'));
}
// The examples.
const models = readdirSync(join(root, 'examples/models')).filter((f) => /\.(off|stl)$/i.test(f)).sort();
for (const f of models) copy(join(root, 'examples/models', f), join(out, 'models', f));
writeFileSync(join(out, 'models/index.json'), `${JSON.stringify(models)}\n`);
console.log(`web/build: page in ${out} (module ${module}, ${models.length} examples)`);
