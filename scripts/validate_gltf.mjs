#!/usr/bin/env node
// Validates a glTF 2.0 asset with the Khronos glTF validator.
//
//   node scripts/validate_gltf.mjs FILE.glb|FILE.gltf
//
// Prints the issue counts and every error, warning, info and hint with its code, JSON pointer
// and message, including those of external resources (buffers, images) read relative to the
// file. Exits 0 when there are no errors (warnings are printed, not fatal), 1 when there are
// errors, 2 on bad usage or when the validator or the file cannot be read.
//
// The validator is the npm package scripts/setup.sh installs into
// <repo>/.cache/gltf-validator/node_modules/gltf-validator; WIRERIG_GLTF_VALIDATOR (the package
// folder) overrides that location.
import fs from 'node:fs';
import path from 'node:path';
import {createRequire} from 'node:module';
import {fileURLToPath} from 'node:url';

const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const validatorDir = process.env.WIRERIG_GLTF_VALIDATOR ||
    path.join(repoRoot, '.cache', 'gltf-validator', 'node_modules', 'gltf-validator');

function fail(message) {
  console.error(`validate_gltf: ${message}`);
  process.exit(2);
}

const args = process.argv.slice(2);
if (args.length !== 1 || args[0].startsWith('-')) {
  fail('usage: node scripts/validate_gltf.mjs FILE.glb|FILE.gltf');
}
const file = path.resolve(args[0]);

let validator;
try {
  validator = createRequire(import.meta.url)(validatorDir);
} catch (error) {
  fail(
      `cannot load the glTF validator from ${validatorDir} (run scripts/setup.sh, or set ` +
      `WIRERIG_GLTF_VALIDATOR): ${error.message}`);
}

let data;
try {
  data = new Uint8Array(fs.readFileSync(file));
} catch (error) {
  fail(`cannot read ${file}: ${error.message}`);
}

const severityNames = ['error', 'warning', 'info', 'hint'];

let report;
try {
  report = await validator.validateBytes(data, {
    uri: path.basename(file),
    maxIssues: 0,  // unlimited
    writeTimestamp: false,
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      const resource = path.resolve(path.dirname(file), decodeURIComponent(uri));
      fs.readFile(resource, (error, bytes) => {
        if (error) {
          reject(error.toString());
        } else {
          resolve(new Uint8Array(bytes));
        }
      });
    }),
  });
} catch (error) {
  fail(`${file}: the validator could not read the asset: ${error}`);
}

const issues = report.issues;
console.log(
    `${file}: glTF validator ${validator.version()}: ` +
    `${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
    `${issues.numInfos} infos, ${issues.numHints} hints`);
for (const message of issues.messages) {
  const severity = severityNames[message.severity] ?? `severity ${message.severity}`;
  const where = message.pointer ?? (message.offset !== undefined ? `@${message.offset}` : '');
  console.log(`  ${severity}: ${message.code} ${where}: ${message.message}`);
}
process.exit(issues.numErrors > 0 ? 1 : 0);
