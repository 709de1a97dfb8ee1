/**
 * The set-up worker (see `shape-maker.ts`): with a wasm instance of its own (of the module the
 * page compiled, sent with each request), meshes an outline and computes the deformer's
 * orders, reporting each stage, and sends the shape back with its arrays transferred, not
 * copied.
 */
import { deformerOrders, init } from "../../core.js";
import { STAGES, makeShape, type SetupMessage, type SetupReply } from "./shape-maker.js";

interface WorkerScope {
  onmessage: ((event: MessageEvent<SetupMessage>) => void) | null;
  postMessage(message: SetupReply, transfer: Transferable[]): void;
}

const scope = globalThis as unknown as WorkerScope;

scope.onmessage = (event) => {
  const { id, request, wasm } = event.data;
  const post = (reply: SetupReply, transfer: Transferable[] = []) => scope.postMessage(reply, transfer);
  void (async () => {
    try {
      await init(wasm);
      post({ id, kind: "progress", stage: STAGES.meshing[0], fraction: STAGES.meshing[1] });
      const shape = makeShape(request);
      post({ id, kind: "progress", stage: STAGES.ordering[0], fraction: STAGES.ordering[1] });
      const orders = deformerOrders(shape.mesh.positions, shape.mesh.triangles, request.options);
      const m = shape.mesh;
      const buffers = [
        m.positions,
        m.triangles,
        m.boundaryEdges,
        m.boundaryVertices,
        shape.edges,
        shape.uvs,
        ...orders,
      ];
      post({ id, kind: "done", shape, orders }, [...new Set(buffers.map((a) => a.buffer))]);
    } catch (error) {
      post({ id, kind: "error", message: error instanceof Error ? error.message : String(error) });
    }
  })();
};
