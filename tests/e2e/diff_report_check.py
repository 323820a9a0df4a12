#!/usr/bin/env python3
"""`tumble diff --report` and `--junit` checked from outside, as CI and a person meet them.

    diff_report_check.py TUMBLE WORK_DIR junit     the JUnit file, read by an XML parser
    diff_report_check.py TUMBLE WORK_DIR browser   the report, opened in headless Chromium

Both compare the same folder pair (identical, within tolerance, changed, missing, extra files,
and names with &, <, quotes and non-ASCII characters) at the CI tolerance, exit 1 expected.

The browser check drives Debian's chromium through the DevTools protocol on a pipe
(--remote-debugging-pipe: NUL-separated JSON on file descriptors 3 and 4), so it needs nothing
but the standard library: the page loads with no console message of level warning or error, no
request leaves the report folder, every <img> exists on disk, decodes (here and in the browser)
and every picture in the folder is shown, failures come first, and the slider and the toggle,
worked with the keyboard, change the pixels shown. Exit 0 passed, 1 failed (reasons printed),
77 skipped (chromium missing; the reason printed).
"""
import base64
import json
import os
import select
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ElementTree
import zlib

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
    return condition


# --- PNG files, written and read with zlib alone ---------------------------------------------

def png_bytes(width, height, pixel):
    """An 8-bit RGB PNG; pixel(x, y) gives (r, g, b)."""
    raw = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y))
                   for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) +
            chunk(b"IEND", b""))


