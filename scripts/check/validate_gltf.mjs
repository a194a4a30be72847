// Validates .glb files with the Khronos glTF-Validator and fails when any has an error.
//
//   node scripts/check/validate_gltf.mjs [--validator DIR] FILE_OR_DIR...
//
// DIR is the installed npm package (PREFIX/node_modules/gltf-validator, see scripts/install/node_tools.sh),
// or else $GLTF_VALIDATOR. Folders are searched for .glb files, recursively; a .gltf is validated when it is
// named, with its external files (buffers, images) read from its folder; a .glb may reference files beside it
// only (a baked animation's shared images), and they are validated with it. Prints one line per file
// with its error/warning/info/hint counts and its first messages. Exit status: 0 when no file has an error,
// 1 when one has (or no .glb was found), 2 for a usage problem or a missing validator.
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

function fail(status, message) {
  console.error(`validate_gltf: ${message}`);
  process.exit(status);
}

const args = process.argv.slice(2);
let validatorDir = process.env.GLTF_VALIDATOR || '';
const inputs = [];
for (let i = 0; i < args.length; ++i) {
  if (args[i] === '--validator') validatorDir = args[++i] || '';
  else inputs.push(args[i]);
}
if (inputs.length === 0) fail(2, 'usage: node scripts/check/validate_gltf.mjs [--validator DIR] FILE_OR_DIR...');
if (!validatorDir) fail(2, 'no validator given: pass --validator DIR or set GLTF_VALIDATOR');
if (!fs.existsSync(path.join(validatorDir, 'package.json')))
  fail(2, `the glTF-Validator is not installed at ${validatorDir}; run scripts/install/node_tools.sh ` +
          `${path.dirname(path.dirname(validatorDir))}`);
const validator = createRequire(import.meta.url)(path.resolve(validatorDir));

const files = [];
for (const input of inputs) {
  if (!fs.existsSync(input)) fail(1, `${input} does not exist`);
  if (fs.statSync(input).isDirectory()) {
    // Baked folders nest: OUTDIR/<input>/<animation>/frame_NNNN.glb. (Debian 12's Node.js 18.13
    // predates readdirSync's recursive option.)
    const walk = (dir) => {
      for (const entry of fs.readdirSync(dir, { withFileTypes: true }).sort((a, b) => a.name < b.name ? -1 : 1)) {
        const full = path.join(dir, entry.name);
        if (entry.isDirectory()) walk(full);
        else if (entry.name.endsWith('.glb')) files.push(full);
      }
    };
    walk(input);
  } else {
    files.push(input);
  }
}
if (files.length === 0) fail(1, `no .glb files in ${inputs.join(' ')}`);

const severities = ['error', 'warning', 'info', 'hint'];
let failed = 0;
for (const file of files) {
  const options = {
    uri: path.basename(file),
    maxIssues: 0,
    // A .glb may reference only a file in its own folder (the images that `bake --glb-images shared` writes
    // once beside the frames); any other external reference is itself a defect.
    externalResourceFunction: (uri) => {
      const name = decodeURIComponent(uri);
      if (/[\/\\:]/.test(name) || name === '.' || name === '..')
        return Promise.reject(new Error(`external resource ${uri} refused: not a file beside the .glb`));
      return fs.promises.readFile(path.join(path.dirname(file), name)).then((data) => new Uint8Array(data));
    },
  };
  if (file.endsWith('.gltf')) {
    options.externalResourceFunction = (uri) => fs.promises.readFile(
      path.join(path.dirname(file), decodeURIComponent(uri))).then((data) => new Uint8Array(data));
  }
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), options);
  const i = report.issues;
  const first = [...i.messages].sort((a, b) => a.severity - b.severity).slice(0, 3).map((m) => `${severities[m.severity]} ${m.code} ${m.pointer || ''}: ${m.message}`);
  console.log(`${i.numErrors ? 'FAIL' : 'ok  '} ${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ` +
              `${i.numInfos} infos, ${i.numHints} hints${first.length ? '\n    ' + first.join('\n    ') : ''}`);
  if (i.numErrors) ++failed;
}
console.log(`${files.length - failed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
