// A static file server for target/playground on 127.0.0.1 (tests; `node test/serve.mjs DIR`
// serves by hand). Only GET of files below DIR; the MIME types the page needs.
import { createServer } from 'node:http';
import { readFile } from 'node:fs/promises';
import { extname, join, normalize } from 'node:path';

const TYPES = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.wasm': 'application/wasm', '.png': 'image/png' };

/** Serves `dir`; resolves to {url, close, requests} (every path asked, for the tests). */
export function serve(dir, port = 0) {
  const requests = [];
  const server = createServer(async (req, res) => {
    const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    requests.push(path);
    const file = normalize(join(dir, path.endsWith('/') ? `${path}index.html` : path));
    if (req.method !== 'GET' || !file.startsWith(normalize(dir))) { res.writeHead(405).end(); return; }
    try {
      const body = await readFile(file);
      res.writeHead(200, { 'Content-Type': TYPES[extname(file)] || 'application/octet-stream' }).end(body);
    } catch {
      res.writeHead(404).end();
    }
  });
  return new Promise((resolve) => server.listen(port, '127.0.0.1', () => resolve({
    url: `http://127.0.0.1:${server.address().port}/`,
    requests,
    close: () => new Promise((r) => server.close(r)),
  })));
}

if (process.argv[1] && process.argv[1].endsWith('serve.mjs')) {
  const s = await serve(process.argv[2] || '../../target/playground', Number(process.argv[3] || 8000));
  console.log(`serving on ${s.url}`);
}
