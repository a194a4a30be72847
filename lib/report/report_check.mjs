// Checks the HTML page of `dqskin report` in headless Chromium against the report.json beside it: the test
// driver of report_check.cmake, usable by hand on any output of `dqskin report`.
//
//   node lib/report/report_check.mjs [--chromium PROGRAM] REPORT_DIR
//
// Opens REPORT_DIR/report.html from file://, waits for its load event, then checks that
//   - nothing went wrong: no console error, no uncaught exception, no failed request;
//   - nothing came from anywhere: every request is a file: or data: URL;
//   - the joint table holds one row per joint of report.json (data-joint="<skin>:<joint>"), and in it one
//     cell per figure (data-key) whose data-value equals the JSON number (relative 1e-12; "" for null) and
//     whose text is the number as the page formats it (shownNumber below, report_numbers.hpp's rule; "–"
//     for null);
//   - every image of report.json's "images" is an <img data-file=…> that decoded (naturalWidth > 0) from a
//     data:image/png URI.
// Prints what it checked, or one line per problem. Exit status: 0 no problem, 1 problems, 2 usage or the
// browser could not run.
import { existsSync, readFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { launchChromium } from '../../web/chromium_pipe.mjs';

// The table's figures, as the contract of report.json names them: "vertices" is the joint's, the others
// are its summary's.
const keys = ['vertices', 'lbs_dib_max', 'dqs_dib_max', 'candy_wrapper', 'dqs_bulge', 'twist_max', 'bend_max', 'flips'];
const absent = '\u2013';

function usage(message) {
  console.error(`report_check: ${message}\nusage: node report_check.mjs [--chromium PROGRAM] REPORT_DIR`);
  process.exit(2);
}

const args = process.argv.slice(2);
let chromium = 'chromium', dir;
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--chromium') {
    if (i + 1 >= args.length) usage('--chromium needs a value');
    chromium = args[++i];
  } else if (args[i].startsWith('--')) usage(`${args[i]}: unknown option`);
  else if (dir === undefined) dir = args[i];
  else usage(`${args[i]}: one REPORT_DIR only`);
}
if (dir === undefined) usage('REPORT_DIR is needed');
const htmlPath = resolve(join(dir, 'report.html'));
let report;
try {
  report = JSON.parse(readFileSync(join(dir, 'report.json'), 'utf8'));
} catch (e) {
  usage(`${join(dir, 'report.json')}: ${e.message}`);
}
if (!existsSync(htmlPath)) usage(`${htmlPath}: no such file`);

// report_numbers.hpp's shown_number(): 3 significant digits, integers whole, scientific outside
// [1e-4, 1e15), ties to even (toFixed rounds an exact tie away from zero, std::to_chars to even).
function shownNumber(x) {
  if (!Number.isFinite(x)) return absent;
  const a = Math.abs(x);
  if (a < 1e15 && Number.isInteger(x)) return String(x);
  // No exact ties below 1e-4 (a 4-digit decimal ending in 5 times 10^-7 or less is not a binary fraction).
  if (a < 1e-4 || a >= 1e15) return x.toExponential(2).replace('e+', 'e');
  let decimals = 0;
  for (const bound of [100, 10, 1, 0.1, 0.01, 0.001]) if (a < bound) ++decimals;
  const exact = a.toFixed(100);  // every decimal of |x| (at or above 1e-4, at most 66 of them)
  const point = exact.indexOf('.');
  const kept = exact.slice(0, decimals === 0 ? point : point + 1 + decimals);
  if (/^50*$/.test(exact.slice(point + 1 + decimals)) && Number(kept.at(-1)) % 2 === 0) return (x < 0 ? '-' : '') + kept;
  return x.toFixed(decimals);
}

const sameNumber = (a, b) => a === b || Math.abs(a - b) <= 1e-12 * Math.max(Math.abs(a), Math.abs(b));

const problems = [];
const requests = [];
let loaded;
const loadedPromise = new Promise((done) => { loaded = done; });
const browser = launchChromium(chromium, {
  size: '1200x900',
  onEvent({ method, params }) {
    if (method === 'Runtime.consoleAPICalled' && (params.type === 'error' || params.type === 'assert'))
      problems.push(`console ${params.type}: ${params.args.map((a) => a.value ?? a.description ?? '').join(' ')}`);
    else if (method === 'Runtime.exceptionThrown')
      problems.push(`exception: ${(params.exceptionDetails.exception?.description ?? params.exceptionDetails.text).split('\n')[0]}`);
    else if (method === 'Log.entryAdded' && params.entry.level === 'error')
      problems.push(`console error (${params.entry.source}): ${params.entry.text}${params.entry.url ? ' ' + params.entry.url : ''}`);
    else if (method === 'Network.requestWillBeSent') {
      const url = params.request.url;
      requests.push(url);
      if (!/^(file|data):/.test(url)) problems.push(`network request: ${url}`);
    } else if (method === 'Network.loadingFailed')
      problems.push(`failed request: ${params.errorText}${params.blockedReason ? ' (' + params.blockedReason + ')' : ''}`);
    else if (method === 'Page.loadEventFired') loaded();
  },
});

