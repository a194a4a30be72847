// Draws frames with the player in headless Chromium and saves them as PNGs: the test driver of
// web/player_test.cmake, usable by hand too.
//
//   node web/capture.mjs --root DIR --out SHOTS [--chromium PROGRAM] [--size 256x256] NAME=QUERY ...
//
// DIR holds player/ (scripts/install/player.sh) and the bakes; each NAME=QUERY opens
// player/?QUERY&size=…&capture=1 and writes SHOTS/NAME.png from the canvas. A static server of DIR
// listens on 127.0.0.1 on a free port while the captures run and is closed afterwards. Chromium runs with
// SwiftShader's WebGL2 (no GPU needed); the page puts the canvas in <pre id="capture"> and marks its body
// data-ready (or data-error), which this script waits for over the DevTools protocol.
// Exit status: 0 all written, 1 a page reported an error or drew nothing (its message printed), 2 usage.
import { createServer } from 'node:http';
import { mkdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { launchChromium } from './chromium_pipe.mjs';

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
    if (!['--root', '--out', '--chromium', '--size'].includes(a)) usage(`${a}: unknown option`);
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
  try {
    let file = normalize(join(root, decodeURIComponent(new URL(request.url, 'http://x').pathname)));
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

// Opens the page in a fresh tab, waits until it says it is done (body data-ready or data-error), and
// returns what it captured.
async function capture(browser, url) {
  const { targetId } = await browser.send('Target.createTarget', { url: 'about:blank' });
  const { sessionId } = await browser.send('Target.attachToTarget', { targetId, flatten: true });
  try {
    // Answers once the page's document is committed: the evaluation below runs in it, not in about:blank.
    const navigation = await browser.send('Page.navigate', { url }, sessionId);
    if (navigation.errorText) return { error: `${url}: ${navigation.errorText}` };
    const waitForPage = `new Promise((done) => {
      const started = Date.now();
      const check = () => {
        const body = document.body;
        if (body && (body.dataset.ready || body.dataset.error))
          done({ error: body.dataset.error, image: document.getElementById('capture')?.textContent });
        else if (Date.now() - started > 90000) done({ error: 'the page did not finish within 90 s' });
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

mkdirSync(options.out, { recursive: true });
// One headless Chromium for every capture (chromium_pipe.mjs).
const browser = launchChromium(options.chromium, { size: options.size });
let failed = false;
try {
  for (const job of jobs) {
    const url = `http://127.0.0.1:${port}/player/?${job.query}&size=${options.size}&capture=1`;
    const page = await capture(browser, url);
    const shot = page.image?.match(/^data:image\/png;base64,([A-Za-z0-9+/=]+)$/);
    if (page.error || !shot) {
      console.error(`capture: ${job.name}: ${page.error ?? 'the page drew nothing'}`);
      failed = true;
      continue;
    }
    writeFileSync(join(options.out, `${job.name}.png`), Buffer.from(shot[1], 'base64'));
    console.log(`capture: ${job.name}.png  ${job.query}`);
  }
} catch (e) {
  console.error(`capture: ${e.message}`);
  failed = true;
} finally {
  await browser.close();
  server.close();
}
process.exit(failed ? 1 : 0);
