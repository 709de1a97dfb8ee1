/**
 * The public API of akap.
 *
 * - The core, in a page or in Node: {@link init}, {@link triangulate}, {@link meshFromArrays},
 *   the built-in shapes and the {@link Deformer}.
 * - Deformation operators: {@link DefOpTrainer} trains a {@link DefOp}, which poses a mesh in
 *   closed form; {@link groundTruth} is the deformation it approximates.
 * - Animations out: {@link encodeAnimation} (GIF, APNG), {@link zipFiles},
 *   {@link animationToJson} and {@link animationFromJson}, {@link spriteSheetTable}.
 * - The posing widget for pages: {@link mount} it into an element, or register the
 *   `<akap-deformer>` custom element with {@link defineElement}.
 *
 * @example
 * ```ts
 * import { init, defaultShape, triangulate, Deformer } from "akap";
 * await init();
 * const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.05 });
 * const deformer = new Deformer(mesh.positions, mesh.triangles);
 * deformer.setHandles([0, 42]);
 * deformer.step([0, 0, 0.01, 0.02]);
 * ```
 *
 * @packageDocumentation
 */
export * from "./core.js";
export * from "./defop.js";
export { defaultWorkerCount, trainDefOp, type TrainControl, type Trained, type TrainProgress } from "./defop-pool.js";
export { readOperatorFile, type OperatorFile } from "./defop-file.js";
export {
  METHODS,
  Widget,
  mount,
  type GalleryItem,
  type MethodPreset,
  type PoseDetail,
  type WidgetOptions,
  type AnimationExport,
  type AnimationExportFormat,
  type AnimationExportOptions,
  type Easing,
  type KeyInfo,
  type SpriteSheet,
} from "./widget/widget.js";
export { defineElement, type AkapDeformerElement } from "./widget/element.js";
export type { SessionData, SessionEvent, SessionMesh, SessionShape, ShapeSpec } from "./session.js";
export { Session, parseSession, sessionMesh } from "./session.js";
export * from "./import.js";
export * from "./animation-files.js";
