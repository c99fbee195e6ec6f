"""The figures in a real browser: headless Chromium through chromedriver
(Selenium 4, launched as tests/browser/explorer.py launches it), each
committed SVG (docs/accuracy.svg, docs/validation/*.svg) from file:// and
sweep plots from a running service on loopback.

Usage: python plots.py BASE_URL [--screenshots DIR]

Checks, per figure, on the laid-out SVG: a <title> and a <desc>; no <style>
element and no style attribute (the explorer inlines sweep plots under a
Content-Security-Policy without inline styles); every text element inside the
viewport; no two text elements overlapping (tick labels, axis names, titles,
legend lines); the legend box outside the plot area and over no data marker;
text colours at 4.5:1 or more on white. A sweep plot is also put into the
explorer page and must raise no policy violation. Saves one PNG per figure to
docs/screenshots/plots/. Every wait is bounded. Exits non-zero on any failure.
"""

import argparse
import glob
import json
import os
import shutil
import sys
import tempfile
import time
import urllib.parse
import urllib.request

from selenium.common.exceptions import TimeoutException
from selenium.webdriver.common.by import By

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from explorer import start_browser, viewport, wait  # noqa: E402  (the same browser, the same flags)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FAILURES = []

# Measures the laid-out figure in the page's own coordinates (CSS px; the SVG
# is shown at its own size, so these are its user units).
MEASURE = r"""
const svg = document.querySelector('svg');
const root = svg.getBoundingClientRect();
const box = (el) => { const r = el.getBoundingClientRect();
  return {x0: r.left - root.left, y0: r.top - root.top, x1: r.right - root.left, y1: r.bottom - root.top}; };
const part = (name) => svg.querySelector(`[data-part="${name}"]`);
const texts = [...svg.querySelectorAll('text')].map((t) => ({
  text: t.textContent.trim(), part: (t.closest('[data-part]') || {dataset: {}}).dataset.part || t.dataset.part || '',
  fill: t.getAttribute('fill'), box: box(t)}));
const frame = part('frame') && part('frame').querySelector('rect');
const legend = svg.querySelector('[data-part="legend-box"]');
const markers = part('markers') ? [...part('markers').querySelectorAll('circle, rect, path')].map(box) : [];
return JSON.stringify({
  width: root.width, height: root.height,
  title: !!svg.querySelector(':scope > title') && svg.querySelector(':scope > title').textContent.trim().length > 0,
  desc: !!svg.querySelector(':scope > desc') && svg.querySelector(':scope > desc').textContent.trim().length > 0,
  style: svg.querySelectorAll('style, [style]').length,
  texts, frame: frame ? box(frame) : null, legend: legend ? box(legend) : null, markers,
  curves: part('curves') ? part('curves').querySelectorAll('path').length : 0,
});
"""


def check(name, condition, detail=""):
    print(("ok   " if condition else "FAIL ") + name + (f": {detail}" if detail and not condition else ""), flush=True)
    if not condition:
        FAILURES.append(name)
    return condition


def overlap(a, b, slack=0.5):
    return a["x0"] < b["x1"] - slack and b["x0"] < a["x1"] - slack and a["y0"] < b["y1"] - slack and b["y0"] < a["y1"] - slack


def contrast(hex_color):
    rgb = [int(hex_color[i:i + 2], 16) / 255 for i in (1, 3, 5)]
    lum = sum(w * (c / 12.92 if c <= 0.03928 else ((c + 0.055) / 1.055) ** 2.4) for w, c in zip((0.2126, 0.7152, 0.0722), rgb))
    return 1.05 / (lum + 0.05)


def size_of(path):
    with open(path, encoding="utf-8") as f:
        head = f.read(400)
    grab = lambda name: float(head.split(f'{name}="', 1)[1].split('"', 1)[0])
    return int(round(grab("width"))), int(round(grab("height")))


def examine(driver, name, path, shots):
    """Loads one SVG file, checks its layout and saves its PNG."""
    width, height = size_of(path)
    viewport(driver, width, height, mobile=False)
    driver.get("file://" + path)
    wait(driver, lambda d: d.find_elements(By.TAG_NAME, "svg"), f"{name} loaded", timeout=10)
    m = json.loads(driver.execute_script(MEASURE))
    check(f"{name}: a <title> and a <desc>", m["title"] and m["desc"])
    check(f"{name}: no <style> and no style attribute", m["style"] == 0, f"{m['style']} found")
    outside = [t["text"] for t in m["texts"]
               if t["box"]["x0"] < -0.5 or t["box"]["y0"] < -0.5
               or t["box"]["x1"] > m["width"] + 0.5 or t["box"]["y1"] > m["height"] + 0.5]
    check(f"{name}: every text inside the figure", not outside, repr(outside))
    texts = m["texts"]
    clashes = [(a["text"], b["text"]) for i, a in enumerate(texts) for b in texts[i + 1:] if overlap(a["box"], b["box"])]
    check(f"{name}: no two texts overlap", not clashes, repr(clashes[:5]))
    ticks = [t for t in texts if t["part"] in ("x-ticks", "y-ticks")]
    check(f"{name}: tick labels on both axes", any(t["part"] == "x-ticks" for t in ticks) and any(t["part"] == "y-ticks" for t in ticks))
    low = sorted({t["fill"] for t in texts if not t["fill"] or contrast(t["fill"]) < 4.5})
    check(f"{name}: text contrast at least 4.5:1", not low, repr(low))
    if m["legend"]:
        check(f"{name}: the legend is outside the plot area", not overlap(m["legend"], m["frame"], slack=0), json.dumps([m["legend"], m["frame"]]))
        hidden = sum(1 for b in m["markers"] if overlap(b, m["legend"], slack=0))
        check(f"{name}: the legend hides no data marker", hidden == 0, f"{hidden} under it")
    shot = os.path.join(shots, name + ".png")
    driver.find_element(By.TAG_NAME, "svg").screenshot(shot)
    check(f"{name}: screenshot saved", os.path.getsize(shot) > 5000)
    return m


