"""The explorer page in a real browser: headless Chromium through chromedriver
(Selenium 4), against a running service on loopback.

Usage: python explorer.py BASE_URL --axe PATH/axe.min.js [--screenshots DIR]

Checks: the form's fields and ranges against openapi/openapi.json; the Maw
disc (oblique) computed in the page equal to the API's own answer; refusals
marking the field the problem's pointer names (aria-invalid, the detail next
to it); every case and the two-body presets computed; a sweep plotted (the
service's SVG) and downloaded; a tangential and a torsional fit; spatial
fits generated from the scene (the cube on a board; two DEM spheres with a
twist law) whose coefficients are the scene's, and their refusals marking a
CSV row, the law, the Impact section's field; the state
restored from the URL; "copy as curl" run and "copy as Python" compiled;
keyboard-only use (Tab through the Maw form, Enter submits); axe-core with no
serious or critical violation; no script error and no policy violation in
the console; no horizontal scroll at a 390 px phone width; screenshots at
1280x900 and 390x844. Every wait is bounded. Exits non-zero on any failure.
"""

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.parse
import urllib.request

from selenium import webdriver
from selenium.common.exceptions import TimeoutException
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import Select, WebDriverWait

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FAILURES = []
WAIT = 15  # seconds, for any one thing the page does


def check(name, condition, detail=""):
    print(("ok   " if condition else "FAIL ") + name + (f": {detail}" if detail and not condition else ""), flush=True)
    if not condition:
        FAILURES.append(name)
    return condition


def api(base, path, body, accept="application/json"):
    """POSTs JSON with urllib; answers (status, parsed JSON or text)."""
    request = urllib.request.Request(
        base + path, data=json.dumps(body).encode(), method="POST",
        headers={"content-type": "application/json", "accept": accept})
    try:
        with urllib.request.urlopen(request, timeout=20) as response:
            text = response.read().decode()
            return response.status, json.loads(text) if "json" in response.headers.get("content-type", "") else text
    except urllib.error.HTTPError as error:
        return error.code, json.loads(error.read().decode())


def leaves(value, pointer=""):
    if isinstance(value, dict):
        return [leaf for k, v in value.items() for leaf in leaves(v, f"{pointer}/{k}")]
    if isinstance(value, list):
        return [leaf for i, v in enumerate(value) for leaf in leaves(v, f"{pointer}/{i}")]
    return [(pointer, value)]


# --- the browser ------------------------------------------------------------

def start_browser(profile):
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in [
        "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
        "--disable-background-networking", "--disable-component-update", "--disable-sync",
        "--no-first-run", "--no-default-browser-check", "--disable-extensions",
        "--disable-domain-reliability", "--disable-client-side-phishing-detection",
        "--metrics-recording-only", "--password-store=basic",
        "--no-pings", "--disable-features=MediaRouter,OptimizationHints,Translate,AutofillServerCommunication",
        # Only loopback: no name resolves to anything else, and anything not
        # on loopback would go to a closed loopback port (Chromium never
        # proxies loopback itself).
        "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1, EXCLUDE localhost",
        "--proxy-server=http://127.0.0.1:9",
        f"--user-data-dir={profile}", "--window-size=1280,900",
    ]:
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    options.add_experimental_option("prefs", {
        "download.default_directory": os.path.join(profile, "downloads"),
        "download.prompt_for_download": False,
    })
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    driver.set_page_load_timeout(30)
    driver.set_script_timeout(30)
    driver.execute_cdp_cmd("Browser.setDownloadBehavior", {
        "behavior": "allow", "downloadPath": os.path.join(profile, "downloads")})
    viewport(driver, 1280, 900, mobile=False)
    return driver


def viewport(driver, width, height, mobile):
    driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride", {
        "width": width, "height": height, "deviceScaleFactor": 1, "mobile": mobile})


def wait(driver, condition, what, timeout=WAIT):
    try:
        return WebDriverWait(driver, timeout, poll_frequency=0.05).until(lambda d: condition(d))
    except TimeoutException:
        check(f"wait for {what}", False, f"not within {timeout} s")
        raise


def seq(driver):
    return int(driver.find_element(By.ID, "outcome-status").get_attribute("data-seq") or "0")


def wait_outcome(driver, after, what):
    """Waits for an outcome computed after `after` (its sequence number)."""
    wait(driver, lambda d: seq(d) > after and d.find_elements(By.CSS_SELECTOR, "#outcome tbody tr"), what)


