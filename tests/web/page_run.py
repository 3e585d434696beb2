#!/usr/bin/env python3
"""Opens a page in headless Chromium and drives it over the DevTools protocol (--remote-debugging-pipe:
no network port, no extra packages), in real time: waits until the page marks itself done
(<body data-exit="N">), then saves what it was asked for.

usage: page_run.py BROWSER URL OUT_DIR [--timeout S] [--screenshot FILE] [--size WxH] [--downloads DIR]
                   [--open FILE ...] [--drop FILE ...]
Writes OUT_DIR/state.json (the text of #state-json), OUT_DIR/log.txt (the text of #log) and prints the
page's exit code, the status line and the wall time; exit 0 if the page finished with code 0.
--downloads DIR: the page's downloads are saved into DIR. --open FILE: once the page runs, FILE is picked in
its "Open a file" input (#open-file), as a user would, one file at a time in the order given. --drop FILE: the
same, dragged from the desktop and dropped on the middle of the page (DevTools' Input.dispatchDragEvent).
"""
import argparse, base64, json, os, subprocess, sys, tempfile, time

ap = argparse.ArgumentParser()
ap.add_argument("browser")
ap.add_argument("url")
ap.add_argument("out")
ap.add_argument("--timeout", type=float, default=240)
ap.add_argument("--screenshot")
ap.add_argument("--size", default="1280x800")
ap.add_argument("--downloads")
ap.add_argument("--open", action="append", default=[])
ap.add_argument("--drop", action="append", default=[])
a = ap.parse_args()
w, h = (int(v) for v in a.size.split("x"))

to_chrome_r, to_chrome_w = os.pipe()
from_chrome_r, from_chrome_w = os.pipe()
profile = tempfile.mkdtemp(prefix="impactlab-web-")
args = [a.browser, "--headless=new", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
        "--allow-file-access-from-files", "--disable-background-networking", "--disable-component-update",
        "--disable-sync", "--no-first-run", "--no-default-browser-check", "--user-data-dir=" + profile,
        "--window-size=%d,%d" % (w, h), "--remote-debugging-pipe", "about:blank"]
if os.getuid() == 0:
    args.insert(1, "--no-sandbox")   # Chromium refuses its sandbox as root


def child_fds():   # the protocol's pipe is the child's fds 3 (commands in) and 4 (replies out)
    os.dup2(to_chrome_r, 3)
    os.dup2(from_chrome_w, 4)


log = open(os.path.join(a.out, "chromium.log"), "w")
proc = subprocess.Popen(args, stdout=log, stderr=log, preexec_fn=child_fds, pass_fds=(3, 4))
os.close(to_chrome_r)
os.close(from_chrome_w)
buf = b""
next_id = 0


def send(method, params=None, session=None):
    global buf, next_id
    next_id += 1
    msg = {"id": next_id, "method": method, "params": params or {}}
    if session:
        msg["sessionId"] = session
    os.write(to_chrome_w, json.dumps(msg).encode() + b"\0")
    while True:   # replies and events, until the reply to this command
        while b"\0" not in buf:
            chunk = os.read(from_chrome_r, 1 << 20)
            if not chunk:
                sys.exit("page_run: chromium closed the protocol pipe")
            buf += chunk
        raw, buf = buf.split(b"\0", 1)
        reply = json.loads(raw)
        if reply.get("id") == next_id:
            if "error" in reply:
                sys.exit("page_run: %s: %s" % (method, reply["error"]))
            return reply.get("result", {})


def evaluate(session, expr):
    r = send("Runtime.evaluate", {"expression": expr, "returnByValue": True}, session)
    return r.get("result", {}).get("value")


code = 1
try:
    target = send("Target.createTarget", {"url": "about:blank"})["targetId"]
    session = send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
    send("Emulation.setDeviceMetricsOverride", {"width": w, "height": h, "deviceScaleFactor": 1, "mobile": False}, session)
    if a.downloads:
        send("Browser.setDownloadBehavior", {"behavior": "allow", "downloadPath": os.path.abspath(a.downloads)})
    start = time.time()
    send("Page.navigate", {"url": a.url}, session)
    exit_code = None
    to_open = list(a.open)
    while time.time() - start < a.timeout:
        time.sleep(0.5)
        exit_code = evaluate(session, "document.body && document.body.getAttribute('data-exit')")
        if exit_code is not None:
            break
        # The page runs once its status line is cleared; then the files, one a second.
        if to_open and evaluate(session, "(document.getElementById('status') || {}).textContent") == "":
            doc = send("DOM.getDocument", {}, session)["root"]["nodeId"]
            node = send("DOM.querySelector", {"nodeId": doc, "selector": "#open-file"}, session)["nodeId"]
            send("DOM.setFileInputFiles", {"nodeId": node, "files": [os.path.abspath(to_open.pop(0))]}, session)
            time.sleep(0.5)
        if a.drop and evaluate(session, "(document.getElementById('status') || {}).textContent") == "":
            data = {"items": [], "files": [os.path.abspath(a.drop.pop(0))], "dragOperationsMask": 1}
            for t in ("dragEnter", "dragOver", "drop"):
                send("Input.dispatchDragEvent", {"type": t, "x": w // 2, "y": h // 2, "data": data}, session)
            time.sleep(0.5)
    if to_open:
        print("page_run: %d files not opened: the page ended first" % len(to_open))
    wall = time.time() - start
    if a.downloads:   # the page's last downloads (written as it finished) land on disk
        for _ in range(40):
            time.sleep(0.25)
            names = os.listdir(a.downloads)
            if names and not any(n.endswith(".crdownload") for n in names):
                break
    status = evaluate(session, "(document.getElementById('status') || {}).textContent") or ""
    state = evaluate(session, "(document.getElementById('state-json') || {}).textContent") or ""
    text_log = evaluate(session, "(document.getElementById('log') || {}).textContent") or ""
    open(os.path.join(a.out, "state.json"), "w").write(state)
    open(os.path.join(a.out, "log.txt"), "w").write(text_log)
    if a.screenshot:
        shot = send("Page.captureScreenshot", {"format": "png"}, session)
        open(a.screenshot, "wb").write(base64.b64decode(shot["data"]))
    print("page_run: exit %s after %.1f s%s" % (exit_code, wall, (", status: " + status) if status.strip() else ""))
    code = 0 if exit_code == "0" and not to_open else 1
finally:
    try:
        send("Browser.close")
    except SystemExit:
        pass
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()
    subprocess.run(["rm", "-rf", profile])
sys.exit(code)
