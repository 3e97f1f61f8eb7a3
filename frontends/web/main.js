// Loads voxtrace_web.wasm (a plain module: exported functions over linear
// memory, see src/lib.rs), renders into the canvas, and shows the voxtrace
// command that renders the same image on the desktop. Cameras, framing and
// effects are computed in the module by the core's types; this file only
// keeps the page's state: what to show, the view, the zoom, the toggles.
// URL parameters set up a render (the end-to-end test uses them):
// ?seed=3&size=24&backend=octree&pos=40,50,30&w=96&h=64
// (pos: a camera position looking at the scene's target, the origin for
// the terrain, instead of the orbit).

const params = new URLSearchParams(location.search);
const $ = (id) => document.getElementById(id);
const canvas = $("frame");
const status = $("status");
const inputs = {
  seed: $("seed"), size: $("size"), backend: $("backend"), view: $("view"),
  shadows: $("shadows"), ao: $("ao"), fog: $("fog"),
};
if (params.has("seed")) inputs.seed.value = params.get("seed");
if (params.has("size")) inputs.size.value = params.get("size");
if (params.has("backend")) inputs.backend.value = params.get("backend") === "dense" ? "0" : "1";
if (params.has("w")) canvas.width = Number(params.get("w"));
if (params.has("h")) canvas.height = Number(params.get("h"));

// The module's view codes: 1 an orbit, then the core's ViewPreset::ALL;
// 9 is the CLI's default view (a model's measured open side).
const VIEWS = ["orbit", "front", "back", "left", "right", "top", "bottom", "iso"];
const DEFAULT_VIEW = 9;
// The ambient-occlusion toggle is the CLI's --ao with this many rays.
const AO_RAYS = 8;
// Orbit angles in degrees (the CLI's --orbit YAW,PITCH), a fixed position
// when the URL gives one, the wheel's zoom in steps of 1.25 times, and
// whether the view is the CLI's default (a model just loaded).
const camera = { yaw: 45, pitch: 30, fixed: null, zoomSteps: 0, measured: false };
if (params.has("pos")) camera.fixed = params.get("pos").split(",").map(Number);
// The model on show (its file name for the command), or null: the terrain.
let model = null;

const { instance } = await WebAssembly.instantiateStreaming(fetch("voxtrace_web.wasm"));
const vt = instance.exports;
const ctx = canvas.getContext("2d");
const ERRORS = ["", "bad seed, size, backend or view", "cannot build the scene",
                "bad camera", "cannot render", "not a .vox file voxtrace can read"];

function message() {
  return new TextDecoder().decode(
    new Uint8Array(vt.memory.buffer, vt.vt_message_ptr(), vt.vt_message_len()));
}

// A word as a POSIX shell reads it back.
const quote = (s) => /^[\w.\/,+-]+$/.test(s) ? s : `'${s.replaceAll("'", "'\\''")}'`;

function draw() {
  const zoom = Math.pow(1.25, camera.zoomSteps);
  const view = camera.fixed ? 0
    : camera.measured ? DEFAULT_VIEW : VIEWS.indexOf(inputs.view.value) + 1;
  const [a, b, c] = camera.fixed ?? [camera.yaw, camera.pitch, 0];
  const effects = (inputs.shadows.checked ? 1 : 0) | (inputs.fog.checked ? 2 : 0);
  const ao = inputs.ao.checked ? AO_RAYS : 0;
  const started = performance.now();
  let code = 0;
  if (!model) {
    const seed = BigInt.asUintN(64, BigInt(inputs.seed.value || "0"));
    code = vt.vt_terrain(Number(seed & 0xffffffffn), Number(seed >> 32n), Number(inputs.size.value));
  }
  if (code === 0) {
    code = vt.vt_render(Number(inputs.backend.value), view, a, b, c, zoom, effects, ao,
      canvas.width, canvas.height);
  }
  const ms = performance.now() - started;
  if (code !== 0) {
    status.textContent = `error: ${ERRORS[code] ?? code}: ${message()}`;
    return;
  }
  const bytes = new Uint8ClampedArray(
    vt.memory.buffer, vt.vt_frame_ptr(), vt.vt_frame_len() * 4);
  ctx.putImageData(new ImageData(bytes.slice(), canvas.width, canvas.height), 0, 0);
  status.textContent = `${ms.toFixed(1)} ms (build included when the scene changed)`;
  const scene = model
    ? ["--vox", quote(model), "--quality", "draft"]
    : ["--seed", inputs.seed.value, "--size", inputs.size.value];
  $("command").textContent = ["voxtrace", ...scene,
    "--backend", inputs.backend.value === "0" ? "dense" : "octree",
    "--width", canvas.width, "--height", canvas.height, message(),
    ...(inputs.shadows.checked ? ["--shadows"] : []),
    ...(ao ? ["--ao", AO_RAYS] : []),
    ...(inputs.fog.checked ? ["--fog"] : []),
    "--out", "render.png"].join(" ");
  document.body.dataset.rendered = String(Number(document.body.dataset.rendered ?? 0) + 1);
}

