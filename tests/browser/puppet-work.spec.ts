/**
 * A puppet's work kept: a session of puppet posing (drags, a joint moved with the Joint
 * tool) saved, loaded into a fresh page and replayed to the recorded pose bit for bit; the
 * posed puppet restored after a reload with its parts' art in depth order; and an image of
 * two separate blobs opened as a puppet of two parts, posed at once.
 */
import { expect, test, type Page } from "@playwright/test";
import { idle, mapping, open, usePrepared } from "./helpers.js";
import { BLUE, GREEN, grid, loadPuppet, near, posedOnPart, screen, svgToShape } from "./puppet-fixture.js";

usePrepared();

/** The bits of the widget's positions, 16 hex digits per coordinate (exact, -0 included). */
const poseBits = (page: Page): Promise<string[]> =>
  page.evaluate(() =>
    Array.from(new BigUint64Array(Float64Array.from(window.akapDemo!.widget.positions()).buffer), (b) =>
      b.toString(16).padStart(16, "0"),
    ),
  );

const state = (page: Page) =>
  page.evaluate(() => {
    const w = window.akapDemo!.widget;
    return { parts: w.parts.map((p) => [p.name, p.depth]), joints: w.joints, handles: w.handleCount };
  });

/** Drags from `from` by (dx, dy) CSS pixels in steps, and waits for the pose to settle. */
async function drag(page: Page, from: [number, number], dx: number, dy: number): Promise<void> {
  await page.mouse.move(...from);
  await page.mouse.down();
  await page.mouse.move(from[0] + dx, from[1] + dy, { steps: 8 });
  await page.mouse.up();
  await idle(page);
}

const ARM = 2;

/**
 * Waits until the work the app keeps (saved a moment after the last change) has the pose
 * on screen, and a puppet's `depths`.
 */
async function savedPose(page: Page, depths: number[]): Promise<void> {
  const stored = () =>
    page.evaluate(
      () =>
        new Promise<string>((resolve) => {
          const request = indexedDB.open("akap");
          // Not made here: the app makes it (with its stores) when it first saves.
          request.onupgradeneeded = () => request.transaction!.abort();
          request.onerror = () => resolve("no database yet");
          request.onsuccess = () => {
            const db = request.result;
            if (!db.objectStoreNames.contains("work")) {
              db.close();
              resolve("no store yet");
              return;
            }
            const get = db.transaction("work").objectStore("work").get("akap-app");
            get.onsuccess = () => {
              const work = get.result as { positions?: Float64Array; depths?: number[] } | undefined;
              db.close();
              resolve(JSON.stringify([Array.from(work?.positions ?? []), work?.depths ?? []]));
            };
            get.onerror = () => {
              db.close();
              resolve("not read");
            };
          };
        }),
    );
  const now = await page.evaluate(() => Array.from(window.akapDemo!.widget.positions()));
  await expect.poll(stored).toBe(JSON.stringify([now, depths]));
}

test("a session of puppet posing (drag, joint moved, drag) saves, loads in a fresh page and replays to the same bits", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await loadPuppet(page);
  const svg = await svgToShape(page);
  const { toCss, unit } = await mapping(page);
  const joints = await page.evaluate(() => window.akapDemo!.widget.joints);
  const armTorso = joints.findIndex((j) => j.parts[0] === ARM && j.parts[1] === 0);
  expect(armTorso, "a joint holds the arm to the torso").toBeGreaterThanOrEqual(0);

  await page.getByRole("button", { name: "Record" }).click();
  // Pins on the torso; the hand dragged up.
  for (const [x, y] of [
    [80, 200],
    [80, 150],
  ] as const)
    await page.mouse.click(...toCss(...svg(x, y)));
  await drag(page, toCss(...svg(193, 120)), -10, -40);

  // The Joint tool: the arm/torso joint dragged (in the pose) to the shoulder.
  const shoulder = svg(137, 120);
  await page.locator("#app select[name=tool]").selectOption("joint");
  const from = toCss(...(await posedOnPart(page, ARM, joints[armTorso]!.point)));
  const to = toCss(...(await posedOnPart(page, ARM, shoulder)));
  await drag(page, from, to[0] - from[0], to[1] - from[1]);
  const moved = (await page.evaluate(() => window.akapDemo!.widget.joints))[armTorso]!;
  expect(moved.parts).toEqual([ARM, 0]);
  expect(Math.hypot(moved.point[0] - shoulder[0], moved.point[1] - shoulder[1])).toBeLessThan(2 * unit);

  // Posing again: the hand dragged further.
  await page.locator("#app select[name=tool]").selectOption("pose");
  const hand = await page.evaluate(() => Array.from(window.akapDemo!.widget.handlePositions().slice(4, 6)));
  await drag(page, toCss(hand[0]!, hand[1]!), -30, -30);
  await page.getByRole("button", { name: "Stop" }).click();
  const recorded = await poseBits(page);
  const recordedState = await state(page);
  expect(recordedState.joints[armTorso]).toEqual(moved);

  const download = page.waitForEvent("download");
  await page.getByRole("button", { name: "Save", exact: true }).click();
  const saved = await (await (await download).createReadStream()).toArray();
  const text = Buffer.concat(saved).toString("utf8");
  const session = JSON.parse(text) as {
    puppet: { parts: { name: string }[]; joints: unknown[] };
    events: Record<string, unknown>[];
  };
  // The header has the puppet as the recording started; the joint's move is an event.
  expect(session.puppet.parts.map((p) => p.name)).toEqual(["Torso", "Head", "Arm", "Hat"]);
  expect(session.puppet.joints).toEqual(joints);
  const jointEvents = session.events.filter((e) => "joints" in e);
  expect(jointEvents).toHaveLength(1);
  expect(jointEvents[0]!.joints).toEqual(recordedState.joints);

  // Replayed in place.
  await page.getByRole("button", { name: "Replay" }).click();
  await expect(page.locator(".akap-host >> .widget")).not.toHaveAttribute("data-replaying", "true");
  await idle(page);
  expect(await poseBits(page)).toEqual(recorded);

  // Loaded in a fresh page showing another shape: the puppet is rebuilt from the session.
  await open(page, "?hud=false&shape=gingerbread");
  expect(await page.evaluate(() => window.akapDemo!.widget.parts)).toEqual([]);
  await page
    .locator('input[name="session-file"]')
    .setInputFiles({ name: "puppet.json", mimeType: "application/json", buffer: Buffer.from(text) });
  await expect.poll(() => poseBits(page)).toEqual(recorded);
  expect(await state(page)).toEqual(recordedState);
});

