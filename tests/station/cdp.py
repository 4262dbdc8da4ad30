# SPDX-License-Identifier: MIT
"""Debian's chromium, headless with software WebGL (SwiftShader), driven over the DevTools
protocol with python3-websocket: a real browser for the page's tests (tests/station/test_page.py)."""
import base64
import json
import os
import shutil
import subprocess
import tempfile
import time

import websocket

from client import end

CHROMIUM_FLAGS = ["--headless=new", "--no-sandbox", "--disable-gpu-sandbox", "--use-gl=angle",
                  "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist",
                  "--no-first-run", "--no-default-browser-check", "--disable-extensions",
                  "--disable-background-networking", "--disable-component-update", "--mute-audio",
                  "--remote-debugging-port=0"]
START_S = 30


def chromium():
    return os.environ.get("FBRL_CHROMIUM") or shutil.which("chromium") or shutil.which("chromium-browser")


class Browser:
    """One headless chromium with one page (a tab), flags its own beyond CHROMIUM_FLAGS;
    .call(method, **params) a DevTools command,
    .eval(js) a value of the page, .screenshot() PNG bytes."""

    def __init__(self, width=1280, height=800, flags=()):
        prog = chromium()
        if prog is None:
            raise OSError("no chromium (Debian: chromium)")
        self.dir = tempfile.mkdtemp(prefix="fbrl-chromium-")
        self.proc = subprocess.Popen([prog] + CHROMIUM_FLAGS + list(flags) + ["--user-data-dir=" + self.dir,
                                                                "--window-size=%d,%d" % (width, height),
                                                                "about:blank"],
                                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        port_file = os.path.join(self.dir, "DevToolsActivePort")
        deadline = time.monotonic() + START_S
        while not os.path.exists(port_file) or os.path.getsize(port_file) == 0:
            if time.monotonic() > deadline or self.proc.poll() is not None:
                self.close()
                raise OSError("chromium did not start its DevTools endpoint")
            time.sleep(0.05)
        time.sleep(0.05)  # the file is written in one go, but its second line may lag
        with open(port_file) as f:
            port = int(f.readline())
        # the tab chromium opened (about:blank)
        import urllib.request
        targets = json.load(urllib.request.urlopen("http://127.0.0.1:%d/json/list" % port))
        page = next(t for t in targets if t["type"] == "page")
        self.ws = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=START_S, suppress_origin=True)
        self._id = 0
        self.events = []
        self.call("Page.enable")
        self.call("Runtime.enable")
        self.call("Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=1, mobile=False)

    def call(self, method, **params):
        self._id += 1
        self.ws.send(json.dumps({"id": self._id, "method": method, "params": params}))
        while True:
            m = json.loads(self.ws.recv())
            if m.get("id") == self._id:
                if "error" in m:
                    raise RuntimeError("%s: %s" % (method, m["error"]))
                return m.get("result", {})
            self.events.append(m)

    def eval(self, js, wait=True):
        r = self.call("Runtime.evaluate", expression=js, returnByValue=True, awaitPromise=wait)
        if "exceptionDetails" in r:
            raise RuntimeError("%s: %s" % (js, r["exceptionDetails"]))
        return r["result"].get("value")

    def wait_for(self, js, seconds=20, what=None):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            v = self.eval(js)
            if v:
                return v
            time.sleep(0.05)
        raise AssertionError("timed out waiting for %s" % (what or js))

    def goto(self, url):
        self.call("Page.navigate", url=url)

    def screenshot(self):
        return base64.b64decode(self.call("Page.captureScreenshot", format="png")["data"])

    def close(self):
        try:
            if getattr(self, "ws", None) is not None:
                self.ws.close()
        finally:
            end(self.proc, 10)
            self.proc.stderr.close()
            shutil.rmtree(self.dir, ignore_errors=True)
