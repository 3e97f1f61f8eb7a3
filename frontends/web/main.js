// Loads voxtrace_web.wasm (a plain module: exported functions over linear
// memory), renders into the canvas, and orbits the camera on drag.
// URL parameters set up a fixed render (used by the end-to-end test):
// ?seed=3&size=24&backend=octree&pos=40,50,30&w=96&h=64

const params = new URLSearchParams(location.search);
const canvas = document.getElementById("frame");
const status = document.getElementById("status");
const inputs = {
  seed: document.getElementById("seed"),
  size: document.getElementById("size"),
  backend: document.getElementById("backend"),
};
if (params.has("seed")) inputs.seed.value = params.get("seed");
if (params.has("size")) inputs.size.value = params.get("size");
if (params.has("backend")) inputs.backend.value = params.get("backend") === "dense" ? "0" : "1";
if (params.has("w")) canvas.width = Number(params.get("w"));
if (params.has("h")) canvas.height = Number(params.get("h"));

// Orbit: yaw and pitch around the origin, at a distance set by the size.
const orbit = { yaw: Math.PI / 4, pitch: 0.55, fixed: null };
if (params.has("pos")) orbit.fixed = params.get("pos").split(",").map(Number);

const { instance } = await WebAssembly.instantiateStreaming(fetch("voxtrace_web.wasm"));
const vt = instance.exports;
const ctx = canvas.getContext("2d");
const ERRORS = ["", "bad seed, size or backend", "cannot build the scene",
                "bad camera", "cannot render"];

function eye() {
  if (orbit.fixed) return orbit.fixed;
  const size = Number(inputs.size.value);
  const r = 2.4 * size + 40;
  return [
    r * Math.cos(orbit.pitch) * Math.cos(orbit.yaw),
    r * Math.sin(orbit.pitch),
    r * Math.cos(orbit.pitch) * Math.sin(orbit.yaw),
  ];
}

function draw() {
  const seed = BigInt.asUintN(64, BigInt(inputs.seed.value || "0"));
  const [x, y, z] = eye();
  const started = performance.now();
  const code = vt.vt_render(
    Number(seed & 0xffffffffn), Number(seed >> 32n),
    Number(inputs.size.value), Number(inputs.backend.value),
    x, y, z, canvas.width, canvas.height);
  const ms = performance.now() - started;
  if (code !== 0) {
    status.textContent = `error: ${ERRORS[code] ?? code}`;
    return;
  }
  const bytes = new Uint8ClampedArray(
    vt.memory.buffer, vt.vt_frame_ptr(), vt.vt_frame_len() * 4);
  ctx.putImageData(new ImageData(bytes.slice(), canvas.width, canvas.height), 0, 0);
  status.textContent = `${ms.toFixed(1)} ms (build included when the scene changed)`;
  document.body.dataset.rendered = String(Number(document.body.dataset.rendered ?? 0) + 1);
}

let pending = false;
function request() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => { pending = false; draw(); });
}

let drag = null;
canvas.addEventListener("pointerdown", (e) => {
  drag = { x: e.clientX, y: e.clientY };
  orbit.fixed = null;
  canvas.setPointerCapture(e.pointerId);
});
canvas.addEventListener("pointermove", (e) => {
  if (!drag) return;
  orbit.yaw += (e.clientX - drag.x) * 0.01;
  orbit.pitch = Math.min(1.5, Math.max(-0.2, orbit.pitch + (e.clientY - drag.y) * 0.01));
  drag = { x: e.clientX, y: e.clientY };
  request();
});
canvas.addEventListener("pointerup", () => { drag = null; });
for (const input of Object.values(inputs)) input.addEventListener("change", request);

draw();