// What the page shows, read in the page: the table's rows and cells, and the images.
const readPage = `(() => {
  const rows = [...document.querySelectorAll('tr[data-joint]')].map((tr) => ({
    joint: tr.dataset.joint,
    cells: [...tr.querySelectorAll('td[data-key]')].map((td) => ({
      key: td.dataset.key, value: td.getAttribute('data-value'), text: td.textContent.trim() })),
  }));
  const images = [...document.querySelectorAll('img[data-file]')].map((img) => ({
    file: img.dataset.file, width: img.naturalWidth, complete: img.complete, src: img.getAttribute('src').slice(0, 22) }));
  return { rows, images, title: document.title };
})()`;

let page;
try {
  const { targetId } = await browser.send('Target.createTarget', { url: 'about:blank' });
  const { sessionId } = await browser.send('Target.attachToTarget', { targetId, flatten: true });
  for (const domain of ['Page', 'Runtime', 'Log', 'Network']) await browser.send(`${domain}.enable`, {}, sessionId);
  const url = pathToFileURL(htmlPath).href;
  const navigation = await browser.send('Page.navigate', { url }, sessionId);
  if (navigation.errorText) problems.push(`${url}: ${navigation.errorText}`);
  const timeout = new Promise((done) => setTimeout(() => done('timeout'), 30000));
  if (await Promise.race([loadedPromise, timeout]) === 'timeout') problems.push(`${url}: no load event within 30 s`);
  await new Promise((done) => setTimeout(done, 200));  // late console messages
  const { result } = await browser.send('Runtime.evaluate', { expression: readPage, returnByValue: true }, sessionId);
  page = result.value;
  await browser.send('Target.closeTarget', { targetId });
} catch (e) {
  console.error(`report_check: ${e.message}`);
  await browser.close();
  process.exit(2);
}
await browser.close();

// The table against report.json.
const rows = new Map();
for (const row of page.rows) {
  if (rows.has(row.joint)) problems.push(`joint ${row.joint}: more than one row`);
  rows.set(row.joint, row);
}
let cellsChecked = 0;
const joints = Array.isArray(report.joints) ? report.joints : [];
for (const joint of joints) {
  const id = `${joint.skin}:${joint.joint}`;
  const row = rows.get(id);
  rows.delete(id);
  if (!row) {
    problems.push(`joint ${id} (${joint.name}): no row in the table`);
    continue;
  }
  for (const key of keys) {
    const expected = key === 'vertices' ? joint.vertices : joint.summary?.[key];
    const cell = row.cells.find((c) => c.key === key);
    ++cellsChecked;
    if (!cell) {
      problems.push(`joint ${id} (${joint.name}): no ${key} cell`);
    } else if (expected === null || expected === undefined) {
      if (cell.value !== '' || cell.text !== absent)
        problems.push(`joint ${id} (${joint.name}) ${key}: null in report.json, data-value "${cell.value}" and text "${cell.text}" on the page`);
    } else if (cell.value === '' || !sameNumber(Number(cell.value), expected)) {
      problems.push(`joint ${id} (${joint.name}) ${key}: data-value "${cell.value}", report.json ${expected}`);
    } else if (cell.text !== shownNumber(expected)) {
      problems.push(`joint ${id} (${joint.name}) ${key}: shows "${cell.text}", expected "${shownNumber(expected)}" for ${expected}`);
    }
  }
}
for (const id of rows.keys()) problems.push(`joint ${id}: a row of the table that report.json does not have`);

// The images.
const images = Array.isArray(report.images) ? report.images : [];
for (const image of images) {
  const shown = page.images.filter((i) => i.file === image.file);
  if (shown.length === 0) problems.push(`image ${image.file}: not on the page`);
  for (const i of shown) {
    if (!i.src.startsWith('data:image/png;base64,')) problems.push(`image ${image.file}: not a data:image/png URI`);
    if (!i.complete || i.width === 0) problems.push(`image ${image.file}: did not decode (naturalWidth ${i.width})`);
  }
}

for (const problem of problems) console.log(`report_check: ${htmlPath}: ${problem}`);
console.log(`report_check: ${htmlPath}: checked ${joints.length} joint rows (${cellsChecked} cells), ` +
            `${images.length} images, ${requests.length} requests, the console and exceptions: ` +
            (problems.length ? `${problems.length} problem${problems.length > 1 ? 's' : ''}` : 'OK'));
process.exit(problems.length ? 1 : 0);
