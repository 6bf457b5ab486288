#!/usr/bin/env python3
"""The web build's tests (docs/web.md#tests), in headless Chromium driven through the DevTools
protocol with Python's standard library only (no npm packages, no pip packages).

Serves web/dist/ (scripts/build-web.sh) on 127.0.0.1 and, once on WebGL2 and once on WebGPU
(both through SwiftShader, Chromium's CPU renderer), checks that:
- the page starts, draws the built-in scene and sets its ready marker on <body>;
- the 3D view equals `bumpview render` of the same state (the default preset at the view's size)
  within the tolerance below, and so does a page whose address carries a preset
  (`#preset=[shading] view = "tangent"`) against `bumpview render --view tangent`;
  a page whose address carries a lesson (`#lesson=over-tilt`) opens with its state, and the
  slide deck's page (`bumpview slides --html`, served as written) opens it from its slide's link
  with the same picture;
- pressing B (bump off) changes the picture, a drag in the view changes it, and a .glb dropped on
  the page is opened and changes it;
- no error reached the console.
Prints the wasm's size (raw and gzip) and each backend's time to first frame, and closes with
"web: N passed, N failed". Fails when Chromium is missing and CI=true; elsewhere says so and
stops with exit code 0.

Usage: scripts/test-web.py [--keep DIR]  (DIR: where to leave the screenshots; default a
temporary folder, removed). Env: BUMPVIEW_BIN (default target/debug/bumpview), CHROMIUM
(default chromium).
"""

import base64
import gzip
import http.server
import json
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse
import urllib.request
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DIST = os.path.join(ROOT, "web", "dist")
GLB = os.path.join(ROOT, "tests", "fixtures", "gltf", "BoxTextured", "glTF-Binary", "BoxTextured.glb")

# Tolerance of the 3D view against `bumpview render` on lavapipe, in 8-bit steps of the sRGB
# values: mean over all channels of all pixels, and the largest single step. SwiftShader and
# lavapipe are different rasterisers: the 4x MSAA samples' coverage of an edge pixel differs, so
# a pixel on an edge can differ by up to the contrast across the edge (measured at 990x657 on
# WebGL2 and WebGPU: 102 in the lit view, 127 in the tangent view) while the mean stays small
# (measured: 0.17 lit, 0.32 tangent).
MEAN_TOLERANCE = 1.0
MAX_TOLERANCE = 192
# A change (B, a drag, a dropped model) must move the mean by at least this many steps.
CHANGED_MEAN = 1.0
# Budgets (docs/web.md): first frame in headless Chromium on this machine, wasm size gzipped.
FIRST_FRAME_BUDGET_MS = 3000.0
WASM_GZIP_BUDGET = 10 * 1024 * 1024
READY_TIMEOUT_S = 120.0