def displayed(driver):
    """The outcome table: pointer -> the value as the page shows it for copying."""
    return driver.execute_script(
        "return Object.fromEntries([...document.querySelectorAll('#outcome tbody tr')]"
        ".map(tr => [tr.dataset.pointer, tr.querySelector('td.num').dataset.value]))")


def page_state(driver):
    return driver.execute_script("return window.explorer.state()")


def same_outcome(name, shown, answer):
    expected = leaves(answer)
    ok = check(f"{name}: one row per output", len(shown) == len(expected), f"{len(shown)} rows, {len(expected)} outputs")
    for pointer, value in expected:
        text = shown.get(pointer)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            good = text is not None and float(text) == float(value)
        else:
            good = text == ("null" if value is None else str(value))
        if not good:
            ok = check(f"{name}: {pointer}", False, f"page {text}, API {value}")
    if ok:
        check(f"{name}: every output equals the API's", True)


def set_field(driver, element_id, text):
    field = driver.find_element(By.ID, element_id)
    field.send_keys(Keys.CONTROL, "a")
    field.send_keys(Keys.DELETE)
    field.send_keys(text)
    return field


def choose_preset(driver, preset):
    before = seq(driver)
    select = Select(driver.find_element(By.ID, "preset"))
    if select.first_selected_option.get_attribute("value") == preset:
        select.select_by_value("")  # the page opens on the Maw disc: choose it anew
    select.select_by_value(preset)
    wait_outcome(driver, before, f"the {preset} outcome")


def run_axe(driver, axe_source, where):
    driver.execute_script(axe_source)
    result = driver.execute_async_script(
        "const done = arguments[arguments.length - 1];"
        "axe.run(document, {resultTypes: ['violations']})"
        ".then(r => done(JSON.stringify(r.violations))).catch(e => done(JSON.stringify({error: String(e)})));")
    violations = json.loads(result)
    if isinstance(violations, dict):
        check(f"axe-core ran ({where})", False, violations["error"])
        return
    bad = [v for v in violations if v["impact"] in ("serious", "critical")]
    for v in bad:
        targets = [n["target"] for n in v["nodes"]][:5]
        print(f"     {v['impact']} {v['id']}: {v['help']} {targets}")
    minor = sorted({f"{v['id']} ({v['impact']})" for v in violations if v not in bad})
    check(f"axe-core: no serious or critical violation ({where})", not bad, ", ".join(v["id"] for v in bad))
    if minor:
        print(f"     (minor: {', '.join(minor)})")


# --- the fields against the OpenAPI document ---------------------------------

def resolve(doc, schema):
    while "$ref" in schema:
        schema = doc["components"]["schemas"][schema["$ref"].split("/")[-1]]
    return schema


def member(doc, schema, key):
    """The schema of `key` under `schema` (through refs, oneOf, arrays)."""
    schema = resolve(doc, schema)
    if key.isdigit() and "items" in schema:
        return resolve(doc, schema["items"])
    for variant in [schema] + [resolve(doc, s) for s in schema.get("oneOf", []) + schema.get("anyOf", [])]:
        props = variant.get("properties", {})
        if key in props:
            return resolve(doc, props[key])
        for inner in variant.get("oneOf", []):
            inner = resolve(doc, inner)
            if key in inner.get("properties", {}):
                return resolve(doc, inner["properties"][key])
    return None


def check_fields(driver, doc):
    cases = driver.execute_script("return window.explorer.fields()")
    request_schema = {
        path: op["post"]["requestBody"]["content"]["application/json"]["schema"]
        for path, op in doc["paths"].items() if path.startswith("/v1/impacts/")}
    check("every impact endpoint has a case", sorted(c["endpoint"] for c in cases) == sorted(request_schema))
    problems = []
    for case in cases:
        for field in case["fields"]:
            schema = request_schema[case["endpoint"]]
            for key in field["path"].strip("/").split("/"):
                schema = member(doc, schema, key) if schema is not None else None
            if schema is None:
                problems.append(f"{case['id']} {field['path']}: not in the schema")
                continue
            types = schema.get("type")
            types = types if isinstance(types, list) else [types]
            if field["type"] == "checkbox":
                if "boolean" not in types:
                    problems.append(f"{case['id']} {field['path']}: not a boolean")
                continue
            if "number" not in types:
                problems.append(f"{case['id']} {field['path']}: not a number ({types})")
            rng = field["range"]
            expect = {}
            if "minimum" in schema:
                expect.update(min=schema["minimum"], exclusiveMin=False)
            if "exclusiveMinimum" in schema:
                expect.update(min=schema["exclusiveMinimum"], exclusiveMin=True)
            if "maximum" in schema:
                expect.update(max=schema["maximum"], exclusiveMax=False)
            if "exclusiveMaximum" in schema:
                expect.update(max=schema["exclusiveMaximum"], exclusiveMax=True)
            got = {"min": rng.get("min"), "max": rng.get("max"),
                   "exclusiveMin": bool(rng.get("exclusiveMin")), "exclusiveMax": bool(rng.get("exclusiveMax"))}
            want = {"min": expect.get("min"), "max": expect.get("max"),
                    "exclusiveMin": expect.get("exclusiveMin", False), "exclusiveMax": expect.get("exclusiveMax", False)}
            if got != want:
                problems.append(f"{case['id']} {field['path']}: page {got}, schema {want}")
    count = sum(len(c["fields"]) for c in cases)
    check(f"the form's {count} fields carry the API's names and ranges", not problems, "; ".join(problems))