let pending = false;
function request() {
  if (pending) return;
  pending = true;
  document.body.dataset.pending = "1";
  requestAnimationFrame(() => {
    pending = false;
    draw();
    delete document.body.dataset.pending;
  });
}

// A .vox file from the picker or a drop: copied into the module's memory
// and parsed there; shown from the CLI's default model view (measured by
// the module: the side that shows the most of it).
async function load(file) {
  const bytes = new Uint8Array(await file.arrayBuffer());
  const ptr = vt.vt_upload(bytes.length);
  if (!ptr) {
    status.textContent = `error: ${file.name} does not fit in memory`;
    return;
  }
  new Uint8Array(vt.memory.buffer, ptr, bytes.length).set(bytes);
  if (vt.vt_load_vox() !== 0) {
    status.textContent = `error: ${file.name}: ${message()}`;
    return;
  }
  model = file.name;
  Object.assign(camera, { fixed: null, zoomSteps: 0, measured: true });
  inputs.view.value = "orbit";
  request();
}

$("file").addEventListener("change", (e) => {
  if (e.target.files.length) load(e.target.files[0]);
});
document.addEventListener("dragover", (e) => {
  e.preventDefault();
  document.body.classList.add("dropping");
});
document.addEventListener("dragleave", () => document.body.classList.remove("dropping"));
document.addEventListener("drop", (e) => {
  e.preventDefault();
  document.body.classList.remove("dropping");
  const file = e.dataTransfer?.files?.[0];
  if (file) load(file);
});

let drag = null;
canvas.addEventListener("pointerdown", (e) => {
  drag = { x: e.clientX, y: e.clientY };
  canvas.setPointerCapture(e.pointerId);
});
canvas.addEventListener("pointermove", (e) => {
  if (!drag) return;
  if (camera.measured) {
    // Orbit on from the default view's measured angles.
    camera.yaw = vt.vt_orbit_yaw();
    camera.pitch = vt.vt_orbit_pitch();
    camera.measured = false;
  }
  camera.fixed = null;
  inputs.view.value = "orbit";
  camera.yaw -= (e.clientX - drag.x) * 0.5;
  camera.pitch = Math.min(89, Math.max(-89, camera.pitch + (e.clientY - drag.y) * 0.5));
  drag = { x: e.clientX, y: e.clientY };
  request();
});
canvas.addEventListener("pointerup", () => { drag = null; });
canvas.addEventListener("wheel", (e) => {
  e.preventDefault();
  camera.zoomSteps = Math.min(16, Math.max(-8, camera.zoomSteps - Math.sign(e.deltaY)));
  request();
}, { passive: false });
// A new seed or size brings the terrain back. (A browser fires "change" on
// blur too, after a file was loaded meanwhile: only a new value counts.)
const terrainKey = () => `${inputs.seed.value},${inputs.size.value}`;
let lastTerrain = terrainKey();
for (const id of ["seed", "size"]) {
  inputs[id].addEventListener("change", () => {
    if (terrainKey() === lastTerrain) return;
    lastTerrain = terrainKey();
    model = null;
    camera.measured = false;
    request();
  });
}
inputs.view.addEventListener("change", () => {
  camera.fixed = null;
  camera.measured = false;
  request();
});
for (const id of ["backend", "shadows", "ao", "fog"]) inputs[id].addEventListener("change", request);

draw();