BACKENDS = {
    "webgl": ["--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
    "webgpu": [
        "--enable-unsafe-webgpu",
        "--use-webgpu-adapter=swiftshader",
        "--enable-features=Vulkan",
        "--use-vulkan=swiftshader",
        "--use-angle=vulkan",
        "--enable-unsafe-swiftshader",
    ],
}


# --- PNG (8-bit RGB or RGBA, not interlaced: what Chromium and bumpview write) ---------------

def png_pixels(data):
    """(width, height, rows of RGB bytes) of a PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and colour in (2, 6) and interlace == 0, f"unsupported PNG {header}"
    channels = 3 if colour == 2 else 4
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up, up_left = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else up_left)) & 255
        previous = line
        rows.append(bytes(line) if channels == 3 else bytes(b for i, b in enumerate(line) if i % 4 != 3))
    return width, height, rows


def difference(a, b):
    """(mean, max) step between two same-size RGB pictures."""
    assert a[:2] == b[:2], f"sizes differ: {a[:2]} and {b[:2]}"
    total, largest, count = 0, 0, 0
    for row_a, row_b in zip(a[2], b[2]):
        for x, y in zip(row_a, row_b):
            d = abs(x - y)
            total += d
            largest = max(largest, d)
        count += len(row_a)
    return total / count, largest


# --- the DevTools protocol over a minimal WebSocket client (RFC 6455) ------------------------

class DevTools:
    def __init__(self, ws_url):
        host_port, path = ws_url[len("ws://"):].split("/", 1)
        host, port = host_port.split(":")
        self.sock = socket.create_connection((host, int(port)), timeout=READY_TIMEOUT_S)
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall(
            f"GET /{path} HTTP/1.1\r\nHost: {host_port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
            f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n".encode())
        response = b""
        while b"\r\n\r\n" not in response:
            response += self.sock.recv(1)
        assert b" 101 " in response.split(b"\r\n")[0], response
        self.next_id, self.events = 0, []

    def _recv_exact(self, n):
        out = b""
        while len(out) < n:
            chunk = self.sock.recv(n - len(out))
            if not chunk:
                raise ConnectionError("DevTools closed the connection")
            out += chunk
        return out

    def _recv_message(self):
        message = b""
        while True:
            first, second = self._recv_exact(2)
            length = second & 127
            if length == 126:
                (length,) = struct.unpack(">H", self._recv_exact(2))
            elif length == 127:
                (length,) = struct.unpack(">Q", self._recv_exact(8))
            message += self._recv_exact(length)
            if first & 0x80:
                return json.loads(message)

    def send(self, method, **params):
        self.next_id += 1
        payload = json.dumps({"id": self.next_id, "method": method, "params": params}).encode()
        mask = os.urandom(4)
        header = bytes([0x81])
        if len(payload) < 126:
            header += bytes([0x80 | len(payload)])
        elif len(payload) < 65536:
            header += bytes([0x80 | 126]) + struct.pack(">H", len(payload))
        else:
            header += bytes([0x80 | 127]) + struct.pack(">Q", len(payload))
        self.sock.sendall(header + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(payload)))
        while True:
            message = self._recv_message()
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message.get("result", {})
            self.events.append(message)

    def evaluate(self, expression):
        result = self.send("Runtime.evaluate", expression=expression, awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in result:
            raise RuntimeError(f"{expression}: {result['exceptionDetails']}")
        return result["result"].get("value")

    def errors(self):
        """Console errors and uncaught exceptions so far."""
        found = []
        for event in self.events:
            method, params = event.get("method"), event.get("params", {})
            if method == "Runtime.consoleAPICalled" and params.get("type") == "error":
                found.append(" ".join(str(a.get("value", a.get("description", ""))) for a in params.get("args", [])))
            elif method == "Runtime.exceptionThrown":
                found.append(params["exceptionDetails"].get("exception", {}).get("description", "exception"))
            elif method == "Log.entryAdded" and params["entry"].get("level") == "error":
                found.append(params["entry"].get("text", ""))
        return found


# --- the page ------------------------------------------------------------------------------

def serve(deck):
    """A static server of web/dist/, the test's .glb and the folder `deck` under /deck/ on
    127.0.0.1; returns its port."""
    class Handler(http.server.SimpleHTTPRequestHandler):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, directory=DIST, **kwargs)

        def translate_path(self, path):
            if path.startswith("/test-model.glb"):
                return GLB
            if path.startswith("/deck/"):
                relative = urllib.parse.unquote(path.split("?", 1)[0].split("#", 1)[0])[len("/deck/"):]
                return os.path.join(deck, *[part for part in relative.split("/") if part not in ("", "..")])
            return super().translate_path(path)

        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server.server_address[1]


def launch(chromium, backend, profile):
    """Chromium headless on about:blank with the backend's flags; returns (process, page's WebSocket URL)."""
    args = [chromium, "--headless", "--no-sandbox", "--disable-quic", "--no-first-run",
            "--disable-background-networking", "--disable-component-update", "--disable-sync",
            f"--user-data-dir={profile}", "--remote-debugging-port=0", "--remote-debugging-address=127.0.0.1",
            "--window-size=1280,800", "--force-device-scale-factor=1", *BACKENDS[backend], "about:blank"]
    process = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 60
    port = None
    while port is None and time.time() < deadline:
        line = process.stderr.readline()
        if not line:
            raise RuntimeError(f"chromium exited ({process.poll()}) before its DevTools port")
        if line.startswith("DevTools listening on ws://"):
            port = int(line.split("ws://", 1)[1].split("/", 1)[0].rsplit(":", 1)[1])
    threading.Thread(target=lambda: process.stderr.read(), daemon=True).start()
    for _ in range(100):
        targets = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list"))
        pages = [t for t in targets if t.get("type") == "page"]
        if pages:
            return process, pages[0]["webSocketDebuggerUrl"]
        time.sleep(0.1)
    raise RuntimeError("chromium has no page")


def wait_ready(page):
    deadline = time.time() + READY_TIMEOUT_S
    while time.time() < deadline:
        data = page.evaluate("document.body ? JSON.stringify(document.body.dataset) : null")
        data = json.loads(data) if data else {}
        if "failed" in data:
            raise RuntimeError(f"the page failed: {data['failed']}")
        if "ready" in data:
            return data
        time.sleep(0.25)
    raise RuntimeError(f"no ready marker within {READY_TIMEOUT_S:.0f} s")


def view_shot(page, view, path):
    """The 3D view's pixels (PNG written to `path`), after two animation frames."""
    page.evaluate("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")
    x, y, w, h = view
    shot = page.send("Page.captureScreenshot", format="png",
                     clip={"x": x, "y": y, "width": w, "height": h, "scale": 1})
    data = base64.b64decode(shot["data"])
    with open(path, "wb") as f:
        f.write(data)
    return png_pixels(data)