test("a posed puppet comes back after a reload: its pose, joints and depths, each part's art in depth order", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await loadPuppet(page);
  const svg = await svgToShape(page);
  const { toCss } = await mapping(page);
  const shoulder = svg(137, 120);
  const joints = await page.evaluate(() => window.akapDemo!.widget.joints);
  const armTorso = joints.findIndex((j) => j.parts[0] === ARM && j.parts[1] === 0);
  joints[armTorso] = { point: shoulder, parts: [ARM, 0] };
  await page.evaluate((joints) => window.akapDemo!.widget.setJoints(joints), joints);

  // Pins on the torso, the hand swung a quarter turn up about the shoulder.
  for (const [x, y] of [
    [80, 200],
    [80, 150],
  ] as const)
    await page.mouse.click(...toCss(...svg(x, y)));
  const hand = svg(193, 120);
  const radius = Math.hypot(hand[0] - shoulder[0], hand[1] - shoulder[1]);
  const swing = (degrees: number): [number, number] => {
    const a = (degrees * Math.PI) / 180;
    return toCss(shoulder[0] + radius * Math.cos(a), shoulder[1] + radius * Math.sin(a));
  };
  await page.mouse.move(...swing(0));
  await page.mouse.down();
  for (let degrees = 5; degrees <= 90; degrees += 5) await page.mouse.move(...swing(degrees), { steps: 3 });
  await page.mouse.up();
  await idle(page);

  // The arm's points along it near the shoulder (SVG 141..152 x 116..122) lie over the
  // torso now (SVG 133..139 x 105..116); the torso's square the arm hid at rest (SVG 120..130 x 110..130) is bare.
  const armPoints: [number, number][] = [];
  for (const a of [4, 8, 12, 15]) for (const b of [-4, -1, 2]) armPoints.push(svg(137 + a, 120 + b));
  const look = async () => {
    const read = await screen(page);
    const over = await read(await Promise.all(armPoints.map(async (p) => toCss(...(await posedOnPart(page, ARM, p))))));
    const bare = await read(grid(toCss, svg, [120, 110, 130, 130], 2.5, 6));
    return {
      arm: over.filter((c) => near(c, BLUE)).length,
      torsoUnderArm: over.filter((c) => near(c, GREEN)).length,
      bare: bare.filter((c) => near(c, GREEN)).length / bare.length,
    };
  };
  const before = await look();
  expect(before.arm, "the arm draws over the torso").toBe(armPoints.length);
  expect(before.bare, "the torso's own art shows where the arm was").toBeGreaterThan(0.5);

  // The arm sent behind the torso (the hand's handle, selected by its drag): the torso's green over it.
  await page.getByRole("button", { name: "Back" }).click();
  await page.getByRole("button", { name: "Back" }).click();
  const depths = Object.fromEntries((await state(page)).parts as [string, number][]);
  expect(depths.Arm!).toBeLessThan(depths.Torso!);
  const behind = await look();
  expect(behind.torsoUnderArm, "the torso draws over the arm").toBe(armPoints.length);

  const posed = { bits: await poseBits(page), state: await state(page) };
  await savedPose(
    page,
    posed.state.parts.map((p) => p[1] as number),
  );
  await page.reload();
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  await idle(page);
  expect(await poseBits(page)).toEqual(posed.bits);
  expect(await state(page)).toEqual(posed.state);
  const after = await look();
  expect(after.torsoUnderArm, "after the reload, the torso still draws over the arm").toBe(armPoints.length);
  expect(after.bare, "after the reload, the torso's art shows where the arm was").toBeGreaterThan(0.5);

  await page.screenshot({ path: "test-results/puppet-reloaded.png" });
});

