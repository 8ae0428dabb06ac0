// gltf_validate.js FILE.glb - the Khronos glTF validator's report on FILE as JSON on stdout.
// Finds the npm package through NODE_PATH (make deps installs it under build/npm).
const fs = require("fs");
const validator = require("gltf-validator");

const path = process.argv[2];
validator.validateBytes(new Uint8Array(fs.readFileSync(path)), { uri: path, maxIssues: 0 })
    .then((report) => process.stdout.write(JSON.stringify(report, null, 1) + "\n"))
    .catch((error) => {
        process.stderr.write(`gltf-validator: ${error}\n`);
        process.exit(1);
    });
