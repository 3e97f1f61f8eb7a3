// End to end in headless Chromium: serve the page, render fixed scenes in
// WebAssembly, read the canvas pixels back, and require them to equal the
// desktop binary's render of the same scene byte for byte. Saves a
// screenshot of the page to target/web-e2e.png.
//
// Needs: the wasm module (cargo build --release -p voxtrace-web --target
// wasm32-unknown-unknown), the CLI (cargo build --release -p voxtrace-cli),
// Chromium at $CHROMIUM or /usr/bin/chromium, and `npm ci` here.

import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";
import { serve } from "../serve.mjs";

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, "../../..");
const cli = process.env.VOXTRACE_BIN ?? path.join(root, "target/release/voxtrace");
const scratch = mkdtempSync(path.join(tmpdir(), "voxtrace-e2e-"));

/// The desktop render as RGB bytes, through the CLI's PPM output.
function native({ seed, size, backend, pos, w, h }) {
  const out = path.join(scratch, `${backend}.ppm`);
  execFileSync(cli, ["--seed", seed, "--size", size, "--backend", backend,
    "--position", pos, "--width", w, "--height", h, "--threads", "1", "--out", out]);
  const bytes = readFileSync(out);
  // Binary PPM: "P6\n<w> <h>\n255\n" then RGB.
  const header = bytes.subarray(0, 40).toString("latin1").match(/^P6\s+(\d+)\s+(\d+)\s+255\s/);
  if (!header || Number(header[1]) !== Number(w) || Number(header[2]) !== Number(h)) {
    throw new Error(`unexpected PPM header in ${out}`);
  }
  return bytes.subarray(header[0].length);
}

const server = await serve(0);
const port = server.address().port;
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
let failures = 0;
try {
  const page = await browser.newPage();
  for (const scene of [
    { seed: "3", size: "24", backend: "octree", pos: "40,50,30", w: "96", h: "64" },
    { seed: "3", size: "24", backend: "dense", pos: "40,50,30", w: "96", h: "64" },
    { seed: "11", size: "40", backend: "octree", pos: "-35,60,52", w: "120", h: "80" },
  ]) {
    const query = new URLSearchParams(scene).toString();
    await page.goto(`http://127.0.0.1:${port}/?${query}`);
    await page.waitForFunction(() => document.body.dataset.rendered === "1");
    const rgba = await page.evaluate(() => {
      const c = document.getElementById("frame");
      return Array.from(c.getContext("2d").getImageData(0, 0, c.width, c.height).data);
    });
    const rgb = native(scene);
    let differing = 0;
    for (let i = 0, j = 0; j < rgb.length; i += 4, j += 3) {
      const same = rgba[i] === rgb[j] && rgba[i + 1] === rgb[j + 1] &&
        rgba[i + 2] === rgb[j + 2] && rgba[i + 3] === 255;
      if (!same) differing++;
    }
    const pixels = rgb.length / 3;
    if (rgba.length !== pixels * 4 || differing > 0) {
      failures++;
      console.log(`FAIL ${query}: ${differing} of ${pixels} pixels differ from the desktop`);
    } else {
      console.log(`ok   ${query}: ${pixels} pixels equal the desktop render`);
    }
  }
  // A screenshot of the page as a user sees it (default scene).
  await page.setViewportSize({ width: 720, height: 560 });
  await page.goto(`http://127.0.0.1:${port}/`);
  await page.waitForFunction(() => document.body.dataset.rendered === "1");
  await page.screenshot({ path: path.join(root, "target/web-e2e.png") });
  console.log(`page status after the default render: ${await page.textContent("#status")}`);
  // Dragging the canvas orbits the camera: a new render with new pixels.
  const grab = () => page.evaluate(() => document.getElementById("frame").toDataURL());
  const before = await grab();
  const box = await page.locator("#frame").boundingBox();
  await page.mouse.move(box.x + 200, box.y + 150);
  await page.mouse.down();
  await page.mouse.move(box.x + 320, box.y + 170, { steps: 4 });
  await page.mouse.up();
  await page.waitForFunction(() => Number(document.body.dataset.rendered) > 1);
  if ((await grab()) === before) {
    failures++;
    console.log("FAIL dragging did not change the view");
  } else {
    console.log("ok   dragging the canvas orbits the camera");
  }
} finally {
  await browser.close();
  server.close();
  rmSync(scratch, { recursive: true, force: true });
}
process.exit(failures === 0 ? 0 : 1);
