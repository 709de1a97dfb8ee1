// Node: the package's core, loaded the way a Node user loads it.
import * as akap from "akap";
import process from "node:process";
import { rotationError } from "./pose.js";

await akap.init();
const { vertices, error } = rotationError(akap);
if (!(vertices > 100 && error < 1e-9)) {
  console.error(`rotation not reproduced: ${vertices} vertices, largest error ${error}`);
  process.exit(1);
}
console.log(`node: ${vertices} vertices rotated rigidly, largest error ${error.toExponential(1)}`);
