// Validates a .glb or .gltf with the Khronos glTF validator; prints one summary line and
// the first issues, exits 1 when the file has errors. Usage: node validate.mjs FILE
import { readFile } from 'node:fs/promises';
import validator from 'gltf-validator';

const file = process.argv[2];
if (!file) {
  console.error('usage: node validate.mjs FILE.glb');
  process.exit(2);
}
const bytes = new Uint8Array(await readFile(file));
const report = await validator.validateBytes(bytes, { maxIssues: 50 });
const i = report.issues;
console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints` +
            ` (${report.info ? report.info.drawCallCount + ' draw calls, ' + report.info.totalVertexCount + ' vertices' : ''})`);
for (const m of i.messages.slice(0, 20))
  console.log(`  ${['error', 'warning', 'info', 'hint'][m.severity]} ${m.code}: ${m.message} at ${m.pointer ?? m.offset ?? ''}`);
process.exit(i.numErrors > 0 ? 1 : 0);
