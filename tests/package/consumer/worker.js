// A Web Worker in the Vite app, importing the package by name.
import * as akap from "akap";
import { rotationError } from "./pose.js";

self.onmessage = async (event) => {
  try {
    await akap.init(event.data.wasm);
    self.postMessage(rotationError(akap));
  } catch (error) {
    self.postMessage({ error: String(error) });
  }
};
