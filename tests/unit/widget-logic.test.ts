/** The widget's logic apart from the page (the drag's velocities are the core's: `src/pose`, tested there): picking, history, geometry, texture maps, keys, options. */
import { beforeAll, describe, expect, it } from "vitest";
import { init } from "../../www/src/index.js";
import { affineThrough } from "../../www/src/widget/view/canvas2d-renderer.js";
import { boundaryLoops, boxUvs, uniqueEdges } from "../../www/src/widget/model/geometry.js";
import { History } from "../../www/src/widget/model/history.js";
import type { KeyPress } from "../../www/src/widget/actions/action.js";
import { keyCommand } from "../../www/src/widget/actions/keys.js";
import { fileKind } from "../../www/src/widget/shapes/shape-files.js";
import { locate, nearestPoint, pointPosition } from "../../www/src/widget/model/picking.js";
import { WIDGET_OPTIONS, widgetSettings } from "../../www/src/widget/options.js";

beforeAll(async () => {
  await init(); // boxUvs goes through the core's textureCoordinates
});

// A unit square split into two counter-clockwise triangles, with a square hole-free boundary.
const square = Float64Array.from([0, 0, 1, 0, 1, 1, 0, 1]);
const squareTriangles = Uint32Array.from([0, 1, 2, 0, 2, 3]);

describe("picking", () => {
  it("finds the triangle and barycentric coordinates that reproduce the point", () => {
    for (const [x, y] of [
      [0.3, 0.1],
      [0.2, 0.7],
      [0.999, 0.5],
    ] as const) {
      const hit = locate(square, squareTriangles, x, y)!;
      expect(hit).toBeDefined();
      expect(hit.barycentric.reduce((a, b) => a + b)).toBeCloseTo(1, 14);
      hit.barycentric.forEach((w) => expect(w).toBeGreaterThanOrEqual(0));
      const [px, py] = pointPosition(square, squareTriangles, hit);
      expect(px).toBeCloseTo(x, 14);
      expect(py).toBeCloseTo(y, 14);
    }
    // (0.3, 0.1) is below the diagonal: triangle 0.
    expect(locate(square, squareTriangles, 0.3, 0.1)!.triangle).toBe(0);
    expect(locate(square, squareTriangles, 0.1, 0.3)!.triangle).toBe(1);
  });

  it("snaps to the closest boundary point within the tolerance, and only then", () => {
    expect(locate(square, squareTriangles, 1.05, 0.5)).toBeUndefined();
    const hit = locate(square, squareTriangles, 1.05, 0.5, 0.1)!;
    const [x, y] = pointPosition(square, squareTriangles, hit);
    expect(x).toBeCloseTo(1, 14);
    expect(y).toBeCloseTo(0.5, 14);
    expect(locate(square, squareTriangles, 1.2, 0.5, 0.1)).toBeUndefined();
  });

  it("nearest point within a radius", () => {
    const points = [0, 0, 1, 0, 0.5, 0.5];
    expect(nearestPoint(points, 0.9, 0.05, 0.2)).toBe(1);
    expect(nearestPoint(points, 0.45, 0.4, 0.2)).toBe(2);
    expect(nearestPoint(points, 3, 3, 0.2)).toBe(-1);
  });
});

describe("history", () => {
  it("undoes and redoes gestures in order and drops redo on a new gesture", () => {
    const h = new History<string>(3);
    h.push("a");
    h.push("b");
    expect(h.undo("c")).toBe("b");
    expect(h.undo("b")).toBe("a");
    expect(h.canUndo).toBe(false);
    expect(h.redo("a")).toBe("b");
    expect(h.redo("b")).toBe("c");
    expect(h.redo("c")).toBeUndefined();
    h.undo("c");
    h.push("x");
    expect(h.canRedo).toBe(false);
  });

  it("forgets the oldest gestures beyond its limit", () => {
    const h = new History<number>(2);
    [1, 2, 3].forEach((s) => h.push(s));
    expect(h.undo(4)).toBe(3);
    expect(h.undo(3)).toBe(2);
    expect(h.undo(2)).toBeUndefined();
  });
});