# --- the spatial fit ---------------------------------------------------------

def fit_cells(driver):
    """The fit table: API name -> [value, standard error] as the page holds them."""
    return driver.execute_script(
        "return Object.fromEntries([...document.querySelectorAll('#fit-table tbody tr')]"
        ".map(tr => [tr.querySelector('code').textContent,"
        " [...tr.querySelectorAll('td.num')].map(td => td.dataset.value)]))")


def fit_lines(driver):
    return driver.find_element(By.ID, "fit-csv").get_attribute("value").splitlines()


def run_fit(driver, what, refused=False):
    driver.find_element(By.ID, "fit-run").click()
    done = "The service refused" if refused else "Fitted"
    wait(driver, lambda d: d.find_element(By.ID, "fit-status").text.startswith(done), f"{what}: the fit")


def sample_from_scene(driver, what):
    Select(driver.find_element(By.ID, "fit-kind")).select_by_value("spatial")
    driver.execute_script("document.getElementById('fit-status').textContent = ''")
    driver.find_element(By.ID, "fit-sample").click()
    wait(driver, lambda d: "press Fit" in d.find_element(By.ID, "fit-status").text, f"{what}: data from the scene")
    return fit_lines(driver)


def csv_request(scene, law, lines):
    """The spatial fit's request for one impact of `scene` from CSV `lines`."""
    header = lines[0].split(",")
    measured = []
    for line in lines[1:]:
        change = {}
        for column, cell in zip(header, line.split(",")):
            if column != "impact":
                vector, component, part = column.split(".")
                change.setdefault(vector, {}).setdefault(component, {})[part] = float(cell)
        measured.append(change)
    return {"law": law, "impacts": [{"bodies": scene["bodies"], "contact": scene["contact"], "measured": measured}]}


def has_member(doc, schema, keys):
    for key in keys:
        schema = member(doc, schema, key) if schema is not None else None
    return schema is not None


def edit_scene(driver, what, edits):
    """Types `edits` (field id -> text) into the Impact section and waits for the outcome."""
    before = seq(driver)
    for field_id, text in edits.items():
        set_field(driver, field_id, text)
    driver.find_element(By.ID, "compute").click()
    wait_outcome(driver, before, f"{what}: the edited outcome")


def generate_from_scene(driver, base, doc, what, law):
    """"Generate from the scene": the CSV holds the service's own ΔV and Δω
    of the Impact section's scene (to 8 digits), one row per body, under
    columns that are members of the API's measured change. Answers the
    scene and the CSV's lines."""
    scene = page_state(driver)["request"]
    lines = sample_from_scene(driver, what)
    got = driver.find_element(By.ID, "fit-law").get_attribute("value")
    check(f"{what}: the spatial fit's law is the scene's", got == law, got)
    header, rows = lines[0].split(","), [[float(x) for x in line.split(",")] for line in lines[1:]]
    status, answer = api(base, "/v1/impacts/spatial", scene)
    check(f"{what}: one CSV row per body", status == 200 and len(rows) == len(answer["bodies"]) == len(scene["bodies"]), str(lines))
    schema = resolve(doc, doc["components"]["schemas"]["SpatialMeasuredChangeDto"])
    unknown = [c for c in header[1:] if not has_member(doc, schema, c.split("."))]
    check(f"{what}: the CSV's columns are the API's", header[0] == "impact" and not unknown, str(unknown))
    far = []
    for row, body in zip(rows, answer["bodies"]):
        for column, value in zip(header, row):
            parts = column.split(".")
            if parts[-1] == "value" and abs(value - body[parts[0]][parts[1]]) > 1e-7 * abs(body[parts[0]][parts[1]]):
                far.append(f"{column}: {value} vs {body[parts[0]][parts[1]]}")
    check(f"{what}: the CSV holds the scene's ΔV and Δω", not far, "; ".join(far))
    return scene, lines