def png_decode(data):
    """(width, height, rows of RGB(A) bytes) of an 8-bit non-interlaced PNG; raises if broken."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    at, idat, header = 8, b"", None
    while at < len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + length]
        if zlib.crc32(kind + body) != struct.unpack(">I", data[at + 8 + length:at + 12 + length])[0]:
            raise ValueError("bad CRC in " + kind.decode("latin-1"))
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or interlace != 0 or colour not in (0, 2, 4, 6):
        raise ValueError("unsupported PNG format %s" % (header,))
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
    raw = zlib.decompress(idat)
    stride = width * channels
    if len(raw) != height * (stride + 1):
        raise ValueError("wrong amount of pixel data")
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            up_left = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - up_left
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - up_left)
                predictor = left if pa <= pb and pa <= pc else up if pb <= pc else up_left
                line[i] = (line[i] + predictor) & 255
            elif kind != 0:
                raise ValueError("bad filter type")
        rows.append(bytes(line))
        previous = line
    return width, height, channels, rows


# --- the fixture -------------------------------------------------------------------------------

WIDTH, HEIGHT = 40, 30
WEIRD = "a&b <c> \"q\" 'été' 🎲.png"  # &, <, >, quotes and non-ASCII in a file name


def gradient(x, y):
    return (40 + 4 * x, 60 + 5 * y, 180 - 2 * x - 2 * y)  # never pure red


def red_block(x, y):
    return (255, 0, 0) if x >= 8 and y >= 6 else gradient(x, y)  # most of the picture


def slightly_off(x, y):
    r, g, b = gradient(x, y)
    return (r + 2, g, b)  # within --max-delta 5


def make_fixture(work, extra_bad_names=False):
    golden, actual = os.path.join(work, "golden"), os.path.join(work, "actual")
    for folder in (golden, actual):
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)

    def put(folder, name, pixel):
        path = os.path.join(folder, name) if isinstance(name, str) else os.path.join(
            os.fsencode(folder), name)
        with open(path, "wb") as out:
            out.write(png_bytes(WIDTH, HEIGHT, pixel))

    put(golden, "same.png", gradient)
    put(actual, "same.png", gradient)
    put(golden, "within.png", gradient)
    put(actual, "within.png", slightly_off)
    put(golden, "changed.png", gradient)
    put(actual, "changed.png", red_block)
    put(golden, WEIRD, gradient)
    put(actual, WEIRD, red_block)
    put(golden, "missing.png", gradient)
    put(actual, "extra.png", gradient)
    passing, failing = {"same.png", "within.png"}, {"changed.png", WEIRD, "missing.png", "extra.png"}
    if extra_bad_names:
        # A control character and a byte that is not UTF-8: XML 1.0 has no way to write either;
        # they must come out as U+FFFD, the document still valid.
        put(golden, "ctl\x01.png", gradient)
        put(actual, "ctl\x01.png", red_block)
        put(golden, b"bad\xff.png", gradient)
        put(actual, b"bad\xff.png", gradient)
        failing.add("ctl\ufffd.png")
        passing.add("bad\ufffd.png")
    return passing, failing


def run_diff(tumble, work, extra):
    result = subprocess.run([tumble, "diff", "golden", "actual", "--max-delta", "5",
                             "--max-fraction", "0.001"] + extra, cwd=work, capture_output=True,
                            timeout=60)
    check(result.returncode == 1, "tumble diff: exit %d, expected 1 (failures present)\n%s%s" % (
        result.returncode, result.stdout.decode(errors="replace"),
        result.stderr.decode(errors="replace")))
    return result


# --- JUnit -------------------------------------------------------------------------------------

def check_junit(tumble, work):
    passing, failing = make_fixture(work, extra_bad_names=True)
    run_diff(tumble, work, ["--junit", "out/junit.xml"])
    with open(os.path.join(work, "out/junit.xml"), "rb") as f:
        document = f.read()
    root = ElementTree.fromstring(document)  # expat: raises on anything that is not XML 1.0
    suites = [root] if root.tag == "testsuite" else root.findall("testsuite")
    check(len(suites) == 1, "one <testsuite>, found %d" % len(suites))
    suite = suites[0]
    check(suite.get("name") == "tumble diff", "suite name %r" % suite.get("name"))
    cases = suite.findall("testcase")
    names = [c.get("name") for c in cases]
    check(suite.get("tests") == str(len(passing) + len(failing)) == str(len(cases)),
          "tests=%s for %d testcases" % (suite.get("tests"), len(cases)))
    check(suite.get("failures") == str(len(failing)), "failures=%s, expected %d" % (
        suite.get("failures"), len(failing)))
    check(float(suite.get("time")) >= 0.0, "time=%r" % suite.get("time"))
    check(set(names) == passing | failing, "testcase names %r" % sorted(names))
    for case in cases:
        failure = case.find("failure")
        name = case.get("name")
        if not check((failure is not None) == (name in failing), "%r: failure %r" % (name, failure)):
            continue
        float(case.get("time"))
        if failure is None:
            continue
        message = failure.get("message")
        if name in ("missing.png", "extra.png"):
            check("missing from" in message, "%r: message %r" % (name, message))
        else:
            check("pixels differ" in message and "largest delta" in message and "PSNR" in message,
                  "%r: message without the metrics: %r" % (name, message))
            check("max delta 5, max fraction 0.001" in message, "%r: no tolerance in %r" % (
                name, message))
            check(failure.text.startswith(name + ": "), "%r: details %r" % (name, failure.text))
    print("junit: %d testcases, %d failures, %d bytes" % (len(cases), len(failing), len(document)))


# --- the browser -------------------------------------------------------------------------------

class Chromium:
    """Headless Chromium driven over --remote-debugging-pipe."""

    def __init__(self, binary, profile):
        to_browser, self.to_browser = os.pipe()
        self.from_browser, from_browser_w = os.pipe()

        def wire_pipes():  # in the child: the protocol's fixed descriptors 3 and 4
            os.dup2(to_browser, 3)
            os.dup2(from_browser_w, 4)

        self.process = subprocess.Popen(
            [binary, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
             "--no-first-run", "--disable-background-networking", "--disable-component-update",
             "--disable-sync", "--disable-extensions", "--user-data-dir=" + profile,
             "--remote-debugging-pipe", "--window-size=1100,900", "--hide-scrollbars",
             "about:blank"],
            pass_fds=(3, 4), preexec_fn=wire_pipes, stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_browser)
        os.close(from_browser_w)
        self.buffer, self.last_id, self.events = b"", 0, []

    def receive(self, timeout=120.0):  # a cold start beside other tests on 2 cores can be slow
        deadline = time.monotonic() + timeout
        while b"\0" not in self.buffer:
            left = deadline - time.monotonic()
            ready, _, _ = select.select([self.from_browser], [], [], max(left, 0))
            if not ready:
                raise TimeoutError("chromium did not answer in %g s" % timeout)
            data = os.read(self.from_browser, 1 << 20)
            if not data:
                raise EOFError("chromium closed the DevTools pipe")
            self.buffer += data
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def call(self, method, session=None, **params):
        self.last_id += 1
        message = {"id": self.last_id, "method": method, "params": params}
        if session:
            message["sessionId"] = session
        os.write(self.to_browser, json.dumps(message).encode() + b"\0")
        while True:
            reply = self.receive()
            if reply.get("id") == self.last_id:
                if "error" in reply:
                    raise RuntimeError("%s: %s" % (method, reply["error"]))
                return reply["result"]
            self.events.append(reply)

    def wait_for(self, method):
        while not any(e.get("method") == method for e in self.events):
            self.events.append(self.receive())

    def close(self):
        self.process.kill()
        self.process.wait()
        os.close(self.to_browser)
        os.close(self.from_browser)


def find_chromium():
    for candidate in ("/usr/bin/chromium", shutil.which("chromium") or "",
                      shutil.which("chromium-browser") or ""):
        if candidate and os.access(candidate, os.X_OK):
            return candidate
    return None


def red_pixels(png_data):
    width, height, channels, rows = png_decode(png_data)
    count = 0
    for row in rows:
        for x in range(width):
            r, g, b = row[x * channels:x * channels + 3]
            count += r > 240 and g < 16 and b < 16
    return count


def check_browser(tumble, work):
    binary = find_chromium()
    if binary is None:
        print("SKIP: chromium is not installed (Debian package chromium; scripts/setup --tests "
              "installs it), so the report cannot be opened in a browser here")
        return 77
    passing, failing = make_fixture(work)
    started = time.monotonic()
    run_diff(tumble, work, ["--report", "report"])
    report = os.path.realpath(os.path.join(work, "report"))
    index = os.path.join(report, "index.html")
    if not check(os.path.isfile(index), "no report/index.html"):
        return 1
    profile = tempfile.mkdtemp(prefix="chromium-profile-", dir=work)
    browser = Chromium(binary, profile)
    try:
        target = browser.call("Target.createTarget", url="about:blank")["targetId"]
        session = browser.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
        for domain in ("Page", "Runtime", "Network", "Log"):
            browser.call(domain + ".enable", session)
        browser.call("Page.navigate", session, url="file://" + index)
        browser.wait_for("Page.loadEventFired")

        def evaluate(expression):
            result = browser.call("Runtime.evaluate", session, expression=expression,
                                  returnByValue=True, awaitPromise=True)
            if "exceptionDetails" in result:
                raise RuntimeError("evaluate %s: %s" % (expression, result["exceptionDetails"]))
            return result["result"].get("value")

        # Every picture decoded by the browser too (decode() rejects when it cannot).
        images = evaluate("""Promise.all(Array.from(document.images, i => i.decode().then(
            () => [i.getAttribute('src'), i.naturalWidth, i.naturalHeight],
            () => [i.getAttribute('src'), 0, 0])))""")
        check(len(images) > 0, "the page shows no image")
        referenced = set()
        for src, width, height in images:
            check(width > 0 and height > 0, "the browser cannot decode %s" % src)
            path = os.path.join(report, src)
            referenced.add(os.path.normpath(path))
            if check(os.path.isfile(path), "%s is referenced but missing" % src):
                with open(path, "rb") as f:
                    w, h, _, _ = png_decode(f.read())
                check((w, h) == (width, height) == (WIDTH, HEIGHT), "%s is %dx%d" % (src, w, h))
        on_disk = {os.path.normpath(os.path.join(report, "images", f))
                   for f in os.listdir(os.path.join(report, "images"))}
        check(on_disk <= referenced, "pictures in the folder but not on the page: %s" %
              sorted(on_disk - referenced))
        check(set(os.listdir(report)) == {"index.html", "images"}, "report holds %s" %
              sorted(os.listdir(report)))

        # Failures first; every pair has its section.
        sections = evaluate("""Array.from(document.querySelectorAll('section.pair'),
            s => [s.dataset.name, s.classList.contains('fail')])""")
        verdicts = [fail for _, fail in sections]
        check(verdicts == sorted(verdicts, reverse=True), "a pass comes before a failure: %r" %
              sections)
        check({n for n, f in sections if f} == failing, "failing sections %r" % sections)
        check({n for n, f in sections if not f} == passing, "passing sections %r" % sections)
        summary = evaluate("document.getElementById('summary').textContent")
        worst = max(abs(u - v) for x in range(WIDTH) for y in range(HEIGHT)
                    for u, v in zip(gradient(x, y), red_block(x, y)))
        check(summary == "6 pairs, 4 failed, worst delta %d" % worst, "summary %r" % summary)

        # The in-place compare of changed.png: the keyboard moves the slider and flips the
        # toggle, and each time the pixels shown change (actual has a pure red block, expected
        # none).
        box = "Array.from(document.querySelectorAll('section.pair')).find(s => s.dataset.name" \
              " === 'changed.png').querySelector('.compare')"
        evaluate(box + ".scrollIntoView()")
        rect = evaluate("(() => { const r = %s.querySelector('.stage').getBoundingClientRect();"
                        " return [r.x + scrollX, r.y + scrollY, r.width, r.height]; })()" % box)

        def shot():
            data = browser.call("Page.captureScreenshot", session, format="png",
                                captureBeyondViewport=True,
                                clip={"x": rect[0], "y": rect[1], "width": rect[2],
                                      "height": rect[3], "scale": 1})["data"]
            return base64.b64decode(data)

        def press(key, code, key_code, text=None):
            for kind in ("keyDown", "keyUp"):
                params = {"type": kind, "key": key, "code": code, "windowsVirtualKeyCode": key_code}
                if text and kind == "keyDown":
                    params["text"] = text
                browser.call("Input.dispatchKeyEvent", session, **params)

        before = shot()
        evaluate(box + ".querySelector('input').focus()")
        press("End", "End", 35)
        value = evaluate(box + ".querySelector('input').value")
        at_end = shot()
        check(value == "100", "End on the slider: value %r, expected 100" % value)
        check(red_pixels(before) > 0, "half actual shows no red block")
        check(at_end != before and red_pixels(at_end) == 0,
              "End on the slider did not show the whole expected picture")
        evaluate(box + ".querySelector('button').focus()")
        press(" ", "Space", 32, text=" ")
        toggled = shot()
        state = evaluate(box + ".querySelector('output').textContent")
        check(toggled != at_end and red_pixels(toggled) > red_pixels(before),
              "Space on the toggle did not show the whole actual picture (%r)" % state)
        check(state == "showing actual", "toggle state %r" % state)

        # Nothing but the report folder was asked for, and nothing complained.
        for event in browser.events:
            method, params = event.get("method"), event.get("params", {})
            if method == "Network.requestWillBeSent":
                url = params["request"]["url"]
                check(url.startswith("file://" + report + "/"), "request outside the report: " + url)
            elif method == "Network.loadingFailed":
                check(False, "a load failed: %s" % params.get("errorText"))
            elif method == "Runtime.exceptionThrown":
                check(False, "uncaught exception: %s" % json.dumps(params["exceptionDetails"])[:500])
            elif method == "Runtime.consoleAPICalled":
                check(params["type"] not in ("error", "warning", "assert"),
                      "console %s: %s" % (params["type"], json.dumps(params["args"])[:300]))
            elif method == "Log.entryAdded":
                entry = params["entry"]
                check(entry["level"] not in ("error", "warning"),
                      "console %s: %s" % (entry["level"], entry.get("text")))
        requests = sum(e.get("method") == "Network.requestWillBeSent" for e in browser.events)
        print("browser: %d sections, %d images, %d requests (all in the report folder), "
              "report %d bytes, %.1f s" % (len(sections), len(images), requests,
                                           sum(os.path.getsize(os.path.join(d, f))
                                               for d, _, fs in os.walk(report) for f in fs),
                                           time.monotonic() - started))
        if os.environ.get("DIFF_REPORT_SCREENSHOT"):
            # For docs/figures: the top of the page at a reading size.
            browser.call("Emulation.setDeviceMetricsOverride", session, width=900, height=1000,
                         deviceScaleFactor=1, mobile=False)
            evaluate("window.scrollTo(0, 0)")
            data = browser.call("Page.captureScreenshot", session, format="png")["data"]
            with open(os.environ["DIFF_REPORT_SCREENSHOT"], "wb") as f:
                f.write(base64.b64decode(data))
    finally:
        browser.close()
        shutil.rmtree(profile, ignore_errors=True)
    return 0


def main():
    tumble, work, mode = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), sys.argv[3]
    os.makedirs(work, exist_ok=True)
    code = check_junit(tumble, work) if mode == "junit" else check_browser(tumble, work)
    if code == 77:
        return 77
    for failure in failures:
        print("FAIL: " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
