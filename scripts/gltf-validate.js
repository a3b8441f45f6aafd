#!/usr/bin/env node
// Validates GLB/glTF files with the Khronos glTF validator (the gltf-validator npm package, installed
// by scripts/install-browser.sh). Prints one JSON line per file: its counts of errors, warnings,
// infos and hints, and its first messages. Exit 0 when no file has an error, 1 otherwise, 2 when the
// validator cannot be loaded. Usage: node scripts/gltf-validate.js FILE...
'use strict';
const fs = require('fs');
let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('gltf-validate: the gltf-validator package is not installed (npm install -g gltf-validator; '
    + 'NODE_PATH=$(npm root -g))');
  process.exit(2);
}
(async () => {
  let failed = false;
  for (const file of process.argv.slice(2)) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {maxIssues: 50});
    const i = report.issues;
    failed = failed || i.numErrors > 0;
    console.log(JSON.stringify({file, validator: report.validatorVersion, errors: i.numErrors,
      warnings: i.numWarnings, infos: i.numInfos, hints: i.numHints,
      messages: i.messages.slice(0, 10).map(m => `${m.severity} ${m.code} ${m.pointer || ''}: ${m.message}`)}));
  }
  process.exit(failed ? 1 : 0);
})().catch(e => { console.error('gltf-validate: ' + e); process.exit(2); });