def settle(page, seconds=1.5):
    """Lets the viewer finish what an input started (a scene job, a full-quality frame)."""
    end = time.time() + seconds
    while time.time() < end:
        page.evaluate("new Promise(r => setTimeout(r, 100))")


class Results:
    def __init__(self):
        self.passed, self.failed = 0, 0

    def check(self, name, ok, detail):
        print(f"{'ok  ' if ok else 'FAIL'} {name}: {detail}", flush=True)
        if ok:
            self.passed += 1
        else:
            self.failed += 1


def equals_native(results, name, picture, out, flags):
    """Checks `picture` against `bumpview render` of its size with `flags`."""
    w, h = picture[:2]
    native_png = os.path.join(out, f"native-{w}x{h}{''.join(flags)}.png")
    if not os.path.exists(native_png):
        binary = os.environ.get("BUMPVIEW_BIN", os.path.join(ROOT, "target", "debug", "bumpview"))
        subprocess.run([binary, "render", "--size", f"{w}x{h}", *flags, "--out", native_png], check=True,
                       stdout=subprocess.DEVNULL)
    with open(native_png, "rb") as f:
        native = png_pixels(f.read())
    mean, largest = difference(picture, native)
    command = " ".join(["bumpview render --size", f"{w}x{h}", *flags])
    results.check(f"{name} equals `{command}`", mean <= MEAN_TOLERANCE and largest <= MAX_TOLERANCE,
                  f"mean {mean:.3f} steps (tolerance {MEAN_TOLERANCE}), max {largest} (tolerance {MAX_TOLERANCE})")


def changed(results, page, name, mean):
    """A picture changed by an input: by CHANGED_MEAN at least, and not by a failure (a panic
    blanks the page, which changes it too)."""
    errors = page.errors()
    results.check(name, mean >= CHANGED_MEAN and not errors,
                  f"mean change {mean:.3f} steps" + (f", after {len(errors)} console errors" if errors else ""))