describe("geometry and exports", () => {
  it("lists each edge once and chains the boundary into loops", () => {
    const edges = uniqueEdges(squareTriangles, 4);
    expect(edges.length).toBe(2 * 5); // 4 sides and the diagonal
    const loops = boundaryLoops([0, 1, 1, 2, 2, 3, 3, 0, 5, 4, 4, 6, 6, 5]);
    expect(loops.map((l) => l.length).sort()).toEqual([3, 4]);
  });

  it("maps the bounding box to texture space keeping the aspect ratio", () => {
    const uvs = boxUvs([0, 0, 2, 0, 2, 1, 0, 1]);
    expect(Array.from(uvs)).toEqual([0, 0.25, 1, 0.25, 1, 0.75, 0, 0.75]);
  });

  it("maps a triangle's texture pixels onto its screen corners (the 2D renderer's affine map)", () => {
    // The unit triangle to one scaled by 2 and 3 at (10, 20): a = 2, d = 3, no shear.
    expect(
      affineThrough(
        [
          [0, 0],
          [1, 0],
          [0, 1],
        ],
        [
          [10, 20],
          [12, 20],
          [10, 23],
        ],
      ),
    ).toEqual([2, 0, 0, 3, 10, 20]);
    // A texture triangle with rows down (v up flips y) onto a rotated one: each corner lands.
    const from: [number, number][] = [
      [4, 8],
      [20, 8],
      [4, 2],
    ];
    const to: [number, number][] = [
      [100, 100],
      [100, 132],
      [88, 100],
    ];
    const [a, b, c, d, e, f] = affineThrough(from, to)!;
    from.forEach(([x, y], k) => {
      expect(a * x + c * y + e).toBeCloseTo(to[k]![0], 12);
      expect(b * x + d * y + f).toBeCloseTo(to[k]![1], 12);
    });
    // Texture points on a line have no area: no map.
    expect(
      affineThrough(
        [
          [0, 0],
          [1, 1],
          [2, 2],
        ],
        to,
      ),
    ).toBeUndefined();
  });
});

describe("keyboard shortcuts", () => {
  const press = (key: string, mods: Partial<Omit<KeyPress, "key">> = {}) =>
    keyCommand({ key, ctrlKey: false, metaKey: false, altKey: false, shiftKey: false, ...mods });
  it("maps keys to commands", () => {
    expect(press("z", { ctrlKey: true })).toEqual({ kind: "undo" });
    expect(press("Z", { metaKey: true, shiftKey: true })).toEqual({ kind: "redo" });
    expect(press("y", { ctrlKey: true })).toEqual({ kind: "redo" });
    expect(press("Delete")).toEqual({ kind: "delete" });
    expect(press("Backspace")).toEqual({ kind: "delete" });
    expect(press("ArrowUp")).toEqual({ kind: "nudge", dx: 0, dy: 1 });
    expect(press("ArrowLeft", { shiftKey: true })).toEqual({ kind: "nudge", dx: -10, dy: 0 });
    expect(press("w")).toEqual({ kind: "toggle", what: "wireframe" });
    expect(press("Escape")).toEqual({ kind: "deselect" });
    expect(press("v")).toEqual({ kind: "toggle", what: "field" });
    expect(press("f")).toEqual({ kind: "fit" });
    expect(press("?", { shiftKey: true })).toEqual({ kind: "help" });
    expect(press("+")).toEqual({ kind: "zoom", factor: 1.25 });
  });
  it("leaves keys typed into fields to the field, and Space and Enter to buttons", () => {
    const typed = (key: string, focus: "text" | "control") =>
      keyCommand({ key, ctrlKey: false, metaKey: false, altKey: false, shiftKey: false }, focus);
    for (const key of ["Backspace", "Delete", "ArrowUp", "End", "9", "w", "f"])
      expect(typed(key, "text")).toBe(undefined);
    expect(typed(" ", "control")).toBe(undefined);
    expect(typed("Enter", "control")).toBe(undefined);
    expect(typed("Delete", "control")).toEqual({ kind: "delete" });
  });
  it("leaves other keys and browser shortcuts alone", () => {
    expect(press("q")).toBeUndefined();
    expect(press("w", { ctrlKey: true })).toBeUndefined();
    expect(press("ArrowUp", { altKey: true })).toBeUndefined();
  });
});

describe("user files", () => {
  it("are recognised by extension or type", () => {
    expect(fileKind("Cat.SVG")).toBe("svg");
    expect(fileKind("drawing", "image/svg+xml")).toBe("svg");
    expect(fileKind("photo.jpeg")).toBe("image");
    expect(fileKind("scan", "image/webp")).toBe("image");
    expect(fileKind("model.obj")).toBe("obj");
    expect(fileKind("pose.json")).toBe("json");
    expect(fileKind("notes.txt", "text/plain")).toBeUndefined();
  });
});

describe("widget options", () => {
  it("refuses a misspelt option by name, listing the options, and takes every listed one", () => {
    let error: (Error & { code?: string }) | undefined;
    try {
      widgetSettings({ vertexes: 2000 } as never);
    } catch (e) {
      error = e as Error & { code?: string };
    }
    expect(error?.message).toBe(`unknown widget option \`vertexes\`; the options are ${WIDGET_OPTIONS.join(", ")}`);
    expect(error?.code).toBe("invalid-option");
    expect(WIDGET_OPTIONS).toContain("vertices");
    const all = Object.fromEntries(WIDGET_OPTIONS.map((name) => [name, undefined]));
    expect(widgetSettings(all).vertices).toBe(1500);
  });
});