def fit_equals_scene(driver, what, expected, bodies, impacts=1):
    """Fits the CSV: the coefficients are `expected` (to the data's 8
    digits), χ² is the rounding's, and each impact has its regimes and 6
    residuals per body."""
    run_fit(driver, what)
    cells = fit_cells(driver)
    for name, value in expected["coefficients"].items():
        got = float(cells.get(name, ["nan"])[0])
        check(f"{what}: the fit finds the scene's {name} = {value}", abs(got - value) <= 1e-6 * max(1.0, abs(value)), f"{got} ({cells})")
        se = cells.get(name, ["nan", "nan"])[1]
        check(f"{what}: {name} has its standard error", se == "" or float(se) > 0, se)
    fitted = sorted(n for n in cells if not n.startswith(("chi_squared", "degrees_of_freedom", "impacts")))
    check(f"{what}: nothing else is fitted", fitted == sorted(expected["coefficients"]), str(fitted))
    chi2 = float(cells.get("chi_squared", ["nan"])[0])
    check(f"{what}: χ² is the rounding's (< 1e-6)", chi2 < 1e-6, str(chi2))
    dof = int(cells.get("degrees_of_freedom", ["-1"])[0])
    check(f"{what}: the degrees of freedom are the data's less the coefficients",
          dof == 6 * bodies * impacts - len(expected["coefficients"]), str(dof))
    for i in range(impacts):
        residuals = cells.get(f"impacts[{i}].residuals", [""])[0].split(", ")
        check(f"{what}: impact {i}'s residuals, 6 per body", len(residuals) == 6 * bodies, str(residuals))
        for key, regimes in expected["regimes"].items():
            got = cells.get(f"impacts[{i}].{key}", [""])[0]
            check(f"{what}: impact {i}'s {key}", got == regimes[i], got)
    return cells


