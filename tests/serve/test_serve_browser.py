#!/usr/bin/env python3
"""ctest serve_browser: `hilite serve`'s page in headless Chromium (Debian's chromium, chromium-driver,
python3-selenium).

Loads the page, moves the incidence slider 20 times (value set, input event dispatched) and times each move
to the updated views and aspect (performance.now() in the page: median and 95th percentile printed, never
asserted), compares the displayed aspects with `hilite measure --json` for the same values to 1e-6, loads a
result folder that `hilite run` wrote, checks that the two views of each side are not blank and takes a
screenshot (written to SCREENSHOT.png when given: docs/serve.png is one), switches B's model and compares again.
Exit 77 (skipped) naming what is missing when Chromium, its driver or Selenium is not installed.
Usage: test_serve_browser.py HILITE [SCREENSHOT.png]"""
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(__file__))
from serve_fixture import measure_cli, server, wait_for  # noqa: E402

HILITE = sys.argv[1]
SHOT = sys.argv[2] if len(sys.argv) > 2 else None
CHROMIUM, DRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"

missing = [p for p in (CHROMIUM, DRIVER) if not os.path.exists(p)]
try:
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
except ImportError:
    missing.append("python3-selenium (import selenium)")
if missing:
    print("serve_browser: skipped, missing: " + ", ".join(missing) + " (apt-get install chromium chromium-driver "
          "python3-selenium, or scripts/quickstart test)")
    sys.exit(77)

TINY = """[experiment]
name = "tiny"
title = "serve_browser's result folder"
description = "two configurations"
[scene.camera]
size = "64"
[[sweep]]
key = "light.incidence"
values = [0, 60]
[[plot]]
file = "aspect.png"
title = "aspect"
x = "incidence_deg"
y = "aspect"
series = "model"
"""


def main():
    tmp = tempfile.mkdtemp(prefix="hilite-serve-browser-")
    results = os.path.join(tmp, "results")
    os.makedirs(results)
    env = dict(os.environ, MESA_SHADER_CACHE_DISABLE="true")
    with open(os.path.join(tmp, "tiny.toml"), "w") as f:
        f.write(TINY)
    subprocess.run([HILITE, "run", os.path.join(tmp, "tiny.toml"), "-o", os.path.join(results, "tiny")], check=True,
                   env=env, stdout=subprocess.DEVNULL)
    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1400,1100",
              f"--user-data-dir={tmp}/profile"):
        opts.add_argument(a)
    driver = None
    failures = []

    def check(cond, what):
        if not cond:
            failures.append(what)
            print("FAIL:", what)

    try:
        with server(HILITE, results=results) as (base, _, proc):
            driver = webdriver.Chrome(service=Service(DRIVER), options=opts)
            driver.set_script_timeout(60)
            driver.get(base + "/")
            js = driver.execute_script
            wait_for(lambda: js("return document.body.dataset.ready === 'true'"), 60, "the page's first update")

            def move(value):
                seq = int(js("return document.getElementById('status').dataset.seq"))
                js("const s = document.getElementById('incidence'); s.value = arguments[0];"
                   "s.dispatchEvent(new Event('input'));", str(value))
                wait_for(lambda: js("const s = document.getElementById('status').dataset;"
                                    "return Number(s.seq) > arguments[0] && s.incidence === arguments[1]",
                                    seq, str(value)), 60, f"the update for incidence {value}")
                return js("return window.hilite.latencies[window.hilite.latencies.length - 1]")

            def compare(side, what):
                aspect = js(f"return document.getElementById('aspect-{side}').dataset.aspect")
                values = js(f"return JSON.parse(document.getElementById('aspect-{side}').dataset.values)")
                row = measure_cli(HILITE, values)
                ok = abs(float(aspect) - row["aspect"]) <= 1e-6
                print(f"{what}, {side.upper()} {values.get('model')}: page aspect {aspect}, CLI {row['aspect']!r}")
                check(ok, f"{what}: {side.upper()}'s aspect {aspect} vs hilite measure {row['aspect']}")

            latencies = [move(v) for v in [x * 4 + 2.5 for x in range(20)]]
            lat = sorted(latencies)
            p95 = lat[min(len(lat) - 1, int(round(0.95 * (len(lat) - 1))))]
            print(f"latency slider -> both views and aspects at 256^2 over {len(lat)} moves: median "
                  f"{statistics.median(lat):.1f} ms, p95 {p95:.1f} ms (min {lat[0]:.1f}, max {lat[-1]:.1f})")
            move(37.5)
            compare("a", "incidence 37.5")
            compare("b", "incidence 37.5")
            check(js("return document.getElementById('aspect-a').dataset.aspect") !=
                  js("return document.getElementById('aspect-b').dataset.aspect"), "the two sides differ")

            # A result folder.
            js("const f = document.getElementById('results-folder'); f.value = 'tiny';"
               "f.dispatchEvent(new Event('change'));")
            wait_for(lambda: js("return document.querySelectorAll('#results-table tbody tr').length === 2 && "
                                "[...document.querySelectorAll('#results-pictures img')].some(i => i.naturalWidth > 0)"),
                     60, "the result folder's table and pictures")

            # The views are not blank: pixel statistics of the four canvases, then a screenshot.
            for cid in ("photo-a", "measure-a", "photo-b", "measure-b"):
                mean, spread, lit = js(
                    "const c = document.getElementById(arguments[0]);"
                    "const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;"
                    "let s = 0, s2 = 0, lit = 0, n = d.length / 4;"
                    "for (let i = 0; i < d.length; i += 4) { const v = (d[i] + d[i+1] + d[i+2]) / 3;"
                    "  s += v; s2 += v * v; if (v > 64) lit++; }"
                    "const m = s / n; return [m, Math.sqrt(Math.max(0, s2 / n - m * m)), lit];", cid)
                print(f"#{cid}: mean {mean:.1f}, std {spread:.1f}, {lit} pixels above 64")
                check(spread > 3 and lit > 20, f"#{cid} looks blank (mean {mean:.1f}, std {spread:.1f}, lit {lit})")
            js("window.scrollTo(0, 0)")
            png = driver.get_screenshot_as_png()
            check(len(png) > 20000, f"the screenshot is {len(png)} bytes (blank?)")
            if SHOT:
                with open(SHOT, "wb") as f:
                    f.write(png)
                print("screenshot:", SHOT)

            # Switch B's model.
            seq = int(js("return document.getElementById('status').dataset.seq"))
            js("const m = document.getElementById('p-b-model'); m.value = 'beckmann';"
               "m.dispatchEvent(new Event('change'));")
            wait_for(lambda: js("return Number(document.getElementById('status').dataset.seq) > arguments[0] && "
                                "JSON.parse(document.getElementById('aspect-b').dataset.values).model === 'beckmann'",
                                seq), 60, "the update after switching B to beckmann")
            compare("b", "B switched to beckmann")
            compare("a", "A matched to beckmann")

            errors = [e for e in driver.get_log("browser") if e.get("level") == "SEVERE"] if hasattr(driver, "get_log") else []
            check(not errors, f"the page logged errors: {errors}")
            check(proc.poll() is None, "the server is alive")
    finally:
        if driver is not None:
            driver.quit()
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"serve_browser: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