def sweep_svg(base, body):
    request = urllib.request.Request(
        base + "/v1/sweeps", data=json.dumps(body).encode(), method="POST",
        headers={"content-type": "application/json", "accept": "image/svg+xml"})
    with urllib.request.urlopen(request, timeout=20) as response:
        return response.read().decode()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("base")
    parser.add_argument("--screenshots", default=os.path.join(ROOT, "docs", "screenshots", "plots"))
    args = parser.parse_args()
    base = args.base.rstrip("/")
    host = urllib.parse.urlparse(base).hostname
    if host not in ("127.0.0.1", "localhost", "::1"):
        sys.exit(f"refusing a non-loopback target: {host}")
    os.makedirs(args.screenshots, exist_ok=True)

    started = time.monotonic()
    work = tempfile.mkdtemp(prefix="plots-")
    profile = os.path.join(work, "profile")
    figures = [("accuracy", os.path.join(ROOT, "docs", "accuracy.svg"))]
    figures += [("validation-" + os.path.basename(p)[:-4], p)
                for p in sorted(glob.glob(os.path.join(ROOT, "docs", "validation", "*.svg")))]
    check("the committed figures are there", len(figures) >= 12, f"{len(figures)} found")

    # Sweep plots from the service: the paper's Figure 2 (one series: regime
    # bands) and Maw's disc at three friction coefficients (switch markers).
    with open(os.path.join(ROOT, "examples", "figure2_coulomb_friction.json"), encoding="utf-8") as f:
        figure2 = json.load(f)
    with open(os.path.join(ROOT, "examples", "figure3_tangential_restitution_maw.json"), encoding="utf-8") as f:
        three = json.load(f)
    three["axes"] = [{"path": "/velocity/tangential", "linspace": {"start": -1.0, "stop": 5.0, "count": 121}},
                     {"path": "/friction", "values": [0.1, 0.123, 0.2]}]
    three["outputs"] = ["/contact_velocity/final/tangential"]
    sweeps = {}
    for name, body in [("sweep-figure2", figure2), ("sweep-three-frictions", three)]:
        svg = sweep_svg(base, body)
        path = os.path.join(work, name + ".svg")
        with open(path, "w", encoding="utf-8") as f:
            f.write(svg)
        figures.append((name, path))
        sweeps[name] = svg

    driver = start_browser(profile)
    try:
        measured = {}
        for name, path in figures:
            measured[name] = examine(driver, name, path, args.screenshots)
        bands = sweeps["sweep-figure2"]
        check("Figure 2 sweep: sticking and sliding bands in the legend",
              'data-label="sticking"' in bands and 'data-label="sliding"' in bands and ">regime: sliding<" in bands)
        check("Figure 2 sweep: axes with symbol and unit",
              "tangential velocity v<tspan" in bands and "> (m/s)</tspan>" in bands)
        check("three-friction sweep: three curves and regime switches marked",
              measured["sweep-three-frictions"]["curves"] == 3 and len(measured["sweep-three-frictions"]["markers"]) >= 6)
        check("Chung & Ooi Test 6 β: every cited point drawn",
              len(measured["validation-chung_ooi_test6_beta"]["markers"]) == 34,
              str(len(measured["validation-chung_ooi_test6_beta"]["markers"])))

        # The sweep plot inlined in the explorer, as sweep.js does: no policy violation.
        viewport(driver, 1280, 900, mobile=False)
        driver.get(base + "/")
        wait(driver, lambda d: d.execute_script("return document.readyState") == "complete", "the explorer page")
        violations = driver.execute_async_script(
            "const [svg, done] = arguments; const seen = [];"
            "document.addEventListener('securitypolicyviolation', (e) => seen.push(e.violatedDirective));"
            "const doc = new DOMParser().parseFromString(svg, 'image/svg+xml');"
            "const node = document.importNode(doc.documentElement, true);"
            "document.getElementById('sweep-plot').replaceChildren(node);"
            "document.getElementById('sweep-figure').hidden = false;"
            "requestAnimationFrame(() => setTimeout(() => done(seen), 200));", bands)
        check("the sweep plot inlined in the explorer raises no policy violation", violations == [], repr(violations))
    except TimeoutException as error:
        check("every wait within its bound", False, str(error))
    finally:
        driver.quit()
        shutil.rmtree(work, ignore_errors=True)
    took = time.monotonic() - started
    check("the plots check took under two minutes", took < 120, f"{took:.1f} s")
    print(f"plots test took {took:.1f} s")
    print(f"{len(FAILURES)} failed" if FAILURES else "all plot checks passed")
    sys.exit(1 if FAILURES else 0)


if __name__ == "__main__":
    main()
