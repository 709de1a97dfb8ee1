/**
 * Texture coordinates in the browser, end to end, on an image whose every pixel the test
 * knows: a block of four coloured quadrants in a clear margin. The convention is
 * Wavefront OBJ's (u from the left, v up from the bottom row), so the pixel under a vertex
 * with texture coordinates (u, v) is column u * width, row (1 - v) * height from the top.
 */
import { expect, test, type Page } from "@playwright/test";
import { init, meshToObj, textureCoordinates, traceImage, triangulate } from "../../www/src/index.js";
import { open, usePrepared } from "./helpers.js";

usePrepared();

const [W, H, MARGIN] = [80, 60, 6];
/** Quadrants of the block as the image shows them: top left, top right, bottom left, bottom right. */
const COLOURS = [
  [230, 30, 30],
  [30, 200, 30],
  [30, 30, 230],
  [240, 220, 20],
] as const;

/** The colour of pixel (column, row), rows from the top, or undefined in the clear margin. */
function pixel(column: number, row: number): readonly number[] | undefined {
  if (column < MARGIN || column >= W - MARGIN || row < MARGIN || row >= H - MARGIN) return undefined;
  return COLOURS[(row < H / 2 ? 0 : 2) + (column < W / 2 ? 0 : 1)];
}

/** The image's RGBA pixels, rows from the top (as ImageData). */
function rgba(): Uint8ClampedArray {
  const data = new Uint8ClampedArray(W * H * 4);
  for (let row = 0; row < H; row++) {
    for (let column = 0; column < W; column++) {
      const c = pixel(column, row);
      if (c) data.set([...c, 255], 4 * (row * W + column));
    }
  }
  return data;
}

/** The quadrant colour a point of the traced frame (pixels, y up) lies in, away from seams and edges. */
function colourAt(x: number, y: number): readonly number[] | undefined {
  const away = 2;
  if (Math.abs(x - W / 2) < away || Math.abs(y - H / 2) < away) return undefined;
  if (x < MARGIN + away || x > W - MARGIN - away || y < MARGIN + away || y > H - MARGIN - away) return undefined;
  return pixel(Math.floor(x), Math.floor(H - y));
}

/** The image as PNG bytes, encoded by the page's canvas. */
async function png(page: Page): Promise<Buffer> {
  const url = await page.evaluate(
    ({ data, width, height }) => {
      const canvas = document.createElement("canvas");
      canvas.width = width;
      canvas.height = height;
      canvas.getContext("2d")!.putImageData(new ImageData(Uint8ClampedArray.from(data), width, height), 0, 0);
      return canvas.toDataURL("image/png");
    },
    { data: Array.from(rgba()), width: W, height: H },
  );
  return Buffer.from(url.slice(url.indexOf(",") + 1), "base64");
}

/** `v` and `vt` lines of an OBJ text, as [x, y] and [u, v] pairs. */
function objVertices(text: string): { positions: [number, number][]; uvs: [number, number][] } {
  const pairs = (tag: string) =>
    text
      .split("\n")
      .filter((line) => line.startsWith(`${tag} `))
      .map((line) => line.split(/\s+/).slice(1, 3).map(Number) as [number, number]);
  return { positions: pairs("v"), uvs: pairs("vt") };
}

/** The colour the widget in `host` (the app's `#app`, or an element) draws at shape point (x, y). */
async function drawnAt(page: Page, host: string, x: number, y: number): Promise<number[]> {
  return page.evaluate(
    ({ host, x, y }) => {
      const element = document.querySelector(host)!;
      const gl = element.querySelector(".akap-host")!.shadowRoot!.querySelector("canvas.mesh") as HTMLCanvasElement;
      type Viewed = { view: { scale: number; offsetX: number; offsetY: number } };
      const view = (host === "#app" ? window.akapDemo!.widget : (element as unknown as { widget: Viewed }).widget).view;
      const screen = document.createElement("canvas");
      screen.width = gl.width;
      screen.height = gl.height;
      const ctx = screen.getContext("2d")!;
      ctx.drawImage(gl, 0, 0);
      const [px, py] = [Math.round(view.offsetX + view.scale * x), Math.round(view.offsetY - view.scale * y)];
      const d = ctx.getImageData(px, py, 1, 1).data;
      return [d[0]!, d[1]!, d[2]!];
    },
    { host, x, y },
  );
}

/** Largest channel difference. */
const near = (c: readonly number[], want: readonly number[]) => Math.max(...c.map((v, i) => Math.abs(v - want[i]!)));

/** The middles of the quadrants in the traced frame (pixels, y up), in the order of COLOURS. */
function quadrantMiddles(): [number, number][] {
  const [qx, qy] = [(W - 2 * MARGIN) / 4, (H - 2 * MARGIN) / 4];
  return [
    [MARGIN + qx, H - MARGIN - qy],
    [W - MARGIN - qx, H - MARGIN - qy],
    [MARGIN + qx, MARGIN + qy],
    [W - MARGIN - qx, MARGIN + qy],
  ];
}

/** The vertex nearest each quadrant's middle. */
function quadrantVertices(positions: [number, number][]): [number, number][] {
  const gap = (p: [number, number], c: [number, number]) => Math.hypot(p[0] - c[0], p[1] - c[1]);
  return quadrantMiddles().map((c) => positions.reduce((a, b) => (gap(b, c) < gap(a, c) ? b : a)));
}

/** Makes the page's canvases refuse WebGL2, as browsers without it do: the widget falls back to 2D. */
async function withoutWebGl2(page: Page): Promise<void> {
  await page.addInitScript(() => {
    const getContext = HTMLCanvasElement.prototype.getContext;
    HTMLCanvasElement.prototype.getContext = function (this: HTMLCanvasElement, type: string, options?: unknown) {
      return type === "webgl2" ? null : getContext.call(this, type, options);
    } as typeof getContext;
  });
}