def check_spatial_fits(driver, base, doc):
    # The cube of the preset, one body sliding on the board: e and f.
    choose_preset(driver, "cube-corner")
    scene, lines = generate_from_scene(driver, base, doc, "cube-corner", "friction")
    fit_equals_scene(driver, "cube-corner", {
        "coefficients": {"restitution": 0.28, "friction": 0.17}, "regimes": {"regime": ["sliding"]}}, bodies=1)
    # Labelled from the quantity table, as the outcome is.
    quantities = json.load(urllib.request.urlopen(base + "/assets/quantities.json", timeout=20))
    names = {q["path"]: q["name"] for c in quantities["cases"] for q in c["inputs"]}
    labels = driver.execute_script(
        "return Object.fromEntries([...document.querySelectorAll('#fit-table tbody tr')]"
        ".map(tr => [tr.querySelector('code').textContent, tr.querySelector('th').textContent]))")
    check("the spatial fit's coefficients are labelled from the quantity table",
          names["/restitution"] in labels.get("restitution", "") and names["/friction"] in labels.get("friction", ""), str(labels))

    # A cell that is not a number: the refusal names its row and member.
    csv = driver.find_element(By.ID, "fit-csv")
    cells = lines[1].split(",")
    cells[1] = "abc"
    driver.execute_script("arguments[0].value = arguments[1]", csv, "\n".join([lines[0], ",".join(cells)]))
    run_fit(driver, "a cell that is not a number", refused=True)
    error = driver.find_element(By.ID, "fit-csv-error").text
    check("a refused spatial row is named: its row and member", csv.get_attribute("aria-invalid") == "true"
          and error.startswith("Row 1 (velocity_change.x.value)"), error)

    # Two DEM spheres sliding, with Coulomb friction: e and f from both bodies' changes.
    choose_preset(driver, "dem-spheres")
    driver.find_element(By.ID, "law-friction").click()
    edit_scene(driver, "dem-spheres", {"f-friction": "0.01"})
    generate_from_scene(driver, base, doc, "dem-spheres", "friction")
    fit_equals_scene(driver, "dem-spheres", {
        "coefficients": {"restitution": 0.9, "friction": 0.01}, "regimes": {"regime": ["sliding"]}}, bodies=2)

    # The cube with a twist law: one impact spins slowly (e_z answers), a
    # second, its own spin in the CSV's angular_velocity.z column, fast (μ_z
    # caps it); together they give e, f, e_z and μ_z.
    choose_preset(driver, "cube-corner")
    driver.find_element(By.ID, "toggle-twist").click()
    edit_scene(driver, "the cube with a twist law", {
        "f-torsion-restitution": "0.3", "f-torsion-friction": "0.4", "f-torsion-pitch_radius": "0.01",
        "f-bodies-0-angular_velocity-z": "3"})
    scene, lines = generate_from_scene(driver, base, doc, "the cube with a twist law", "friction")
    fast = json.loads(json.dumps(scene))
    fast["bodies"][0]["angular_velocity"]["z"] = 30.0
    status, answer = api(base, "/v1/impacts/spatial", fast)
    sigma = lines[1].split(",")[2::2]  # the generated uncertainties
    values = [answer["bodies"][0][v][c] for v in ("velocity_change", "angular_velocity_change") for c in "xyz"]
    row = ["1"] + [x for value, s in zip(values, sigma) for x in (f"{value:.8g}", s)]
    text = "\n".join([lines[0] + ",angular_velocity.z", lines[1] + ",", ",".join(row) + ",30"])
    driver.execute_script("arguments[0].value = arguments[1]", driver.find_element(By.ID, "fit-csv"), text)
    fit_equals_scene(driver, "the cube with a twist law, two impacts", {
        "coefficients": {"restitution": 0.28, "friction": 0.17, "torsion.restitution": 0.3, "torsion.friction": 0.4},
        "regimes": {"regime": ["sliding", "sliding"], "torsional_regime": ["restitution", "sliding"]}}, bodies=1, impacts=2)

    # The DEM spheres as the preset has them (tangential restitution) stick:
    # no impact determines f, refused at /law, which the page marks with the
    # problem's detail.
    choose_preset(driver, "dem-spheres")
    scene, lines = generate_from_scene(driver, base, doc, "the sticking spheres", "tangential_restitution")
    run_fit(driver, "the sticking spheres", refused=True)
    status, problem = api(base, "/v1/fits/spatial", csv_request(scene, "tangential_restitution", lines))
    check("the API refuses the sticking spheres' friction at /law", status == 422 and problem.get("pointer") == "/law", json.dumps(problem))
    law = driver.find_element(By.ID, "fit-law")
    error = driver.find_element(By.ID, "fit-law-error").text
    check("the page marks the law with the problem's detail",
          law.get_attribute("aria-invalid") == "true" and error == problem.get("detail"), error)

    # A refused member of the scene (a negative pitch radius) is marked on the Impact section.
    choose_preset(driver, "tennis-sidespin")
    sample_from_scene(driver, "the sidespin ball")
    set_field(driver, "f-torsion-pitch_radius", "-0.005")
    # The page refuses it as you type; unmark it, so the mark is the fit's.
    wait(driver, lambda d: d.find_element(By.ID, "outcome-status").text.startswith("Refused"), "the refused scene")
    driver.execute_script("document.getElementById('f-torsion-pitch_radius').removeAttribute('aria-invalid')")
    run_fit(driver, "a negative pitch radius", refused=True)
    field = driver.find_element(By.ID, "f-torsion-pitch_radius")
    check("a refused pitch radius is marked on the Impact section", field.get_attribute("aria-invalid") == "true"
          and "/torsion/pitch_radius" in driver.find_element(By.ID, "fit-problem").text, driver.find_element(By.ID, "fit-problem").text)
    set_field(driver, "f-torsion-pitch_radius", "0.005")


# --- the test ----------------------------------------------------------------

def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("base")
    parser.add_argument("--axe", required=True)
    parser.add_argument("--screenshots", default=os.path.join(ROOT, "docs", "screenshots"))
    parser.add_argument("--openapi", default=os.path.join(ROOT, "openapi", "openapi.json"))
    args = parser.parse_args()
    base = args.base.rstrip("/")
    host = urllib.parse.urlparse(base).hostname
    if host not in ("127.0.0.1", "localhost", "::1"):
        sys.exit(f"refusing a non-loopback target: {host}")
    with open(args.axe, encoding="utf-8") as f:
        axe_source = f.read()
    with open(args.openapi, encoding="utf-8") as f:
        doc = json.load(f)
    os.makedirs(args.screenshots, exist_ok=True)

    started = time.monotonic()
    profile = tempfile.mkdtemp(prefix="explorer-chromium-")
    driver = start_browser(profile)
    try:
        run(driver, base, axe_source, doc, args.screenshots, profile)
    except TimeoutException:
        pass  # reported by wait()
    finally:
        console = driver.get_log("browser")
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)
    # Refusals are the service's 4xx answers the test provokes; anything else
    # (a script error, a policy violation) fails.
    noise = [e for e in console if e["level"] == "SEVERE"
             and "the server responded with a status of 4" not in e["message"]]
    for e in noise:
        print(f"     console: {e['message']}")
    check("no script error or policy violation in the console", not noise)
    print(f"browser test took {time.monotonic() - started:.1f} s")
    print(f"{len(FAILURES)} failed" if FAILURES else "all browser checks passed")
    sys.exit(1 if FAILURES else 0)


