// A Web Worker of a page without a bundler, importing the package by path.
import * as akap from "../node_modules/akap/www/lib/index.js";
import { rotationError } from "../pose.js";

self.onmessage = async () => {
  try {
    await akap.init();
    self.postMessage(rotationError(akap));
  } catch (error) {
    self.postMessage({ error: String(error) });
  }
};