def run_backend(chromium, backend, port, out, results):
    profile = tempfile.mkdtemp(prefix="bumpview-chromium-")
    process, ws_url = launch(chromium, backend, profile)
    try:
        page = DevTools(ws_url)
        for domain in ("Runtime.enable", "Log.enable", "Page.enable"):
            page.send(domain)
        page.send("Page.navigate", url=f"http://127.0.0.1:{port}/#backend={backend}")
        try:
            data = wait_ready(page)
        except RuntimeError as e:
            results.check(f"{backend}: the page gets ready", False, f"{e}; console: {page.errors()}")
            return
        first_frame_ms = float(data["ready"])
        results.check(f"{backend}: the page gets ready", data.get("backend") == backend,
                      f"backend {data.get('backend')}, first frame {first_frame_ms:.0f} ms after navigation "
                      f"(budget {FIRST_FRAME_BUDGET_MS:.0f} ms: "
                      f"{'within' if first_frame_ms <= FIRST_FRAME_BUDGET_MS else 'OVER'})")
        view = [round(float(v)) for v in data["view"].split(",")]
        x, y, w, h = view
        built_in = view_shot(page, view, os.path.join(out, f"{backend}-built-in.png"))

        equals_native(results, f"{backend}: the view", built_in, out, [])

        page.send("Input.dispatchMouseEvent", type="mousePressed", x=x + w / 2, y=y + h / 2, button="left",
                  clickCount=1)
        page.send("Input.dispatchMouseEvent", type="mouseReleased", x=x + w / 2, y=y + h / 2, button="left",
                  clickCount=1)
        for kind in ("keyDown", "keyUp"):
            page.send("Input.dispatchKeyEvent", type=kind, key="b", code="KeyB", text="b" if kind == "keyDown" else "",
                      windowsVirtualKeyCode=66)
        settle(page)
        bump_off = view_shot(page, view, os.path.join(out, f"{backend}-bump-off.png"))
        mean, _ = difference(built_in, bump_off)
        changed(results, page, f"{backend}: B turns bump mapping off", mean)

        steps = 10
        for i in range(steps + 1):
            kind = "mousePressed" if i == 0 else "mouseMoved"
            page.send("Input.dispatchMouseEvent", type=kind, x=x + w / 2 + 20 * i, y=y + h / 2, button="left",
                      buttons=1, clickCount=1 if i == 0 else 0)
        page.send("Input.dispatchMouseEvent", type="mouseReleased", x=x + w / 2 + 20 * steps, y=y + h / 2,
                  button="left", clickCount=1)
        settle(page)
        dragged = view_shot(page, view, os.path.join(out, f"{backend}-dragged.png"))
        mean, _ = difference(bump_off, dragged)
        changed(results, page, f"{backend}: a drag turns the camera", mean)

        page.evaluate(f"""(async () => {{
            const bytes = await (await fetch('/test-model.glb')).arrayBuffer();
            const transfer = new DataTransfer();
            transfer.items.add(new File([bytes], 'BoxTextured.glb', {{ type: 'model/gltf-binary' }}));
            const canvas = document.getElementById('bumpview');
            for (const type of ['dragenter', 'dragover', 'drop']) {{
                canvas.dispatchEvent(new DragEvent(type, {{ dataTransfer: transfer, bubbles: true, cancelable: true,
                    clientX: {x + w / 2}, clientY: {y + h / 2} }}));
            }}
        }})()""")
        settle(page, 3.0)
        dropped = view_shot(page, view, os.path.join(out, f"{backend}-dropped-glb.png"))
        mean, _ = difference(dragged, dropped)
        changed(results, page, f"{backend}: a dropped .glb is opened", mean)

        errors = page.errors()
        results.check(f"{backend}: no console error", not errors, f"{len(errors)} errors {errors[:3]}")

        preset = urllib.parse.quote('[shading]\nview = "tangent"\n')
        page.send("Page.navigate", url="about:blank")
        page.evaluate("new Promise(r => setTimeout(r, 200))")
        page.send("Page.navigate", url=f"http://127.0.0.1:{port}/#backend={backend}&preset={preset}")
        data = wait_ready(page)
        tangent = view_shot(page, [round(float(v)) for v in data["view"].split(",")],
                            os.path.join(out, f"{backend}-preset-tangent.png"))
        equals_native(results, f"{backend}: a preset in the address", tangent, out, ["--view", "tangent"])

        # A lesson in the address opens with its whole state: over-tilt's close, strong wall.
        page.send("Page.navigate", url="about:blank")
        page.evaluate("new Promise(r => setTimeout(r, 200))")
        page.send("Page.navigate", url=f"http://127.0.0.1:{port}/#backend={backend}&lesson=over-tilt")
        data = wait_ready(page)
        lesson_view = [round(float(v)) for v in data["view"].split(",")]
        lesson = view_shot(page, lesson_view, os.path.join(out, f"{backend}-lesson.png"))
        mean = difference(built_in, lesson)[0] if lesson[:2] == built_in[:2] else float("inf")
        changed(results, page, f"{backend}: a lesson in the address", mean)

        # The deck's page links the slide to the same lesson, live in the web build beside it.
        page.send("Page.navigate", url=f"http://127.0.0.1:{port}/deck/index.html")
        page.evaluate("new Promise(r => setTimeout(r, 500))")
        href = page.evaluate("document.querySelector('figure a').href")
        page.send("Page.navigate", url=f"{href}&backend={backend}")
        data = wait_ready(page)
        linked = view_shot(page, [round(float(v)) for v in data["view"].split(",")],
                           os.path.join(out, f"{backend}-deck-link.png"))
        mean, largest = difference(lesson, linked) if linked[:2] == lesson[:2] else (float("inf"), 255)
        results.check(f"{backend}: the deck's slide opens its lesson live ({href.split('/deck/', 1)[-1]})",
                      mean <= MEAN_TOLERANCE, f"mean {mean:.3f} steps from the lesson's own address, max {largest}")
    finally:
        process.terminate()
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            process.kill()
        shutil.rmtree(profile, ignore_errors=True)