def run(driver, base, axe_source, doc, shots, profile):
    driver.get(base + "/")
    wait(driver, lambda d: d.execute_script("return document.documentElement.dataset.ready === 'true'"), "the page to start")
    wait_outcome(driver, 0, "the first outcome")
    check("the page's title", "restitution" in driver.title)
    check_fields(driver, doc)

    # The Maw disc, oblique: the page's outcome is the API's.
    choose_preset(driver, "maw-oblique")
    maw = {
        "body": {"mass": 1.0, "inertia": 0.00125},
        "contact": {"tangential_offset": 0.0, "normal_offset": 0.05},
        "velocity": {"normal": -1.0, "tangential": 2.0, "angular": 0.0},
        "restitution": 0.93, "friction": 0.123,
    }
    state = page_state(driver)
    check("the Maw preset fills the oblique form", state["case"] == "oblique" and state["request"] == maw, json.dumps(state["request"]))
    status, answer = api(base, "/v1/impacts/oblique", maw)
    check("the API answers the Maw disc", status == 200)
    same_outcome("Maw disc (oblique)", displayed(driver), answer)
    scene = driver.find_element(By.ID, "scene")
    check("the scene draws the disc and the arrows",
          len(scene.find_elements(By.CSS_SELECTOR, "circle")) >= 3 and len(scene.find_elements(By.CSS_SELECTOR, "line[marker-end]")) >= 4)
    driver.execute_script("document.activeElement.blur()")
    driver.save_screenshot(os.path.join(shots, "explorer-desktop.png"))
    check("desktop screenshot saved", os.path.getsize(os.path.join(shots, "explorer-desktop.png")) > 10000)
    run_axe(driver, axe_source, "Maw outcome")

    # Exact precision: the page sends it and shows the exact answer.
    before = seq(driver)
    driver.find_element(By.CSS_SELECTOR, "input[name='precision'][value='exact']").click()
    wait_outcome(driver, before, "the exact outcome")
    status, exact = api(base, "/v1/impacts/oblique", {**maw, "precision": "exact"})
    same_outcome("Maw disc, exact", displayed(driver), exact)
    driver.find_element(By.CSS_SELECTOR, "input[name='precision'][value='fast']").click()

    # Refusals: restitution 1.5, then a value that is not a number.
    for field_id, text, pointer in [("f-restitution", "1.5", "/restitution"), ("f-velocity-tangential", "NaN", "/velocity/tangential")]:
        set_field(driver, field_id, text)
        driver.find_element(By.ID, "compute").click()
        wait(driver, lambda d: d.find_element(By.ID, field_id).get_attribute("aria-invalid") == "true", f"{field_id} marked invalid")
        request = page_state(driver)["request"]
        status, problem = api(base, "/v1/impacts/oblique", request)
        check(f"{text} is refused by the API at {pointer}", status == 422 and problem.get("pointer") == pointer, json.dumps(problem))
        field = driver.find_element(By.ID, field_id)
        error = driver.find_element(By.ID, f"{field_id}-error")
        check(f"{field_id}: the problem's detail next to the field",
              error.is_displayed() and error.text == problem["detail"], f"{error.text!r} vs {problem['detail']!r}")
        check(f"{field_id}: described by its error", f"{field_id}-error" in field.get_attribute("aria-describedby").split())
        check(f"{field_id}: the outcome is cleared", not driver.find_elements(By.CSS_SELECTOR, "#outcome tbody tr"))
        if text == "1.5":
            run_axe(driver, axe_source, "a refused request")
        set_field(driver, field_id, "0.93" if field_id == "f-restitution" else "2")
    before = seq(driver)
    driver.find_element(By.ID, "compute").click()
    wait_outcome(driver, before, "the outcome after the fix")
    check("the marks go when the request is accepted", not driver.find_elements(By.CSS_SELECTOR, "#impact-form [aria-invalid='true']"))

    # A sweep: the preset's Figure 2 sweep, the service's SVG, downloads.
    driver.find_element(By.ID, "sweep-run").click()
    wait(driver, lambda d: d.find_elements(By.CSS_SELECTOR, "#sweep-plot svg"), "the sweep plot")
    plot = driver.find_element(By.CSS_SELECTOR, "#sweep-plot svg")
    check("the sweep plot is the service's SVG with a curve", len(plot.find_elements(By.CSS_SELECTOR, "polyline, path")) >= 1)
    check("the sweep plotted the preset's 301 points", "301 points" in driver.find_element(By.ID, "sweep-caption").text)
    for accept, ext in [("text/csv", "csv"), ("application/vnd.apache.arrow.stream", "arrow"), ("application/x-ndjson", "ndjson")]:
        driver.find_element(By.CSS_SELECTOR, f"[data-download='{accept}']").click()
        wait(driver, lambda d: f"sweep-oblique.{ext}" in d.find_element(By.ID, "sweep-status").text, f"the {ext} download")
    downloads = os.path.join(profile, "downloads")
    wait(driver, lambda d: os.path.exists(os.path.join(downloads, "sweep-oblique.csv")), "the CSV file", timeout=10)
    with open(os.path.join(downloads, "sweep-oblique.csv"), encoding="utf-8") as f:
        rows = f.read().strip().splitlines()
    check("the CSV download holds the header and 301 rows", len(rows) == 302 and rows[0].startswith("/velocity/tangential"), rows[0])
    # A refused sweep marks the count.
    set_field(driver, "sweep-count", "-3")
    driver.find_element(By.ID, "sweep-run").click()
    wait(driver, lambda d: d.find_element(By.ID, "sweep-count").get_attribute("aria-invalid") == "true", "the point count marked invalid")
    set_field(driver, "sweep-count", "301")
    run_axe(driver, axe_source, "sweep plotted")

    # Every case computes from its defaults, and the two-body presets match the API.
    for case in ["normal", "oblique", "tangential", "torsional", "planar", "spatial"]:
        before = seq(driver)
        Select(driver.find_element(By.ID, "case")).select_by_value(case)
        wait_outcome(driver, before, f"the {case} outcome")
        check(f"{case}: the scene is drawn", len(driver.find_element(By.ID, "scene").find_elements(By.CSS_SELECTOR, "line, circle, polygon")) >= 5)
        if case in ("torsional", "spatial"):
            run_axe(driver, axe_source, f"the {case} form")
    for preset, case in [("spinning-ball", "torsional"), ("cars", "planar"), ("tennis-topspin", "spatial"), ("maw-tangential", "tangential")]:
        choose_preset(driver, preset)
        request = page_state(driver)["request"]
        status, answer = api(base, f"/v1/impacts/{case}", request)
        check(f"{preset}: the API answers the page's request", status == 200)
        same_outcome(preset, displayed(driver), answer)

    # Copy as curl (run) and as Python (compiled).
    driver.execute_script("window.lastCopied = ''")
    driver.find_element(By.ID, "copy-curl").click()
    command = wait(driver, lambda d: d.execute_script("return window.lastCopied"), "the copied curl command")
    check("copy as curl names the endpoint", "/v1/impacts/tangential" in command)
    if shutil.which("curl") and shutil.which("bash"):
        out = subprocess.run(["bash", "-c", command], capture_output=True, text=True, timeout=20)
        check("the copied curl command gives the page's outcome", out.returncode == 0 and json.loads(out.stdout) == answer)
    driver.execute_script("window.lastCopied = ''")
    driver.find_element(By.ID, "copy-python").click()
    program = wait(driver, lambda d: d.execute_script("return window.lastCopied"), "the copied Python program")
    try:
        compile(program, "copied.py", "exec")
        check("copy as Python is a Python program calling the generated client",
              "impacts_tangential.sync" in program and "TangentialRequest.from_dict" in program)
    except SyntaxError as error:
        check("copy as Python compiles", False, str(error))

    # Share: the URL restores the page.
    url = driver.current_url
    shared = page_state(driver)["request"]
    driver.get("about:blank")
    driver.get(url)
    wait(driver, lambda d: d.execute_script("return document.documentElement.dataset.ready === 'true'"), "the shared page")
    wait_outcome(driver, 0, "the shared page's outcome")
    check("the shared URL restores the case and the request",
          page_state(driver)["case"] == "tangential" and page_state(driver)["request"] == shared)

    # Fits: sample data from the service, the coefficients, the fitted line.
    for kind, coefficient, value in [("tangential", "restitution", 0.93), ("torsional", "torsional_restitution", 0.2)]:
        Select(driver.find_element(By.ID, "fit-kind")).select_by_value(kind)
        driver.find_element(By.ID, "fit-sample").click()
        wait(driver, lambda d: "press Fit" in d.find_element(By.ID, "fit-status").text, f"{kind} sample data")
        driver.find_element(By.ID, "fit-run").click()
        wait(driver, lambda d: d.find_element(By.ID, "fit-status").text.startswith("Fitted")
             and d.find_element(By.ID, "fit-figure").is_displayed()
             and d.find_elements(By.CSS_SELECTOR, "#fit-plot svg [data-part=curves] path"), f"the {kind} fit plot")
        markers = driver.find_elements(By.CSS_SELECTOR, "#fit-plot svg [data-part=markers] circle")
        check(f"the {kind} fit plot marks every measured row", len(markers) == len(
            [l for l in driver.find_element(By.ID, "fit-csv").get_attribute("value").splitlines()[1:] if l.strip()]),
            str(len(markers)))
        cells = driver.execute_script(
            "return Object.fromEntries([...document.querySelectorAll('#fit-table tbody tr')]"
            ".map(tr => [tr.querySelector('code').textContent, tr.querySelectorAll('td.num')[0].textContent]))")
        got = float(cells.get(coefficient, "nan").replace("−", "-"))
        check(f"{kind} fit recovers {coefficient} ≈ {value}", abs(got - value) < 0.05, str(cells))
    # A refused fit: too few rows marks the CSV.
    csv = driver.find_element(By.ID, "fit-csv")
    lines = csv.get_attribute("value").splitlines()[:3]
    driver.execute_script("arguments[0].value = arguments[1]", csv, "\n".join(lines))
    driver.find_element(By.ID, "fit-run").click()
    wait(driver, lambda d: d.find_element(By.ID, "fit-csv").get_attribute("aria-invalid") == "true", "the CSV marked invalid")
    check_spatial_fits(driver, base, doc)
    run_axe(driver, axe_source, "fits")

    # Keyboard only: Tab from the first field through the Maw form to
    # Compute; Enter submits.
    driver.get(base + "/?preset=maw-oblique")
    wait_outcome(driver, 0, "the Maw outcome (keyboard)")
    driver.execute_script("document.getElementById('case').focus()")
    visited = []
    active = None
    for _ in range(60):
        active = driver.switch_to.active_element
        ident = active.get_attribute("id")
        visited.append(ident)
        if ident == "compute":
            break
        if ident == "f-velocity-tangential":
            active.send_keys(Keys.CONTROL, "a")
            active.send_keys("1.5")
        active.send_keys(Keys.TAB)
    check("Tab reaches Compute through the form", visited[-1] == "compute", " → ".join(visited))
    labelled = driver.execute_script(
        "return arguments[0].every(id => { const el = document.getElementById(id);"
        " return el && (el.labels && el.labels.length > 0 || el.tagName === 'BUTTON' || el.getAttribute('aria-label')); })",
        [v for v in visited if v])
    check("every control met on the way has a label", labelled and all(visited), " → ".join(map(str, visited)))
    for expected in ["case", "preset", "f-body-mass", "f-body-inertia", "f-velocity-tangential", "f-restitution", "f-friction"]:
        check(f"Tab visits {expected}", expected in visited)
    before = seq(driver)
    active.send_keys(Keys.ENTER)
    wait_outcome(driver, before, "the outcome after Enter")
    request = page_state(driver)["request"]
    check("the typed value is in the request", request["velocity"]["tangential"] == 1.5, json.dumps(request))
    status, answer = api(base, "/v1/impacts/oblique", request)
    same_outcome("keyboard-only Maw disc at v_t = 1.5", displayed(driver), answer)
    # Enter in a field submits too.
    before = seq(driver)
    driver.find_element(By.ID, "f-friction").send_keys(Keys.ENTER)
    wait_outcome(driver, before, "the outcome after Enter in a field")

    # The phone: one column, no horizontal scroll, a screenshot.
    viewport(driver, 390, 844, mobile=True)
    driver.get(base + "/?preset=maw-oblique")
    wait_outcome(driver, 0, "the phone outcome")
    width = driver.execute_script("return [document.documentElement.scrollWidth, window.innerWidth]")
    check("no horizontal scroll at 390 px", width[0] <= width[1], str(width))
    run_axe(driver, axe_source, "phone")
    driver.save_screenshot(os.path.join(shots, "explorer-phone.png"))
    check("phone screenshot saved", os.path.getsize(os.path.join(shots, "explorer-phone.png")) > 10000)


if __name__ == "__main__":
    main()
