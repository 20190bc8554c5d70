#!/usr/bin/env node
// wqmesh: a tiny static file server on 127.0.0.1, without dependencies, for
// `npm start` (scripts/start.sh) and the browser tests. Serves the files
// under ROOT (default: the checkout) with their MIME types (.mjs/.js
// text/javascript, .wasm application/wasm, ...), never a file outside ROOT,
// GET and HEAD only, no caching; a folder serves its index.html.
// Usage: node scripts/serve.mjs [--root DIR] [--port N] [--csp POLICY] [--quiet]
//   --port 0 (the default) picks a free port; the URL is printed on stdout as
//   "serve: http://127.0.0.1:PORT/". --csp adds a Content-Security-Policy
//   header to every answer, e.g. --csp "script-src 'self' 'wasm-unsafe-eval'".
// As a module: const { url, close } = await serve({ root, port, csp }).
// SPDX-License-Identifier: GPL-3.0-or-later
import { createReadStream } from 'node:fs';
import { stat } from 'node:fs/promises';
import { createServer } from 'node:http';
import { dirname, extname, join, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

/** MIME type by file extension; anything else is application/octet-stream. */
export const MIME_TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.htm': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.cjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json; charset=utf-8',
  '.map': 'application/json; charset=utf-8',
  '.wasm': 'application/wasm',
  '.svg': 'image/svg+xml',
  '.png': 'image/png',
  '.jpg': 'image/jpeg',
  '.jpeg': 'image/jpeg',
  '.gif': 'image/gif',
  '.ico': 'image/x-icon',
  '.txt': 'text/plain; charset=utf-8',
  '.md': 'text/markdown; charset=utf-8',
  '.off': 'text/plain; charset=utf-8',
  '.stl': 'model/stl',
  '.mesh': 'text/plain; charset=utf-8',
  '.vtu': 'application/xml',
  '.d.ts': 'text/plain; charset=utf-8',
};

function send(res, status, text, headers) {
  res.writeHead(status, { ...headers, 'Content-Type': 'text/plain; charset=utf-8' });
  res.end(`${status} ${text}\n`);
}

/**
 * Starts the server. Resolves to { url, port, server, close() } once it
 * listens; `close()` resolves when it has stopped.
 */
export async function serve({ root = resolve(dirname(fileURLToPath(import.meta.url)), '..'), port = 0,
                              host = '127.0.0.1', csp = '', cacheControl = 'no-store', log = () => {} } = {}) {
  const base = resolve(root);
  // cacheControl: 'no-store' by default; a measurement of the browser's wasm
  // code cache needs one that lets the HTTP cache keep the files
  // (examples/node/wasm_browser.mjs: 'max-age=3600').
  const common = { 'Cache-Control': cacheControl, 'X-Content-Type-Options': 'nosniff' };
  if (csp) common['Content-Security-Policy'] = csp;
  const server = createServer(async (req, res) => {
    if (req.method !== 'GET' && req.method !== 'HEAD') {
      send(res, 405, 'method not allowed', { ...common, Allow: 'GET, HEAD' });
      return;
    }
    let path;
    try {
      path = decodeURIComponent(new URL(req.url, 'http://localhost').pathname);
    } catch {
      send(res, 400, 'bad request', common);
      return;
    }
    let file = resolve(join(base, path));
    if (file !== base && !file.startsWith(base + sep)) {
      send(res, 403, 'forbidden', common);
      return;
    }
    try {
      let info = await stat(file);
      if (info.isDirectory()) {
        file = join(file, 'index.html');
        info = await stat(file);
      }
      if (!info.isFile()) throw new Error('not a file');
      const type = MIME_TYPES[file.endsWith('.d.ts') ? '.d.ts' : extname(file).toLowerCase()] ?? 'application/octet-stream';
      res.writeHead(200, { ...common, 'Content-Type': type, 'Content-Length': info.size });
      log(`${req.method} ${path} 200`);
      if (req.method === 'HEAD') {
        res.end();
        return;
      }
      createReadStream(file).on('error', () => res.destroy()).pipe(res);
    } catch {
      log(`${req.method} ${path} 404`);
      send(res, 404, 'not found', common);
    }
  });
  await new Promise((ok, fail) => {
    server.once('error', fail);
    server.listen(port, host, ok);
  });
  const actual = server.address().port;
  return {
    url: `http://${host}:${actual}/`,
    port: actual,
    server,
    close: () => new Promise((ok) => {
      server.close(() => ok());
      server.closeAllConnections?.();
    }),
  };
}

// ---- Command line --------------------------------------------------------------

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const args = process.argv.slice(2);
  const opts = { port: 0, csp: '', quiet: false };
  const usage = 'usage: node scripts/serve.mjs [--root DIR] [--port N] [--csp POLICY] [--quiet]';
  for (let i = 0; i < args.length; ++i) {
    const a = args[i];
    const value = () => {
      if (i + 1 >= args.length) {
        console.error(`serve: ${a} needs a value\n${usage}`);
        process.exit(1);
      }
      return args[++i];
    };
    if (a === '--root') opts.root = value();
    else if (a === '--port') {
      opts.port = Number(value());
      if (!Number.isInteger(opts.port) || opts.port < 0 || opts.port > 65535) {
        console.error(`serve: --port needs a whole number in [0, 65535]\n${usage}`);
        process.exit(1);
      }
    } else if (a === '--csp') opts.csp = value();
    else if (a === '--quiet') opts.quiet = true;
    else if (a === '--help' || a === '-h') {
      console.log(usage);
      process.exit(0);
    } else {
      console.error(`serve: unknown argument '${a}'\n${usage}`);
      process.exit(1);
    }
  }
  try {
    const s = await serve({ ...opts, log: opts.quiet ? () => {} : (line) => console.error(`serve: ${line}`) });
    console.log(`serve: ${s.url}`);
    const stop = () => s.close().then(() => process.exit(0));
    process.on('SIGINT', stop);
    process.on('SIGTERM', stop);
  } catch (e) {
    console.error(`serve: cannot listen: ${e.message}`);
    process.exit(1);
  }
}
