// Validates glTF files with the Khronos glTF validator and prints one JSON line per file:
// {"file", "errors", "warnings", "infos", "messages": [first messages]}. Exit status 1 when a
// file has an error. Usage: node validate_gltf.mjs FILE...
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

let failed = false;
for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) => readFile(path.join(path.dirname(file), decodeURIComponent(uri))),
  });
  const issues = report.issues;
  const line = {
    file,
    errors: issues.numErrors,
    warnings: issues.numWarnings,
    infos: issues.numInfos,
    messages: issues.messages.slice(0, 10).map((m) => `${m.severity} ${m.code} ${m.pointer ?? ''} ${m.message}`),
    extensions: report.info ? report.info.extensionsUsed : [],
  };
  if (issues.numErrors > 0) failed = true;
  console.log(JSON.stringify(line));
}
process.exit(failed ? 1 : 0);
