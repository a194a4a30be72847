// Draws frames with the player in headless Chromium and saves them as PNGs: the test driver of
// web/player_test.cmake, usable by hand too.
//
//   node web/capture.mjs --root DIR --out SHOTS [--chromium PROGRAM] [--size 256x256] NAME=QUERY ...
//
// DIR holds player/ (scripts/install-player.sh) and the bakes; each NAME=QUERY opens
// player/?QUERY&size=…&capture=1 and writes SHOTS/NAME.png from the canvas. A static server of DIR
// listens on 127.0.0.1 on a free port while the captures run and is closed afterwards. Chromium runs with
// SwiftShader's WebGL2 (no GPU needed) and --dump-dom; the page puts the canvas in <pre id="capture">.
// Exit status: 0 all written, 1 a page reported an error or drew nothing (its message printed), 2 usage.
import { spawn } from 'node:child_process';
import { createServer } from 'node:http';
import { mkdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { extname, join, normalize, resolve, sep } from 'node:path';

const types = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css',
  '.json': 'application/json', '.glb': 'model/gltf-binary', '.png': 'image/png',
};

function usage(message) {
  console.error(`capture: ${message}\nusage: node capture.mjs --root DIR --out SHOTS [--chromium PROGRAM] [--size WxH] NAME=QUERY ...`);
  process.exit(2);
}

const args = process.argv.slice(2);
const options = { chromium: 'chromium', size: '256x256' };
const jobs = [];
for (let i = 0; i < args.length; ++i) {
  const a = args[i];
  if (a.startsWith('--')) {
    if (i + 1 >= args.length) usage(`${a} needs a value`);
    options[a.slice(2)] = args[++i];
  } else if (a.includes('=')) {
    const at = a.indexOf('=');
    jobs.push({ name: a.slice(0, at), query: a.slice(at + 1) });
  } else {
    usage(`${a}: expected NAME=QUERY`);
  }
}
if (!options.root || !options.out || jobs.length === 0) usage('--root, --out and at least one capture are needed');
const root = resolve(options.root);

// Files under root only; anything else is 404.
const server = createServer((request, response) => {
  const path = normalize(join(root, decodeURIComponent(new URL(request.url, 'http://x').pathname)));
  let file = path;
  try {
    if (statSync(file).isDirectory()) file = join(file, 'index.html');
    if (!(file === root || file.startsWith(root + sep))) throw new Error('outside');
    const body = readFileSync(file);
    response.writeHead(200, { 'Content-Type': types[extname(file)] ?? 'application/octet-stream' });
    response.end(body);
  } catch {
    response.writeHead(404);
    response.end();
  }
});
await new Promise((done) => server.listen(0, '127.0.0.1', done));
const port = server.address().port;

function chromium(url) {
  return new Promise((done) => {
    const child = spawn(options.chromium, [
      '--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--disable-gpu-sandbox', '--no-first-run', '--disable-extensions', '--hide-scrollbars',
      `--window-size=${options.size.replace('x', ',')}`,
      // Virtual time waits for the page's fetches and promises; the budget bounds a page that never ends.
      '--virtual-time-budget=60000', '--dump-dom', url,
    ], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '', err = '';
    child.stdout.on('data', (d) => { out += d; });
    child.stderr.on('data', (d) => { err += d; });
    const timer = setTimeout(() => child.kill('SIGKILL'), 120000);
    child.on('close', (status) => { clearTimeout(timer); done({ status, out, err }); });
    child.on('error', (e) => { clearTimeout(timer); done({ status: -1, out, err: String(e) }); });
  });
}

mkdirSync(options.out, { recursive: true });
let failed = false;
for (const job of jobs) {
  const url = `http://127.0.0.1:${port}/player/?${job.query}&size=${options.size}&capture=1`;
  const { status, out, err } = await chromium(url);
  const shot = out.match(/<pre id="capture">data:image\/png;base64,([A-Za-z0-9+/=]+)<\/pre>/);
  if (!shot) {
    const error = out.match(/data-error="([^"]*)"/);
    console.error(`capture: ${job.name}: ${error ? error[1] : `no image (chromium exit ${status}) ${err.split('\n').filter((l) => !/dbus|Fontconfig/.test(l)).slice(-3).join(' ')}`}`);
    failed = true;
    continue;
  }
  writeFileSync(join(options.out, `${job.name}.png`), Buffer.from(shot[1], 'base64'));
  console.log(`capture: ${job.name}.png  ${job.query}`);
}
server.close();
process.exit(failed ? 1 : 0);
