// Draws frames of dqskin's bone textures with other runtimes (Babylon.js, PlayCanvas) in headless Chromium
// and saves them as PNGs: the driver of web/runtimes_test.cmake, usable by hand too.
//
//   node web/runtimes/capture.mjs --modules NODE_MODULES --bakes DIR --out SHOTS [--chromium PROGRAM]
//        [--size 256x256] NAME=PAGE?QUERY ...
//   node web/runtimes/capture.mjs --modules NODE_MODULES --bakes DIR --serve    (prints the address, serves)
//
// A static server on 127.0.0.1 (a free port) shows three folders, nothing else:
//   /web/           this repository's web/ (the pages in web/runtimes/ and the player's modules they share)
//   /node_modules/  NODE_MODULES, where scripts/install/node_tools.sh put three, @babylonjs/core and
//                   playcanvas: the pages import the released packages from there, never from a network
//   /bake/          DIR, the bakes
// Each NAME=PAGE?QUERY opens /web/runtimes/PAGE?QUERY&size=…&capture=1 (PAGE: babylon.html or
// playcanvas.html) and writes SHOTS/NAME.png. Chromium runs with SwiftShader's WebGL2 (no GPU needed);
// the page puts the canvas in <pre id="capture"> and marks its body data-ready (or data-error).
// Exit status: 0 all written, 1 a page reported an error or drew nothing (its message printed), 2 usage.
import { createServer } from 'node:http';
import { mkdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { dirname, extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium } from '../chromium_pipe.mjs';

const types = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css',
  '.json': 'application/json', '.glb': 'model/gltf-binary', '.png': 'image/png', '.wasm': 'application/wasm',
};

function usage(message) {
  console.error(`capture: ${message}\nusage: node capture.mjs --modules NODE_MODULES --bakes DIR ` +
    '(--out SHOTS [--chromium PROGRAM] [--size WxH] NAME=PAGE?QUERY ... | --serve)');
  process.exit(2);
}

const args = process.argv.slice(2);
const options = { chromium: 'chromium', size: '256x256' };
const jobs = [];
for (let i = 0; i < args.length; ++i) {
  const a = args[i];
  if (a === '--serve') {
    options.serve = true;
  } else if (a.startsWith('--')) {
    if (!['--modules', '--bakes', '--out', '--chromium', '--size'].includes(a)) usage(`${a}: unknown option`);
    if (i + 1 >= args.length) usage(`${a} needs a value`);
    options[a.slice(2)] = args[++i];
  } else if (/^[A-Za-z0-9_.-]+=[a-z]+\.html\?/.test(a)) {
    const at = a.indexOf('=');
    jobs.push({ name: a.slice(0, at), page: a.slice(at + 1) });
  } else {
    usage(`${a}: expected NAME=PAGE?QUERY`);
  }
}
if (!options.modules || !options.bakes) usage('--modules and --bakes are needed');
if (!options.serve && (!options.out || jobs.length === 0)) usage('--out and at least one capture are needed');
const mounts = {
  web: resolve(dirname(fileURLToPath(import.meta.url)), '..'),
  node_modules: resolve(options.modules),
  bake: resolve(options.bakes),
};

// /MOUNT/rest → a file under that mount's folder; anything else is 404.
const server = createServer((request, response) => {
  try {
    const path = decodeURIComponent(new URL(request.url, 'http://x').pathname);
    const [, mount, rest] = path.match(/^\/([^/]+)(\/.*)?$/) ?? [];
    const root = mounts[mount];
    if (!root) throw new Error('no such mount');
    let file = normalize(join(root, rest ?? '/'));
    if (!(file === root || file.startsWith(root + sep))) throw new Error('outside');
    if (statSync(file).isDirectory()) file = join(file, 'index.html');
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
if (options.serve) {
  console.log(`capture: serving on http://127.0.0.1:${port}/web/runtimes/babylon.html?bake=/bake/… ` +
    `and /web/runtimes/playcanvas.html?bake=/bake/… (Ctrl-C stops)`);
} else {
  process.exit(await captureAll());
}

// Opens the page in a fresh tab, waits until it says it is done (body data-ready or data-error), and
// returns what it captured.
async function capture(browser, url) {
  const { targetId } = await browser.send('Target.createTarget', { url: 'about:blank' });
  const { sessionId } = await browser.send('Target.attachToTarget', { targetId, flatten: true });
  try {
    const navigation = await browser.send('Page.navigate', { url }, sessionId);
    if (navigation.errorText) return { error: `${url}: ${navigation.errorText}` };
    const waitForPage = `new Promise((done) => {
      const started = Date.now();
      const check = () => {
        const body = document.body;
        if (body && (body.dataset.ready || body.dataset.error))
          done({ error: body.dataset.error, image: document.getElementById('capture')?.textContent });
        else if (Date.now() - started > 120000) done({ error: 'the page did not finish within 120 s' });
        else setTimeout(check, 50);
      };
      check();
    })`;
    const { result } = await browser.send('Runtime.evaluate', { expression: waitForPage, awaitPromise: true, returnByValue: true }, sessionId);
    return result.value ?? { error: 'no answer from the page' };
  } finally {
    await browser.send('Target.closeTarget', { targetId });
  }
}

async function captureAll() {
  mkdirSync(options.out, { recursive: true });
  const browser = launchChromium(options.chromium, { size: options.size });
  let failed = false;
  try {
    for (const job of jobs) {
      const url = `http://127.0.0.1:${port}/web/runtimes/${job.page}&size=${options.size}&capture=1`;
      const page = await capture(browser, url);
      const shot = page.image?.match(/^data:image\/png;base64,([A-Za-z0-9+/=]+)$/);
      if (page.error || !shot) {
        console.error(`capture: ${job.name}: ${page.error ?? 'the page drew nothing'}`);
        failed = true;
        continue;
      }
      writeFileSync(join(options.out, `${job.name}.png`), Buffer.from(shot[1], 'base64'));
      console.log(`capture: ${job.name}.png  ${job.page}`);
    }
  } catch (e) {
    console.error(`capture: ${e.message}`);
    failed = true;
  } finally {
    await browser.close();
    server.close();
  }
  return failed ? 1 : 0;
}
