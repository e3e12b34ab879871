// The Khronos glTF-Validator on one file: prints its report's counts and its errors
// and warnings as JSON. Usage: node validate.cjs NODE_MODULES_DIR FILE
const path = require('path');
const fs = require('fs');
const validator = require(path.join(path.resolve(process.argv[2]), 'gltf-validator'));
const file = process.argv[3];
validator
  .validateBytes(new Uint8Array(fs.readFileSync(file)), { maxIssues: 200 })
  .then((report) => {
    const issues = report.issues;
    console.log(JSON.stringify({
      version: report.validatorVersion,
      errors: issues.numErrors,
      warnings: issues.numWarnings,
      messages: issues.messages.filter((m) => m.severity <= 1),
    }));
  })
  .catch((error) => { console.error(String(error)); process.exit(1); });
