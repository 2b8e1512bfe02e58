// Validates glTF binaries with the Khronos glTF validator (npm `gltf-validator`) and prints,
// per file, its error, warning, info and hint counts and every error and warning message.
// Exits 1 when any file has an error. Run through `scripts/gltf-validate.sh`, which installs
// the validator; the tests call it on every file they export.
import { createRequire } from "node:module";
import { readFileSync } from "node:fs";

const require = createRequire(process.env.GLTF_VALIDATOR_DIR + "/");
const validator = require("gltf-validator");

let failed = false;
for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: file,
    maxIssues: 0,
    externalResourceFunction: (uri) => Promise.reject(new Error(`${file}: external resource ${uri}`)),
  });
  const i = report.issues;
  console.log(
    `${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`,
  );
  for (const m of i.messages) {
    if (m.severity <= 1) {
      console.log(`  ${m.severity === 0 ? "error" : "warning"} ${m.code} at ${m.pointer ?? ""}: ${m.message}`);
    }
  }
  failed ||= i.numErrors > 0;
}
process.exit(failed ? 1 : 0);
