// A tiny static server for the page: index.html and main.js from this
// folder, voxtrace_web.wasm from cargo's target folder ($CARGO_TARGET_DIR
// when set, as cargo itself resolves it: relative to the current folder;
// else target/ at the repository's root).
// `node frontends/web/serve.mjs [port]`, then open http://localhost:8080/.

import { createServer } from "node:http";
import { readFile } from "node:fs/promises";
import { fileURLToPath } from "node:url";
import path from "node:path";

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, "../..");
const targetDir = process.env.CARGO_TARGET_DIR
  ? path.resolve(process.env.CARGO_TARGET_DIR)
  : path.join(root, "target");
const files = {
  "/": [path.join(here, "index.html"), "text/html"],
  "/index.html": [path.join(here, "index.html"), "text/html"],
  "/main.js": [path.join(here, "main.js"), "text/javascript"],
  "/voxtrace_web.wasm": [
    path.join(targetDir, "wasm32-unknown-unknown/release/voxtrace_web.wasm"),
    "application/wasm",
  ],
};

export function serve(port = 8080) {
  const server = createServer(async (req, res) => {
    const entry = files[new URL(req.url, "http://localhost").pathname];
    if (!entry) {
      res.writeHead(404).end("not found");
      return;
    }
    try {
      const body = await readFile(entry[0]);
      res.writeHead(200, { "content-type": entry[1] }).end(body);
    } catch (e) {
      // A file that is not there is a 404, and for the module says how to
      // make it; anything else is the server's own failure.
      const missing = e.code === "ENOENT";
      const hint = missing && entry[1] === "application/wasm"
        ? " (not built yet: rustup target add wasm32-unknown-unknown, then" +
          " cargo build --release -p voxtrace-web --target wasm32-unknown-unknown;" +
          " set CARGO_TARGET_DIR if cargo builds elsewhere)"
        : "";
      res.writeHead(missing ? 404 : 500).end(`${entry[0]}: ${e.message}${hint}`);
    }
  });
  return new Promise((resolve) => server.listen(port, "127.0.0.1", () => resolve(server)));
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const port = Number(process.argv[2] ?? 8080);
  await serve(port);
  console.log(`voxtrace page: http://localhost:${port}/`);
}
