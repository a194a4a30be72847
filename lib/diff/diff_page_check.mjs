// Checks the page of `dqskin diff --html DIR` in headless Chromium against the diff's JSON report: the
// test driver of diff_page_check.cmake, usable by hand on any page.
//
//   node lib/diff/diff_page_check.mjs [--chromium PROGRAM] [--shot FILE] DIR REPORT_JSON
//
// Opens DIR/index.html from file://, then checks that
//   - nothing went wrong: no console error, no uncaught exception, no failed request, and every request
//     is a file: or data: URL (nothing from the network);
//   - every pair of the report (of a geometric diff: every clip or file) has one section, in the page's
//     order: failures, then warnings, then passes; every link to a section finds it;
//   - every picture of every section decodes (lazy ones loaded by scrolling to them);
//   - the toggle, clicked with the mouse, hides the candidate over the reference and shows it again, and
//     the swipe clips the candidate at the slider's place;
//   - a geometric diff's clips have their chart, one point per frame of the report;
// and, with --shot, saves a screenshot of the first section. Prints what it checked, or one line per
// problem. Exit status: 0 no problem, 1 problems, 2 usage or the browser could not run.
import { existsSync, readFileSync, writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { launchChromium } from '../../web/chromium_pipe.mjs';

function usage(message) {
  console.error(`diff_page_check: ${message}\nusage: node diff_page_check.mjs [--chromium PROGRAM] [--shot FILE] DIR REPORT_JSON`);
  process.exit(2);
}

const args = process.argv.slice(2);
let chromium = 'chromium', shot, dir, reportPath;
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--chromium' || args[i] === '--shot') {
    if (i + 1 >= args.length) usage(`${args[i]} needs a value`);
    if (args[i] === '--chromium') chromium = args[++i];
    else shot = args[++i];
  } else if (args[i].startsWith('--')) usage(`${args[i]}: unknown option`);
  else if (dir === undefined) dir = args[i];
  else if (reportPath === undefined) reportPath = args[i];
  else usage(`${args[i]}: one DIR and one REPORT_JSON`);
}
if (reportPath === undefined) usage('DIR and REPORT_JSON are needed');
const htmlPath = resolve(join(dir, 'index.html'));
if (!existsSync(htmlPath)) usage(`${htmlPath}: no such file`);
let report;
try {
  report = JSON.parse(readFileSync(reportPath, 'utf8'));
} catch (e) {
  usage(`${reportPath}: ${e.message}`);
}

const problems = [];
const requests = [];
let loaded;
const loadedPromise = new Promise((done) => { loaded = done; });
const browser = launchChromium(chromium, {
  size: '1400x1000',
  onEvent({ method, params }) {
    if (method === 'Runtime.consoleAPICalled' && (params.type === 'error' || params.type === 'assert'))
      problems.push(`console ${params.type}: ${params.args.map((a) => a.value ?? a.description ?? '').join(' ')}`);
    else if (method === 'Runtime.exceptionThrown')
      problems.push(`exception: ${(params.exceptionDetails.exception?.description ?? params.exceptionDetails.text).split('\n')[0]}`);
    else if (method === 'Log.entryAdded' && params.entry.level === 'error')
      problems.push(`console error (${params.entry.source}): ${params.entry.text}${params.entry.url ? ' ' + params.entry.url : ''}`);
    else if (method === 'Network.requestWillBeSent') {
      requests.push(params.request.url);
      if (!/^(file|data):/.test(params.request.url)) problems.push(`network request: ${params.request.url}`);
    } else if (method === 'Network.loadingFailed')
      problems.push(`failed request: ${params.errorText}${params.blockedReason ? ' (' + params.blockedReason + ')' : ''}`);
    else if (method === 'Page.loadEventFired') loaded();
  },
});

