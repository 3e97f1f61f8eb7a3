// End to end in headless Chromium: serve the page, render in WebAssembly,
// read the canvas pixels back, and require them to equal the desktop
// binary's render of the same scene, camera and effects byte for byte:
// terrain from fixed positions on both backends; docs/terrain.vox loaded
// through the file picker and through a dropped file (and three models of
// ../shared/scenes/vox when that folder is there); each effect toggled;
// the top and iso views; a zoom by the mouse wheel (against the command the
// page prints for its camera); an orbit by dragging. Saves a screenshot of
// the page to web-e2e.png in cargo's target folder.
//
// Needs: the wasm module (cargo build --release -p voxtrace-web --target
// wasm32-unknown-unknown), the CLI (cargo build --release -p voxtrace-cli;
// $VOXTRACE_BIN, else the release binary under $CARGO_TARGET_DIR or
// target/), Chromium at $CHROMIUM or /usr/bin/chromium, and `npm ci` here.

import { execFileSync } from "node:child_process";
import { existsSync, mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";
import { serve } from "../serve.mjs";

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, "../../..");
const targetDir = process.env.CARGO_TARGET_DIR
  ? path.resolve(process.env.CARGO_TARGET_DIR)
  : path.join(root, "target");
const cli = process.env.VOXTRACE_BIN ?? path.join(targetDir, "release/voxtrace");
const sample = path.join(root, "docs/terrain.vox");
const scratch = mkdtempSync(path.join(tmpdir(), "voxtrace-e2e-"));

/// The desktop render for the CLI flags `args`, as RGB bytes (PPM output).
function native(args, w, h) {
  const out = path.join(scratch, "native.ppm");
  execFileSync(cli, [...args, "--width", String(w), "--height", String(h),
    "--threads", "1", "--out", out], { stdio: ["ignore", "ignore", "pipe"] });
  const bytes = readFileSync(out);
  // Binary PPM: "P6\n<w> <h>\n255\n" then RGB.
  const header = bytes.subarray(0, 40).toString("latin1").match(/^P6\s+(\d+)\s+(\d+)\s+255\s/);
  if (!header || Number(header[1]) !== w || Number(header[2]) !== h) {
    throw new Error(`unexpected PPM header in ${out}`);
  }
  return bytes.subarray(header[0].length);
}

/// The flags of the command the page shows, with the model's path for its
/// file name, without the size and output (native adds its own).
function pageFlags(command) {
  const words = command.split(" ").slice(1);
  const out = [];
  for (let i = 0; i < words.length; i++) {
    if (["--width", "--height", "--out"].includes(words[i])) { i++; continue; }
    out.push(words[i]);
    if (words[i] === "--vox") { out.push(sample); i++; }
  }
  return out;
}