def main():
    keep = sys.argv[sys.argv.index("--keep") + 1] if "--keep" in sys.argv else None
    chromium = shutil.which(os.environ.get("CHROMIUM", "chromium"))
    if chromium is None:
        if os.environ.get("CI") == "true":
            print("web: chromium is missing (install Debian's chromium); 0 passed, 1 failed")
            return 1
        print("web: chromium is missing: the web tests did not run (install Debian's chromium)")
        return 0
    wasm = os.path.join(DIST, "bumpview_bg.wasm")
    if not os.path.exists(wasm):
        print("web: no web/dist/ (run scripts/build-web.sh first)\n0 passed, 1 failed")
        return 1
    raw = os.path.getsize(wasm)
    with open(wasm, "rb") as f:
        packed = len(gzip.compress(f.read(), 9))
    results = Results()
    results.check("wasm size", packed <= WASM_GZIP_BUDGET,
                  f"{raw} bytes raw ({raw / 2**20:.1f} MiB), {packed} gzip -9 ({packed / 2**20:.1f} MiB; "
                  f"budget {WASM_GZIP_BUDGET / 2**20:.0f} MiB)")
    out = keep or tempfile.mkdtemp(prefix="bumpview-web-")
    os.makedirs(out, exist_ok=True)
    binary = os.environ.get("BUMPVIEW_BIN", os.path.join(ROOT, "target", "debug", "bumpview"))
    deck = os.path.join(out, "deck")
    subprocess.run([binary, "slides", "--force", "--size", "480x270", "--lessons", "over-tilt", "--html",
                    "--web-build", DIST, "--out", deck], check=True, stdout=subprocess.DEVNULL)
    port = serve(deck)
    try:
        for backend in BACKENDS:
            try:
                run_backend(chromium, backend, port, out, results)
            except Exception as e:  # one backend's failure must not hide the other's results
                results.check(f"{backend}: ran", False, repr(e))
    finally:
        if keep is None:
            shutil.rmtree(out, ignore_errors=True)
    print(f"web: {results.passed} passed, {results.failed} failed")
    return 0 if results.failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
