// Type-checked against the shipped .d.ts files (tsc -p . in the consumer project): the API
// as a TypeScript user sees it. The @ts-expect-error lines fail the check if the types
// were lost (an `any` accepts everything, and then the directive is unused).
import {
  Deformer,
  compiledModule,
  defaultShape,
  init,
  mount,
  triangulate,
  type MeshData,
  type Metrics,
  type Widget,
  type WidgetOptions,
} from "akap";

export async function pose(): Promise<Metrics> {
  await init();
  const mesh: MeshData = triangulate(defaultShape(), { targetEdgeLength: 0.05 });
  const deformer = new Deformer(mesh.positions, mesh.triangles, { method: "akap", lambda: 100 });
  deformer.setHandles([0, 42]);
  deformer.step([0, 0, 0.01, 0.02]);
  const positions: Float64Array = deformer.positions();
  // @ts-expect-error the method is "akap", "arap", "mls" or "cauchy-green"
  deformer.setOptions({ method: "fem" });
  // @ts-expect-error positions are numbers
  void new Deformer("0 0 1 0 0 1", [0, 1, 2]);
  const module: WebAssembly.Module = compiledModule();
  void module;
  void positions;
  return deformer.metrics();
}

export async function embed(element: HTMLElement): Promise<Widget> {
  const options: WidgetOptions = { shape: "gingerbread", vertices: 1200, hud: false, wasm: "/akap_bg.wasm" };
  // @ts-expect-error there is no such method
  const wrong: WidgetOptions = { method: "fem" };
  void wrong;
  const widget = await mount(element, options);
  const count: number = widget.vertexCount;
  void count;
  return widget;
}
