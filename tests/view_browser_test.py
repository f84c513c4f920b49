#!/usr/bin/python3
"""`quiver view` end to end, in headless Chromium driven by Selenium:

  - the server starts and prints its URL; the page loads, fetches the scene
    and refines the first view to its final frame on a 160x120 canvas;
  - the canvas holds, byte for byte, the PNG that the view's "Copy command"
    command writes (the command names the view, the size, aa and threads);
  - a left-drag orbits: the camera moves, coarse frames follow, and the new
    final frame differs from the first and again equals its command's PNG
    (and /api/png's image);
  - a request without the token gets 403, a bad parameter 400 with a message;
  - SIGINT ends the server with exit code 130 within 5 s.
Timings (view change to coarse, full and final frame drawn, measured in the
page) are printed, not checked.

Usage: /usr/bin/python3 tests/view_browser_test.py --quiver QUIVER [--scene SCENE] --workdir DIR
(exit 0 pass, 1 fail, 77 skipped saying why: no chromium, chromedriver or selenium).
"""
import argparse
import base64
import json
import math
import os
import re
import shlex
import signal
import struct
import subprocess
import sys
import threading
import time
import traceback
import urllib.error
import urllib.parse
import urllib.request
import zlib

SKIP = 77
CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
WIDTH, HEIGHT = 160, 120
VIEW_FLAGS = ["--width", str(WIDTH), "--height", str(HEIGHT), "--aa", "grid:2", "--threads", "2"]
URL_TIMEOUT = 60     # s: the scene is read and its BVH built before the URL line
FRAME_TIMEOUT = 120  # s: a view's whole chain, coarse to final
STOP_TIMEOUT = 5     # s: SIGINT to exit


class Failure(Exception):
    pass


def fail(message):
    raise Failure(message)


def load_selenium():
    """The Selenium names used here, or exit 77 saying what is missing."""
    for path in (CHROMIUM, CHROMEDRIVER):
        if not os.access(path, os.X_OK):
            print(f"SKIP: {path} is missing (apt-get install chromium chromium-driver)")
            sys.exit(SKIP)
    try:
        from selenium import webdriver
        from selenium.common.exceptions import TimeoutException
        from selenium.webdriver.chrome.service import Service
        from selenium.webdriver.common.action_chains import ActionChains
        from selenium.webdriver.common.by import By
        from selenium.webdriver.support.ui import WebDriverWait
    except ImportError as error:
        print(f"SKIP: no selenium for {sys.executable} ({error}; apt-get install python3-selenium)")
        sys.exit(SKIP)
    return argparse.Namespace(webdriver=webdriver, Service=Service, ActionChains=ActionChains, By=By,
                              WebDriverWait=WebDriverWait, TimeoutException=TimeoutException)


# ---- the server --------------------------------------------------------------

class Server:
    """`quiver view` as a subprocess; its stderr is read by a thread (kept for failure messages).
    The URL is the first http://...?token=<32 hex digits> on stderr, on a line of its own or not."""

    def __init__(self, quiver, scene, workdir):
        self.command = [quiver, "view", *([scene] if scene else []), *VIEW_FLAGS]
        self.stderr_lines = []
        self.url_found = threading.Event()
        self.url = None
        self.stdout = open(os.path.join(workdir, "view.stdout"), "w")
        self.process = subprocess.Popen(self.command, cwd=workdir, stdin=subprocess.DEVNULL, stdout=self.stdout,
                                        stderr=subprocess.PIPE, text=True)
        threading.Thread(target=self._read_stderr, daemon=True).start()

    def _read_stderr(self):
        for line in self.process.stderr:
            self.stderr_lines.append(line.rstrip("\n"))
            match = re.search(r"(http://\S+[?&]token=[0-9a-f]{32})\b", line)
            if match and not self.url:
                self.url = match.group(1)
                self.url_found.set()
        self.url_found.set()  # end of stderr: the process ended

    def stderr_tail(self, lines=10):
        return "\n".join("    " + line for line in self.stderr_lines[-lines:]) or "    (nothing)"

    def wait_for_url(self):
        if not self.url_found.wait(URL_TIMEOUT) or not self.url:
            code = self.process.poll()
            state = "still running" if code is None else f"exited with {code}"
            fail(f"no http://...?token=... URL on stderr within {URL_TIMEOUT} s ({state}): {shlex.join(self.command)}")
        return self.url

    def stop_with_sigint(self):
        self.process.send_signal(signal.SIGINT)
        start = time.monotonic()
        try:
            code = self.process.wait(STOP_TIMEOUT)
        except subprocess.TimeoutExpired:
            fail(f"the server was still running {STOP_TIMEOUT} s after SIGINT")
        print(f"SIGINT: exit {code} after {time.monotonic() - start:.2f} s")
        if code != 130:
            fail(f"the server exited with {code} after SIGINT, not 130\n  stderr:\n{self.stderr_tail()}")

    def kill(self):
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()
        self.stdout.close()