const rank = { FAIL: 2, WARN: 1, PASS: 0 };
let checkedImages = 0, checkedCharts = 0, interactions = 'none';
try {
  const { targetId } = await browser.send('Target.createTarget', { url: 'about:blank' });
  const { sessionId } = await browser.send('Target.attachToTarget', { targetId, flatten: true });
  const evaluate = async (expression) =>
    (await browser.send('Runtime.evaluate', { expression, returnByValue: true, awaitPromise: true }, sessionId)).result.value;
  for (const domain of ['Page', 'Runtime', 'Log', 'Network']) await browser.send(`${domain}.enable`, {}, sessionId);
  const url = pathToFileURL(htmlPath).href;
  const navigation = await browser.send('Page.navigate', { url }, sessionId);
  if (navigation.errorText) problems.push(`${url}: ${navigation.errorText}`);
  const timeout = new Promise((done) => setTimeout(() => done('timeout'), 30000));
  if (await Promise.race([loadedPromise, timeout]) === 'timeout') problems.push(`${url}: no load event within 30 s`);

  // Sections against the report.
  const sections = await evaluate(`[...document.querySelectorAll('section.pair')].map((s) => ({
    id: s.id, name: s.dataset.name, status: s.dataset.status }))`);
  const pairs = report.pairs ?? report.clips ?? [];  // an image diff's pairs, a geometric diff's clips or files
  if (sections.length !== pairs.length) problems.push(`${sections.length} sections for ${pairs.length} entries of the report`);
  for (const p of pairs) {
    const s = sections.find((x) => x.name === p.name);
    if (!s) problems.push(`pair ${p.name}: no section`);
    else if (s.status !== p.status) problems.push(`pair ${p.name}: section says ${s.status}, the report ${p.status}`);
  }
  for (let i = 1; i < sections.length; ++i)
    if (rank[sections[i].status] > rank[sections[i - 1].status])
      problems.push(`section ${sections[i].id} (${sections[i].status}) after ${sections[i - 1].id} (${sections[i - 1].status})`);
  const brokenLinks = await evaluate(`[...document.querySelectorAll('a[href^="#"]')]
    .map((a) => a.getAttribute('href')).filter((h) => !document.getElementById(h.slice(1)))`);
  for (const h of brokenLinks) problems.push(`link ${h}: no such section`);

  // Every picture, each brought into view so that lazy ones load.
  const images = await evaluate(`(async () => {
    const all = [...document.querySelectorAll('section img')];
    for (const img of all) {
      img.scrollIntoView();
      if (!img.complete) await new Promise((done) => { img.onload = img.onerror = done; setTimeout(done, 5000); });
    }
    return all.map((img) => ({ src: img.getAttribute('src'), width: img.naturalWidth }));
  })()`);
  for (const img of images) if (img.width === 0) problems.push(`picture ${img.src}: did not decode`);
  checkedImages = images.length;

  // The toggle with the mouse, the swipe through its input event.
  const box = await evaluate(`(() => {
    const c = document.querySelector('.compare');
    if (!c) return null;
    c.scrollIntoView({ block: 'center' });
    const r = c.querySelector('button.toggle').getBoundingClientRect();
    return { x: r.x + r.width / 2, y: r.y + r.height / 2 };
  })()`);
  if (box) {
    const state = `(() => { const c = document.querySelector('.compare'), o = c.querySelector('img.over');
      return { visibility: getComputedStyle(o).visibility, clip: getComputedStyle(o).clipPath, label: c.querySelector('.showing').textContent }; })()`;
    const click = async () => {
      for (const type of ['mousePressed', 'mouseReleased'])
        await browser.send('Input.dispatchMouseEvent', { type, x: box.x, y: box.y, button: 'left', clickCount: 1 }, sessionId);
    };
    const before = await evaluate(state);
    await click();
    const toggled = await evaluate(state);
    await click();
    const back = await evaluate(state);
    if (before.visibility !== 'visible' || toggled.visibility !== 'hidden' || back.visibility !== 'visible')
      problems.push(`toggle: candidate ${before.visibility} → ${toggled.visibility} → ${back.visibility}, expected visible → hidden → visible`);
    if (toggled.label !== 'A (reference)') problems.push(`toggle: says "${toggled.label}" while showing the reference`);
    await evaluate(`(() => { const s = document.querySelector('.compare input.swipe'); s.value = 30;
      s.dispatchEvent(new Event('input')); })()`);
    const swiped = await evaluate(state);
    if (swiped.clip !== 'inset(0px 0px 0px 30%)') problems.push(`swipe at 30: candidate clipped "${swiped.clip}"`);
    interactions = 'toggle and swipe';
  } else if (report.kind !== 'bakes' && pairs.some((p) => p.status !== 'PASS' && p.max_error)) {  // bakes: figures only
    problems.push('no toggle or swipe for pairs that differ');
  }

  // A geometric diff's clips: each with more than one frame has its chart, one point per frame.
  if (report.clips && report.kind === 'gltf') {
    const charts = await evaluate(`[...document.querySelectorAll('section.pair')].map((s) => ({
      name: s.dataset.name, points: s.querySelectorAll('svg.chart circle.frame').length,
      width: s.querySelector('svg.chart')?.getBoundingClientRect().width ?? 0 }))`);
    for (const clip of report.clips) {
      const chart = charts.find((c) => c.name === clip.name);
      if (!chart || clip.frames.length < 2) continue;
      if (chart.points !== clip.frames.length) problems.push(`clip ${clip.name}: chart has ${chart.points} points for ${clip.frames.length} frames`);
      if (chart.width === 0) problems.push(`clip ${clip.name}: chart not shown`);
    }
    checkedCharts = charts.filter((c) => c.points > 0).length;
  }

  if (shot) {
    await evaluate(`(() => { const c = document.querySelector('.compare input.swipe'); if (c) { c.value = 50; c.dispatchEvent(new Event('input')); }
      document.querySelector('section.pair')?.scrollIntoView(); })()`);
    await new Promise((done) => setTimeout(done, 300));
    const { data } = await browser.send('Page.captureScreenshot', { format: 'png' }, sessionId);
    writeFileSync(shot, Buffer.from(data, 'base64'));
  }
  await new Promise((done) => setTimeout(done, 200));  // late console messages
  await browser.send('Target.closeTarget', { targetId });
} catch (e) {
  console.error(`diff_page_check: ${e.message}`);
  await browser.close();
  process.exit(2);
}
await browser.close();

for (const problem of problems) console.log(`diff_page_check: ${htmlPath}: ${problem}`);
console.log(`diff_page_check: ${htmlPath}: checked ${(report.pairs ?? report.clips)?.length ?? 0} sections, ${checkedImages} pictures, ` +
            (report.clips ? `${checkedCharts} charts, ` : '') +
            `${interactions}, ${requests.length} requests, the console and exceptions: ` +
            (problems.length ? `${problems.length} problem${problems.length > 1 ? 's' : ''}` : 'OK'));
process.exit(problems.length ? 1 : 0);