test.beforeAll(async () => {
  await init(); // the library in Node, to compute what the README tells users to
});

for (const renderer of ["webgl2", "2d"] as const) {
  test(`an imported image is drawn unmirrored (${renderer}), and its OBJ's vt find each vertex's pixel`, async ({
    page,
  }) => {
    if (renderer === "2d") await withoutWebGl2(page);
    await page.setViewportSize({ width: 900, height: 700 });
    await open(page);
    expect(await page.evaluate(() => window.akapDemo!.widget.renderer)).toBe(renderer);
    await page.locator('input[name="shape-file"]').setInputFiles({
      name: "quadrants.png",
      mimeType: "image/png",
      buffer: await png(page),
    });
    await expect(page.getByRole("combobox", { name: "Shape" }).locator("option:checked")).toHaveText("quadrants.png");
    await page.evaluate(() => window.akapDemo!.widget.whenIdle());

    const download = page.waitForEvent("download");
    await page.getByRole("button", { name: "OBJ", exact: true }).click();
    const fs = await import("node:fs/promises");
    const { positions, uvs } = objVertices(await fs.readFile((await (await download).path())!, "utf8"));
    expect(uvs.length).toBe(positions.length);

    // Each vertex inside a quadrant samples that quadrant's colour through its vt.
    let checked = 0;
    positions.forEach(([x, y], i) => {
      const want = colourAt(x, y);
      if (!want) return;
      const [u, v] = uvs[i]!;
      expect(pixel(Math.floor(u * W), Math.floor((1 - v) * H)), `vertex ${i} at (${x}, ${y}), vt ${u} ${v}`).toEqual(
        want,
      );
      checked++;
    });
    expect(checked).toBeGreaterThan(100);

    // The vt are what the library's textureCoordinates gives, as the README has users do.
    const expected = textureCoordinates(positions.flat(), W, H);
    uvs.forEach(([u, v], i) => {
      expect(Math.abs(u - expected[2 * i]!) + Math.abs(v - expected[2 * i + 1]!), `vertex ${i}`).toBeLessThan(1e-6);
    });

    // On screen, each quadrant's middle shows its own colour (a mirrored texture swaps rows).
    for (const [k, at] of quadrantVertices(positions).entries()) {
      expect(near(await drawnAt(page, "#app", ...at), COLOURS[k]!), `at (${at[0]}, ${at[1]})`).toBeLessThan(16);
    }
  });
}

test("an OBJ with v-up vt (the README's textureCoordinates, or another tool's) shows the image unmirrored", async ({
  page,
}) => {
  // The README's path, in Node: trace, mesh, textureCoordinates, meshToObj.
  const outline = traceImage(rgba(), W, H)[0]!;
  const mesh = triangulate(outline, { targetEdgeLength: 3 });
  const readme = meshToObj({ ...mesh, uvs: textureCoordinates(mesh.positions, W, H) });
  // Another tool's: the block as a quad of two triangles, vt worked out by hand (v up).
  const [x0, y0, x1, y1] = [MARGIN, MARGIN, W - MARGIN, H - MARGIN];
  const byHand = [
    ...[`v ${x0} ${y0} 0`, `v ${x1} ${y0} 0`, `v ${x1} ${y1} 0`, `v ${x0} ${y1} 0`],
    ...[`vt ${x0 / W} ${y0 / H}`, `vt ${x1 / W} ${y0 / H}`, `vt ${x1 / W} ${y1 / H}`, `vt ${x0 / W} ${y1 / H}`],
    "f 1/1 2/2 3/3",
    "f 1/1 3/3 4/4",
  ].join("\n");

  await page.setViewportSize({ width: 1000, height: 700 });
  await page.goto("/www/examples/embed.html");
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  const image = await png(page);
  for (const [name, obj] of [
    ["readme.obj", readme],
    ["by-hand.obj", byHand],
  ] as const) {
    await page.route(`**/uv-test/${name}`, (route) => route.fulfill({ body: obj, contentType: "text/plain" }));
  }
  await page.route("**/uv-test/quadrants.png", (route) => route.fulfill({ body: image, contentType: "image/png" }));

  for (const name of ["readme.obj", "by-hand.obj"]) {
    const host = `#${name.replace(".obj", "")}`;
    await page.evaluate(
      async ({ name, id }) => {
        const element = document.createElement("akap-deformer");
        element.id = id;
        element.style.cssText = "display: block; height: 360px";
        for (const [key, value] of Object.entries({ src: `/uv-test/${name}`, texture: "/uv-test/quadrants.png" })) {
          element.setAttribute(key, value);
        }
        element.setAttribute("hud", "false");
        element.setAttribute("controls", "false");
        document.body.prepend(element);
        const widget = await (element as unknown as { ready: Promise<{ whenIdle(): Promise<void> }> }).ready;
        await widget.whenIdle();
      },
      { name, id: host.slice(1) },
    );
    // Vertices of the traced mesh; the quad has only its corners, so the quadrants' middles.
    const points = name === "readme.obj" ? quadrantVertices(objVertices(readme).positions) : quadrantMiddles();
    for (const [k, at] of points.entries()) {
      expect(near(await drawnAt(page, host, ...at), COLOURS[k]!), `${name} at (${at[0]}, ${at[1]})`).toBeLessThan(16);
    }
    await page.evaluate((id) => document.getElementById(id)!.remove(), host.slice(1));
  }
});