const server = await serve(0);
const port = server.address().port;
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
let failures = 0;
const fail = (what) => { failures++; console.log(`FAIL ${what}`); };
const W = 96;
const H = 64;
try {
  const page = await browser.newPage();
  const canvas = () => page.evaluate(() => {
    const c = document.getElementById("frame");
    return Array.from(c.getContext("2d").getImageData(0, 0, c.width, c.height).data);
  });
  const rendered = () => page.evaluate(() => Number(document.body.dataset.rendered ?? 0));
  // Runs `action`, then waits until the page has drawn after it and has
  // nothing more scheduled.
  const after = async (action) => {
    const before = await rendered();
    await action();
    await page.waitForFunction((n) => Number(document.body.dataset.rendered ?? 0) > n &&
      document.body.dataset.pending !== "1", before);
  };
  // The canvas against the desktop render of `args` (or of the page's own
  // command when `args` is null).
  const compare = async (what, args) => {
    const rgba = await canvas();
    const command = await page.textContent("#command");
    const w = await page.evaluate(() => document.getElementById("frame").width);
    const h = await page.evaluate(() => document.getElementById("frame").height);
    const rgb = native(args ?? pageFlags(command), w, h);
    let differing = 0;
    for (let i = 0, j = 0; j < rgb.length; i += 4, j += 3) {
      const same = rgba[i] === rgb[j] && rgba[i + 1] === rgb[j + 1] &&
        rgba[i + 2] === rgb[j + 2] && rgba[i + 3] === 255;
      if (!same) differing++;
    }
    const pixels = rgb.length / 3;
    if (rgba.length !== pixels * 4 || differing > 0) {
      fail(`${what}: ${differing} of ${pixels} pixels differ from the desktop (${command})`);
    } else {
      console.log(`ok   ${what}: ${pixels} pixels equal voxtrace ${(args ?? pageFlags(command)).join(" ")}`);
    }
    return rgba;
  };

  for (const scene of [
    { seed: "3", size: "24", backend: "octree", pos: "40,50,30" },
    { seed: "3", size: "24", backend: "dense", pos: "40,50,30" },
    { seed: "11", size: "40", backend: "octree", pos: "-35,60,52" },
  ]) {
    const query = new URLSearchParams({ ...scene, w: W, h: H }).toString();
    await page.goto(`http://127.0.0.1:${port}/?${query}`);
    await page.waitForFunction(() => document.body.dataset.rendered === "1");
    await compare(`terrain ${query}`, ["--seed", scene.seed, "--size", scene.size,
      "--backend", scene.backend, "--position", scene.pos]);
  }

  // A .vox model through the file picker opens on the CLI's default view
  // (no camera flag: the measured side that shows the most of it).
  // The page shows a model as a quick draft (the CLI's default for one
  // is a render with shadows and occlusion).
  const model = ["--vox", sample, "--quality", "draft"];
  await page.goto(`http://127.0.0.1:${port}/?w=${W}&h=${H}`);
  await page.waitForFunction(() => document.body.dataset.rendered === "1");
  await after(() => page.setInputFiles("#file", sample));
  const picked = await compare("docs/terrain.vox from the file picker", model);

  // Models by other authors, when the shared folder is there: materials,
  // emitters and a file's own sun and sky (path-traced on both sides).
  const shared = path.resolve(root, "../shared/scenes/vox");
  const others = ["chr_riotcop.vox", "H1-COLORED.vox", "study.vox"]
    .map((name) => path.join(shared, name)).filter((file) => existsSync(file));
  if (others.length === 0) console.log(`skipped the shared models: ${shared} is absent`);
  for (const file of others) {
    await after(() => page.setInputFiles("#file", file));
    await compare(`${path.basename(file)} from the file picker`, ["--vox", file, "--quality", "draft"]);
  }
  if (others.length > 0) {
    await after(() => page.setInputFiles("#file", sample));
    await compare("docs/terrain.vox again", model);
  }

  // The same file dropped on the page, after the terrain is back.
  await after(() => page.fill("#seed", "5").then(() => page.dispatchEvent("#seed", "change")));
  if ((await canvas()).every((v, i) => v === picked[i])) fail("the seed did not bring the terrain back");
  const bytes = Array.from(readFileSync(sample));
  await after(() => page.evaluate((bytes) => {
    const data = new DataTransfer();
    data.items.add(new File([new Uint8Array(bytes)], "terrain.vox"));
    const canvas = document.getElementById("frame");
    canvas.dispatchEvent(new DragEvent("dragover", { dataTransfer: data, bubbles: true, cancelable: true }));
    canvas.dispatchEvent(new DragEvent("drop", { dataTransfer: data, bubbles: true, cancelable: true }));
  }, bytes));
  await compare("docs/terrain.vox dropped on the canvas", model);

  // The iso and top views, framed as the CLI frames --view.
  for (const view of ["iso", "top"]) {
    await after(() => page.selectOption("#view", view));
    await compare(`the ${view} view`, [...model, "--view", view]);
  }

  // Each effect alone, on and off again, still from the top: there the
  // model's sun is the paper's, whose shadows show (from over the camera's
  // shoulder, as the default view lights it, the height field hides its
  // own shadows).
  const top = [...model, "--view", "top"];
  for (const [id, flags] of [["shadows", ["--shadows"]], ["ao", ["--ao", "8"]], ["fog", ["--fog"]]]) {
    await after(() => page.check(`#${id}`));
    const on = await compare(`the ${id} toggle`, [...top, ...flags]);
    await after(() => page.uncheck(`#${id}`));
    const off = await compare(`the ${id} toggle off`, top);
    if (on.every((v, i) => v === off[i])) fail(`the ${id} toggle changed no pixel`);
  }

  // The wheel zooms in: the camera the page prints is the CLI's camera for
  // the same picture, and it is closer (orthographic: shows less). Still
  // the top view.
  const framed = await page.textContent("#command");
  const box = await page.locator("#frame").boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await after(() => page.mouse.wheel(0, -100));
  await after(() => page.mouse.wheel(0, -100));
  const zoomed = await page.textContent("#command");
  const height = (c) => Number(c.match(/--position \S+,(\S+),\S+ --lookat \S+,(\S+),/).slice(1, 3)
    .reduce((a, b) => a - b));
  if (!(height(zoomed) < 0.7 * height(framed))) {
    fail(`two wheel steps did not move the camera in: ${framed} -> ${zoomed}`);
  }
  await compare("the top view zoomed by the wheel", null);

  // Dragging orbits: a new render, and still the desktop's pixels.
  const before = await canvas();
  await after(async () => {
    await page.mouse.move(box.x + 40, box.y + 30);
    await page.mouse.down();
    await page.mouse.move(box.x + 70, box.y + 40, { steps: 3 });
    await page.mouse.up();
  });
  const dragged = await compare("the orbit after a drag", null);
  if (dragged.every((v, i) => v === before[i])) fail("dragging did not change the view");
  if ((await page.inputValue("#view")) !== "orbit") fail("dragging did not switch to the orbit");

  // A screenshot of the page as a user sees it (default scene).
  await page.setViewportSize({ width: 720, height: 640 });
  await page.goto(`http://127.0.0.1:${port}/`);
  await page.waitForFunction(() => document.body.dataset.rendered === "1");
  await page.screenshot({ path: path.join(targetDir, "web-e2e.png") });
  console.log(`page status after the default render: ${await page.textContent("#status")}`);
} finally {
  await browser.close();
  server.close();
  rmSync(scratch, { recursive: true, force: true });
}
process.exit(failures === 0 ? 0 : 1);