def http_get(url):
    """(status, body bytes, headers) of a GET, HTTP errors included."""
    try:
        with urllib.request.urlopen(url, timeout=60) as response:
            return response.status, response.read(), response.headers
    except urllib.error.HTTPError as error:
        return error.code, error.read(), error.headers


# ---- PNG ---------------------------------------------------------------------

def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def decode_png(data, name):
    """(width, height, RGB bytes) of an 8-bit RGB (or opaque RGBA) non-interlaced PNG."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(f"{name}: not a PNG")
    header, idat, pos = None, [], 8
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if zlib.crc32(kind + body) != struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])[0]:
            fail(f"{name}: bad CRC in chunk {kind!r}")
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
        elif not kind[0] & 0x20:
            fail(f"{name}: critical chunk {kind!r} is not supported by this decoder")
    if header is None:
        fail(f"{name}: no IHDR")
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace != 0:
        fail(f"{name}: bit depth {depth}, colour type {colour}, interlace {interlace}; "
             "expected 8-bit RGB, not interlaced")
    channels = 3 if colour == 2 else 4
    stride = width * channels
    raw = zlib.decompress(b"".join(idat))
    if len(raw) != height * (stride + 1):
        fail(f"{name}: {len(raw)} bytes of filtered rows, expected {height * (stride + 1)}")
    pixels, previous = bytearray(), bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        row = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if kind == 1:
            for x in range(channels, stride):
                row[x] = (row[x] + row[x - channels]) & 255
        elif kind == 2:
            for x in range(stride):
                row[x] = (row[x] + previous[x]) & 255
        elif kind == 3:
            for x in range(stride):
                left = row[x - channels] if x >= channels else 0
                row[x] = (row[x] + ((left + previous[x]) >> 1)) & 255
        elif kind == 4:
            for x in range(stride):
                left = row[x - channels] if x >= channels else 0
                upper_left = previous[x - channels] if x >= channels else 0
                row[x] = (row[x] + paeth(left, previous[x], upper_left)) & 255
        elif kind != 0:
            fail(f"{name}: row {y} has filter type {kind}")
        pixels += row
        previous = row
    if channels == 4:
        if pixels[3::4] != b"\xff" * (width * height):
            fail(f"{name}: RGBA with pixels not opaque")
        pixels = rgba_to_rgb(pixels)
    return width, height, bytes(pixels)


def rgba_to_rgb(rgba):
    rgb = bytearray(len(rgba) // 4 * 3)
    for channel in range(3):
        rgb[channel::3] = rgba[channel::4]
    return rgb


# ---- the page ----------------------------------------------------------------

def open_browser(se):
    options = se.webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1200,900"):
        options.add_argument(argument)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return se.webdriver.Chrome(service=se.Service(CHROMEDRIVER), options=options)


def page_status(driver):
    try:
        return driver.execute_script("return document.getElementById('status').textContent")
    except Exception as error:  # the page may be gone; this only decorates a failure
        return f"(unreadable: {error})"


def wait_for_final(se, driver, after_view):
    """Waits for the final frame of a view later than after_view; returns that view's number."""
    condition = ("const b = document.body;"
                 "return b.dataset.final === '1' && Number(b.dataset.view) > arguments[0] ? Number(b.dataset.view) : 0")
    try:
        return se.WebDriverWait(driver, FRAME_TIMEOUT, poll_frequency=0.05).until(
            lambda d: d.execute_script(condition, after_view))
    except se.TimeoutException:
        fail(f"no final frame for a view after view {after_view} within {FRAME_TIMEOUT} s; "
             f"status line: {page_status(driver)!r}")


def canvas_pixels(driver):
    """(width, height, RGBA bytes) of the canvas's backing store."""
    width, height, data = driver.execute_script("""
        const canvas = document.getElementById('frame');
        const pixels = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
        let text = '';
        for (let i = 0; i < pixels.length; i += 0x8000) {
            text += String.fromCharCode.apply(null, pixels.subarray(i, i + 0x8000));
        }
        return [canvas.width, canvas.height, btoa(text)];""")
    return width, height, base64.b64decode(data)