test("an image of two separate blobs opens as a puppet of two parts; dragging one leaves the other in place", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page, "?hud=false&shape=gingerbread");
  // 200 x 100 pixels: a red disc about (50, 50) of radius 30 and a blue square 120..180 x
  // 20..80 (pixels, y down), transparent elsewhere.
  await page.evaluate(async () => {
    const canvas = document.createElement("canvas");
    canvas.width = 200;
    canvas.height = 100;
    const ctx = canvas.getContext("2d")!;
    ctx.fillStyle = "#ff0000";
    ctx.beginPath();
    ctx.arc(50, 50, 30, 0, 2 * Math.PI);
    ctx.fill();
    ctx.fillStyle = "#0000ff";
    ctx.fillRect(120, 20, 60, 60);
    const blob = await new Promise<Blob>((resolve) => canvas.toBlob((b) => resolve(b!), "image/png"));
    await window.akapDemo!.widget.loadFile(blob, "blobs.png");
  });
  await idle(page);
  const parts = await page.evaluate(() => {
    const w = window.akapDemo!.widget;
    const p = w.mesh.positions;
    const t = w.mesh.triangles;
    return w.parts.map((part) => {
      let area = 0;
      const vertices = new Set<number>();
      for (const f of part.triangles) {
        const [a, b, c] = [t[3 * f]!, t[3 * f + 1]!, t[3 * f + 2]!];
        area +=
          ((p[2 * b]! - p[2 * a]!) * (p[2 * c + 1]! - p[2 * a + 1]!) -
            (p[2 * c]! - p[2 * a]!) * (p[2 * b + 1]! - p[2 * a + 1]!)) /
          2;
        [a, b, c].forEach((v) => vertices.add(v));
      }
      return { area, vertices: [...vertices], depth: part.depth };
    });
  });
  // Two parts, the square (3600 pixels) and the disc (900 pi, about 2827), to 3%.
  expect(parts).toHaveLength(2);
  const [square, disc] = [...parts].sort((a, b) => b.area - a.area);
  expect(Math.abs(square!.area - 3600) / 3600).toBeLessThan(0.03);
  expect(Math.abs(disc!.area - 900 * Math.PI) / (900 * Math.PI)).toBeLessThan(0.03);
  // The Part list (one part at a time) is not offered.
  await expect(page.locator("#app select[name=part]").locator("xpath=..")).toBeHidden();

  // The square's centre (150, 50 in pixels, y up) dragged 40 CSS pixels right and 30 down.
  const { toCss } = await mapping(page);
  const rest = await page.evaluate(() => Array.from(window.akapDemo!.widget.positions()));
  await drag(page, toCss(150, 50), 40, 30);
  const posed = await page.evaluate(() => Array.from(window.akapDemo!.widget.positions()));
  const at = (list: number[], v: number) => [list[2 * v]!, list[2 * v + 1]!];
  // The disc did not move at all; the square moved with the drag (as one piece).
  for (const v of disc!.vertices) expect(at(posed, v)).toEqual(at(rest, v));
  const shift = await page.evaluate(() => Array.from(window.akapDemo!.widget.handlePositions()));
  const [dx, dy] = [shift[0]! - 150, shift[1]! - 50];
  const { unit } = await mapping(page);
  expect(Math.hypot(dx - 40 * unit, dy + 30 * unit)).toBeLessThan(3 * unit);
  for (const v of square!.vertices) {
    const [x, y] = at(posed, v);
    const [x0, y0] = at(rest, v);
    expect(Math.hypot(x! - x0! - dx, y! - y0! - dy)).toBeLessThan(0.02 * 60);
  }
  // Drawn from the image: blue where the square went, red on the disc.
  const read = await screen(page);
  const [blue, red] = await read([toCss(150 + dx + 20, 50 + dy + 20), toCss(50, 50)]);
  expect(near(blue!, [0, 0, 255]), `square ${blue}`).toBe(true);
  expect(near(red!, [255, 0, 0]), `disc ${red}`).toBe(true);

  // Kept with the work: after a reload, the same two parts in the same pose, drawn from the image.
  await savedPose(
    page,
    [0, 0].map((_, k) => parts[k]!.depth),
  );
  await page.goto("/?hud=false");
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  await idle(page);
  expect(await page.evaluate(() => Array.from(window.akapDemo!.widget.positions()))).toEqual(posed);
  expect(await page.evaluate(() => window.akapDemo!.widget.parts.length)).toBe(2);
  const again = await screen(page);
  const [blue2, red2] = await again([toCss(150 + dx + 20, 50 + dy + 20), toCss(50, 50)]);
  expect(near(blue2!, [0, 0, 255]), `square ${blue2}`).toBe(true);
  expect(near(red2!, [255, 0, 0]), `disc ${red2}`).toBe(true);
  // Re-meshed from the kept image: still two parts.
  await page.evaluate(() => window.akapDemo!.widget.remesh(600));
  await idle(page);
  expect(await page.evaluate(() => window.akapDemo!.widget.parts.length)).toBe(2);
});
