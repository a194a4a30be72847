// Headless Chromium driven over the DevTools protocol on a pipe (file descriptors 3 and 4, NUL-separated
// JSON): no port to pick, nothing for other processes to connect to. Shared by the browser tests'
// drivers: web/capture.mjs (the player) and lib/report/report_check.mjs (the report page).
//
//   const browser = launchChromium('chromium', { size: '256x256', onEvent: (message) => ... });
//   const { targetId } = await browser.send('Target.createTarget', { url: 'about:blank' });
//   ...
//   await browser.close();
//
// send() answers with the command's result or rejects with its error; onEvent receives every message
// that is not an answer (events, with their sessionId when they come from an attached page).
import { spawn } from 'node:child_process';

export function launchChromium(program, { size = '256x256', onEvent = () => {} } = {}) {
  const child = spawn(program, [
    '--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
    '--no-first-run', '--disable-extensions', '--hide-scrollbars', '--remote-debugging-pipe',
    `--window-size=${size.replace('x', ',')}`, 'about:blank',
  ], { stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe'] });
  let next = 0, buffer = '', stderr = '';
  const waiting = new Map();
  child.stderr.on('data', (d) => { stderr = (stderr + d).slice(-4000); });
  child.stdio[4].on('data', (data) => {
    buffer += data;
    for (let end; (end = buffer.indexOf('\0')) >= 0; buffer = buffer.slice(end + 1)) {
      const message = JSON.parse(buffer.slice(0, end));
      const reply = message.id === undefined ? undefined : waiting.get(message.id);
      if (!reply) {
        if (message.method) onEvent(message);
        continue;
      }
      waiting.delete(message.id);
      if (message.error) reply.reject(new Error(message.error.message));
      else reply.resolve(message.result);
    }
  });
  const exited = new Promise((done) => child.on('exit', done));
  child.on('error', (e) => { for (const w of waiting.values()) w.reject(e); });
  exited.then(() => { for (const w of waiting.values()) w.reject(new Error(`chromium exited: ${stderr}`)); });
  return {
    send(method, params = {}, sessionId = undefined) {
      const id = ++next;
      child.stdio[3].write(JSON.stringify({ id, method, params, sessionId }) + '\0');
      return new Promise((resolve, reject) => waiting.set(id, { resolve, reject }));
    },
    async close() {
      child.stdio[3].end();
      const timer = setTimeout(() => child.kill('SIGKILL'), 10000);
      await exited;
      clearTimeout(timer);
    },
  };
}