def copy_command(se, driver):
    """Clicks "Copy command" and returns the command the page shows in #command."""
    driver.execute_script("document.getElementById('command').textContent = ''")
    driver.find_element(se.By.ID, "copy").click()
    try:
        return se.WebDriverWait(driver, 30, poll_frequency=0.05).until(
            lambda d: d.find_element(se.By.ID, "command").text.strip())
    except se.TimeoutException:
        fail(f"no command in #command 30 s after clicking Copy command; status line: {page_status(driver)!r}")


def print_timings(driver, view, label):
    timings = driver.execute_script("return window.quiverView.timings.filter(t => t.view === arguments[0])", view)
    stages = ", ".join(f"{t['stage']} {t['ms_since_view_start']:.1f} ms" for t in timings)
    print(f"timings, {label} (view {view}): {stages or 'none recorded'}")


def browser_errors(driver):
    """The console's errors, less the failed loads of superseded (409) frames."""
    errors = [entry["message"] for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
    return [message for message in errors if "status of 409" not in message]


# ---- checks ------------------------------------------------------------------

OUTPUT = ("-o", "--output")


def find_option(argv, names):
    """(index, value) of the first of names in argv, as "NAME VALUE" or "NAME=VALUE"; (None, None) when absent."""
    for i, word in enumerate(argv):
        for name in names:
            if word == name and i + 1 < len(argv):
                return i, argv[i + 1]
            if word.startswith(name + "="):
                return i, word[len(name) + 1:]
    return None, None


def option(argv, flag, command):
    value = find_option(argv, (flag,) if isinstance(flag, str) else flag)[1]
    if value is None:
        fail(f"the command has no {flag}: {command}")
    return value


def close(a, b):
    return abs(a - b) <= 1e-6 * max(1.0, abs(a), abs(b))


def check_command(command, state, label):
    """The command renders state's view with the flags quiver view was given; returns its argv."""
    argv = shlex.split(command)
    if len(argv) < 2 or os.path.basename(argv[0]) != "quiver" or argv[1] != "render":
        fail(f"{label}: the command does not start with 'quiver render': {command}")
    for flag, key in (("--look-from", "from"), ("--look-at", "at"), ("--up", "up")):
        text = option(argv, flag, command)
        values = [float(part) for part in text.split(",")]
        if len(values) != 3 or not all(close(v, s) for v, s in zip(values, state[key])):
            fail(f"{label}: {flag} {text} in the command, but the page's camera has {key} {state[key]}")
    fov = option(argv, "--fov", command)
    if not close(float(fov), state["fov"]):
        fail(f"{label}: --fov {fov} in the command, but the page's camera has fov {state['fov']}")
    expected = {"--width": str(WIDTH), "--height": str(HEIGHT), "--aa": "grid:2", "--threads": "2",
                "--max-depth": str(state["max_depth"])}
    for flag, value in expected.items():
        if option(argv, flag, command) != value:
            fail(f"{label}: {flag} {option(argv, flag, command)} in the command, expected {value}: {command}")
    if not option(argv, OUTPUT, command).endswith(".png"):
        fail(f"{label}: the command's output is not a .png: {command}")
    return argv


def render_command(argv, quiver, workdir, name):
    """Runs the command (quiver as given, the output in workdir); returns the PNG's path."""
    argv = list(argv)
    argv[0] = quiver
    output = os.path.join(workdir, name)
    index, _ = find_option(argv, OUTPUT)
    if argv[index] in OUTPUT:
        argv[index + 1] = output
    else:
        argv[index] = argv[index].split("=", 1)[0] + "=" + output
    if os.path.exists(output):
        os.remove(output)
    start = time.monotonic()
    done = subprocess.run(argv, cwd=workdir, capture_output=True, text=True, timeout=600)
    if done.returncode != 0 or not os.path.exists(output):
        fail(f"the copied command failed (exit {done.returncode}): {shlex.join(argv)}\n{done.stderr.strip()}")
    print(f"rendered {name} with the copied command in {time.monotonic() - start:.2f} s")
    return output


def compare_pixels(label, canvas, image):
    """Fails naming the first differing pixel and how many differ."""
    width, height, rgba = canvas
    png_width, png_height, rgb = image
    if (width, height) != (png_width, png_height):
        fail(f"{label}: the canvas is {width}x{height}, the PNG {png_width}x{png_height}")
    opaque = rgba[3::4] == b"\xff" * (width * height)
    canvas_rgb = bytes(rgba_to_rgb(rgba))
    if canvas_rgb == rgb and opaque:
        print(f"{label}: the canvas equals the PNG ({width}x{height}, byte for byte)")
        return
    differing = [i for i in range(width * height)
                 if canvas_rgb[3 * i:3 * i + 3] != rgb[3 * i:3 * i + 3] or rgba[4 * i + 3] != 255]
    first = differing[0]
    x, y = first % width, first // width
    fail(f"{label}: {len(differing)} of {width * height} pixels differ; the first at ({x}, {y}): "
         f"canvas RGBA {tuple(rgba[4 * first:4 * first + 4])}, PNG RGB {tuple(rgb[3 * first:3 * first + 3])}")


def count_differing(a, b):
    return sum(1 for i in range(0, len(a), 4) if a[i:i + 3] != b[i:i + 3])


def check_http_errors(base, token, state):
    status, body, _ = http_get(f"{base}/api/scene")
    if status != 403:
        fail(f"/api/scene without the token: HTTP {status}, expected 403")
    wrong = token[:-1] + ("1" if token[-1] == "0" else "0")
    status, body, _ = http_get(f"{base}/api/scene?token={wrong}")
    if status != 403:
        fail(f"/api/scene with a wrong token: HTTP {status}, expected 403")
    query = urllib.parse.urlencode({
        "token": token, "from": ",".join(map(repr, state["from"])), "at": ",".join(map(repr, state["at"])),
        "up": ",".join(map(repr, state["up"])), "fov": repr(state["fov"]), "width": "0", "height": str(HEIGHT),
        "aa": state["aa"], "max_depth": str(state["max_depth"]), "stage": "full"})
    status, body, _ = http_get(f"{base}/api/frame?{query}")
    message = body.decode("utf-8", "replace").strip()
    if status != 400 or not message:
        fail(f"/api/frame with width=0: HTTP {status} {message!r}, expected 400 with a message")
    print(f"without the token: 403; width=0: 400 {message!r}")


def check_png_endpoint(driver, image, label):
    """/api/png (the download link) holds the same image as the command's PNG."""
    href = driver.execute_script("return document.getElementById('download').href")
    if urllib.parse.urlparse(href).path != "/api/png":
        fail(f"{label}: the download link is {href}, not /api/png")
    status, body, headers = http_get(href)
    if status != 200 or headers.get_content_type() != "image/png":
        fail(f"{label}: /api/png: HTTP {status} {headers.get('Content-Type')}")
    if "attachment" not in headers.get("Content-Disposition", ""):
        fail(f"{label}: /api/png has no attachment Content-Disposition: {headers.get('Content-Disposition')!r}")
    if decode_png(body, "/api/png") != image:
        fail(f"{label}: /api/png's image differs from the command's PNG")
    print(f"{label}: /api/png holds the same image as the command's PNG")


def fetch_initial_view(base, token):
    """/api/scene's view as the page's state() names it."""
    status, body, _ = http_get(f"{base}/api/scene?token={token}")
    if status != 200:
        fail(f"/api/scene: HTTP {status} {body[:200]!r}")
    scene = json.loads(body)
    initial = dict(scene["view"], width=scene["width"], height=scene["height"], aa=scene["aa"],
                   max_depth=scene["max_depth"])
    print(f"scene {scene['scene']}: {initial}, {scene['threads']} threads, {scene['isa']}, version {scene['version']}")
    return initial


def check_command_image(se, driver, state, canvas, args, label, name):
    """The copied command names state's view, and the PNG it writes holds the canvas's pixels; returns its image."""
    command = copy_command(se, driver)
    print(f"{label}, command: {command}")
    argv = check_command(command, state, label)
    with open(render_command(argv, args.quiver, args.workdir, name), "rb") as file:
        image = decode_png(file.read(), name)
    compare_pixels(label, canvas, image)
    return image


def drag_to_orbit(se, driver):
    """A left-drag of 80 px across the canvas, in 8 steps (coarse frames in between)."""
    canvas = driver.find_element(se.By.ID, "frame")
    chain = se.ActionChains(driver, duration=100)
    chain.move_to_element_with_offset(canvas, -50, 0).click_and_hold()
    for _ in range(8):
        chain.move_by_offset(10, 0)
    chain.release().perform()


def run_checks(se, driver, server, args):
    parts = urllib.parse.urlparse(server.url)
    base = f"{parts.scheme}://{parts.netloc}"
    token = urllib.parse.parse_qs(parts.query).get("token", [""])[0]
    if not re.fullmatch(r"[0-9a-f]{32}", token):
        fail(f"the URL's token is not 32 hex digits: {server.url}")
    initial = fetch_initial_view(base, token)

    # The first view, refined to its final frame.
    driver.get(server.url)
    first_view = wait_for_final(se, driver, 0)
    state = driver.execute_script("return window.quiverView.state()")
    if state != initial:
        fail(f"the page's first camera {state} is not /api/scene's {initial}")
    print(f"first view {first_view}: {page_status(driver)}")
    print_timings(driver, first_view, "first view")
    if driver.execute_script("return document.body.dataset.stage") != "final":
        fail("body's data-stage is not 'final' when data-final is set (grid:2 anti-aliasing)")
    first = canvas_pixels(driver)
    if first[:2] != (WIDTH, HEIGHT):
        fail(f"the canvas is {first[0]}x{first[1]}, expected {WIDTH}x{HEIGHT}")
    check_command_image(se, driver, state, first, args, "first view", "first.png")

    # An orbit: the camera moves about the look-at point; a new final frame follows.
    drag_to_orbit(se, driver)
    dragged = driver.execute_script("return window.quiverView.state()")
    if dragged["from"] == state["from"]:
        fail(f"the drag did not move the camera: from is still {state['from']}")
    if dragged["at"] != state["at"]:
        fail(f"orbiting moved the look-at point: {state['at']} -> {dragged['at']}")
    print(f"dragged: from {state['from']} -> {dragged['from']}")
    final_view = wait_for_final(se, driver, first_view)
    drawn = driver.execute_script(
        "return window.quiverView.timings.filter(t => t.view > arguments[0] && t.view < arguments[1]).length",
        first_view, final_view)
    print(f"during the drag: views {first_view + 1}..{final_view - 1}, {drawn} coarse frames drawn")
    print(f"after the drag, view {final_view}: {page_status(driver)}")
    print_timings(driver, final_view, "after the drag")
    after = canvas_pixels(driver)
    changed = count_differing(first[2], after[2])
    if changed == 0:
        fail("the final frame after the drag has the same pixels as the first")
    print(f"the new final frame differs from the first in {changed} of {WIDTH * HEIGHT} pixels")
    image = check_command_image(se, driver, dragged, after, args, "after the drag", "dragged.png")
    check_png_endpoint(driver, image, "after the drag")

    # A wheel turned away from the user (deltaY < 0) dollies in: nearer the look-at point, along the same line.
    driver.execute_script(
        "document.getElementById('frame').dispatchEvent("
        "new WheelEvent('wheel', {deltaY: -100, deltaMode: 0, bubbles: true, cancelable: true}))")
    wheeled = driver.execute_script("return window.quiverView.state()")
    distance = lambda view: math.dist(view["from"], view["at"])
    if not distance(wheeled) < distance(dragged):
        fail(f"a wheel step toward the scene did not dolly in: {distance(dragged)} -> {distance(wheeled)}")
    if wheeled["at"] != dragged["at"]:
        fail(f"dollying moved the look-at point: {dragged['at']} -> {wheeled['at']}")
    print(f"wheeled in: distance {distance(dragged):.4g} -> {distance(wheeled):.4g}")

    check_http_errors(base, token, dragged)
    errors = browser_errors(driver)
    for message in errors:
        print(f"browser console: {message}")
    if any("Uncaught" in message for message in errors):
        fail("the page threw (see the browser console above)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quiver", required=True, help="the quiver binary")
    parser.add_argument("--scene", help="the scene file (default: the built-in scene)")
    parser.add_argument("--workdir", required=True, help="a directory for the PNGs")
    args = parser.parse_args()
    args.quiver = os.path.abspath(args.quiver)
    scene = os.path.abspath(args.scene) if args.scene else None
    se = load_selenium()
    if not os.access(args.quiver, os.X_OK):
        print(f"FAIL: {args.quiver} is not an executable")
        return 1
    os.makedirs(args.workdir, exist_ok=True)
    args.workdir = os.path.abspath(args.workdir)

    server = Server(args.quiver, scene, args.workdir)
    driver = None
    try:
        server.wait_for_url()
        print(f"server: {shlex.join(server.command)} -> {server.url}")
        driver = open_browser(se)
        run_checks(se, driver, server, args)
        driver.quit()
        driver = None
        server.stop_with_sigint()
    except Failure as failure:
        print(f"FAIL: {failure}")
        if driver is not None:
            for message in browser_errors(driver):
                print(f"browser console: {message}")
        print(f"server stderr (last lines):\n{server.stderr_tail()}")
        return 1
    except Exception:
        traceback.print_exc(file=sys.stdout)
        print(f"FAIL: an unexpected error (above)\nserver stderr (last lines):\n{server.stderr_tail()}")
        return 1
    finally:
        if driver is not None:
            driver.quit()
        server.kill()
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
